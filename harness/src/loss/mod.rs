//! Joint power loss against the amplitude of an output at resonance (thesis §5.4–5.5,
//! Fig. 5.41–5.45): the form of the ultrasonic knife's measurements, where a converter
//! drives the structure at its resonance with the end-face amplitude set.
//!
//! Per screw torque: build the model with that torque, static preload step; find the
//! resonance of the named output (the scene's sweep, then a golden-section search on
//! the amplitude around its peak) at the excitation that gives the largest amplitude of
//! the study; then, at that frequency, scale the excitation until the output's
//! amplitude is each target and record the joint power loss P = f·ΣE_cycle / share
//! (E_cycle per point from the library's linearization, `share` the modelled fraction
//! of the structure: 0.5 for a half model).

pub mod calibrate;
pub mod effects;
pub mod level;
pub mod mesh;
pub mod plot;
pub mod report;

use thiserror::Error;

use crate::model::Job;
use crate::model::Problem;
pub use crate::settings::{LossStudySpec, ReferencePoint};
use crate::solve::prepared::{PrepareError, Prepared};
use crate::solve::static_step::StaticState;
use crate::solve::sweep::modal_route::ModalRoute;
use crate::solve::sweep::{self, Options, PointFreq, SweepError, C64};

/// Errors of a loss study.
#[derive(Debug, Error)]
pub enum LossError {
    #[error("the scene has no [loss_study] table")]
    NoStudy,
    #[error("loss_study: {0}")]
    Spec(String),
    #[error(transparent)]
    Prepare(#[from] PrepareError),
    #[error("steady-state solve: {0}")]
    Sweep(#[from] SweepError),
    #[error("{what} did not converge at {} Hz", crate::util::number::sig(*freq))]
    NotConverged { what: &'static str, freq: f64 },
    #[error("the calibration did not reach its reference points in {0} steps")]
    Calibration(usize),
}

/// Golden-section steps of the resonance search (interval × 0.618 each: 16 steps take a
/// sweep step of 250 Hz below 0.1 Hz, far inside the joint-damped half-power width).
const GOLDEN_STEPS: usize = 16;
pub use level::LEVEL_TOL;

/// One solved operating point.
#[derive(Debug, Clone)]
pub struct Sample {
    /// Frequency (1/time).
    pub freq: f64,
    /// Excitation scale relative to the scene's excitation.
    pub scale: f64,
    /// Output amplitude (length).
    pub amplitude: f64,
    /// Power lost in the joints of the whole structure (scene units, divided by the
    /// model share).
    pub power: f64,
    /// Per contact point (empty entries for open points).
    pub points: Vec<PointFreq>,
}

impl Sample {
    /// Largest A/δ* of any point and direction.
    pub fn max_ratio(&self) -> f64 {
        self.points.iter().flat_map(|p| p.ratio).fold(0.0, f64::max)
    }
}

/// A model with its preload state, ready for steady-state solves.
pub struct Operating {
    pub problem: Problem,
    pub stat: StaticState,
    base_excitation: Vec<C64>,
    output: usize,
    share: f64,
    opts: Options,
    /// The modal route's basis, kept from one sweep to the next.
    modal: Option<ModalRoute>,
    /// Solves run so far (each one factorization).
    pub solves: usize,
}

impl Operating {
    /// Builds the scene's model and runs its static step; `output` names the output
    /// whose amplitude is studied, `share` the modelled fraction of the structure.
    pub fn new(job: &Job, output: &str, share: f64) -> Result<Self, LossError> {
        let Prepared { problem, stat, .. } = Prepared::new(job, &|_| {})?;
        let output = problem
            .outputs
            .iter()
            .position(|o| o.name == output)
            .ok_or_else(|| LossError::Spec(format!("no output named `{output}`")))?;
        let mut opts = Options::from_scene(job.settings.iteration, job.settings.effects);
        opts.point_results = true;
        opts.linear = crate::run::linear_route(&job.settings, &job.settings.frequencies());
        Ok(Operating {
            modal: None,
            base_excitation: problem.excitation.clone(),
            problem,
            stat,
            output,
            share,
            opts,
            solves: 0,
        })
    }

    /// Steady state at `freqs` with the excitation scaled by `scale`.
    fn sweep(&mut self, freqs: &[f64], scale: f64) -> Result<sweep::SweepResult, LossError> {
        for (e, b) in self
            .problem
            .excitation
            .iter_mut()
            .zip(&self.base_excitation)
        {
            *e = b * scale;
        }
        self.solves += freqs.len();
        Ok(sweep::run_cached(
            &self.problem,
            &self.stat,
            freqs,
            &self.opts,
            &|_, _, _| {},
            &mut self.modal,
        )?)
    }

    /// One frequency, one excitation scale.
    pub fn solve(&mut self, freq: f64, scale: f64) -> Result<Sample, LossError> {
        let r = self.sweep(&[freq], scale)?;
        if !r.converged[0] {
            return Err(LossError::NotConverged {
                what: "contact iteration",
                freq,
            });
        }
        Ok(Sample {
            freq,
            scale,
            amplitude: r.outputs[0][self.output].norm(),
            power: r.power[0] / self.share,
            points: r.points.into_iter().next().unwrap_or_default(),
        })
    }

    /// Output amplitude over `freqs` at `scale`.
    pub fn response(&mut self, freqs: &[f64], scale: f64) -> Result<Vec<f64>, LossError> {
        let r = self.sweep(freqs, scale)?;
        Ok(r.outputs.iter().map(|o| o[self.output].norm()).collect())
    }

    /// Frequency of the largest output amplitude at `scale` between `a` and `b`
    /// (one peak there): golden-section search.
    pub fn resonance(&mut self, a: f64, b: f64, scale: f64) -> Result<f64, LossError> {
        let (mut a, mut b) = (a, b);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let mut c = b - g * (b - a);
        let mut d = a + g * (b - a);
        let mut fc = self.solve(c, scale)?.amplitude;
        let mut fd = self.solve(d, scale)?.amplitude;
        for _ in 0..GOLDEN_STEPS {
            if fc > fd {
                b = d;
                d = c;
                fd = fc;
                c = b - g * (b - a);
                fc = self.solve(c, scale)?.amplitude;
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + g * (b - a);
                fd = self.solve(d, scale)?.amplitude;
            }
        }
        Ok(0.5 * (a + b))
    }

    /// The excitation scale at which the output amplitude at `freq` is `target`
    /// (within [`LEVEL_TOL`], or within the scene's iteration tolerance where the
    /// amplitude jumps across the target), from the estimate `scale`: [`level::search`].
    pub fn level(&mut self, freq: f64, target: f64, scale: f64) -> Result<Sample, LossError> {
        let accept = self.opts.iteration.tolerance;
        level::search(freq, target, scale, accept, &mut |s| self.solve(freq, s))
    }
}

/// One curve point: torque, target amplitude and the operating point that reaches it.
#[derive(Debug, Clone)]
pub struct CurvePoint {
    pub torque: f64,
    pub sample: Sample,
}

/// The job with the torque of screw `screw` set to `torque` (force·length).
pub fn with_torque(job: &Job, screw: &str, torque: f64) -> Result<Job, LossError> {
    job.with_screw_torque(screw, torque)
        .ok_or_else(|| LossError::Spec(format!("no screw named `{screw}`")))
}

/// The grid's peak of the output at the scene's excitation: its index and amplitude
/// (the bracket of the resonance and a linear estimate of the excitation scale).
fn grid_peak(op: &mut Operating, grid: &[f64]) -> Result<(usize, f64), LossError> {
    let amp = op.response(grid, 1.0)?;
    let k = (0..amp.len())
        .max_by(|&a, &b| amp[a].total_cmp(&amp[b]))
        .ok_or_else(|| LossError::Spec("the sweep has no frequencies".into()))?;
    if amp[k] <= 0.0 || !amp[k].is_finite() {
        return Err(LossError::Spec("the output does not move".into()));
    }
    Ok((k, amp[k]))
}

/// The resonance at `scale` around the grid's peak `k`: golden section between its
/// neighbours (the grid point itself on grids of fewer than 3 points).
fn resonance_near(
    op: &mut Operating,
    grid: &[f64],
    k: usize,
    scale: f64,
) -> Result<f64, LossError> {
    if grid.len() < 3 {
        return Ok(grid[k]);
    }
    let (a, b) = (grid[k.saturating_sub(1)], grid[(k + 1).min(grid.len() - 1)]);
    op.resonance(a, b, scale)
}

/// The largest of `amplitudes`, all of which must be > 0 (and at least one given).
fn check_amplitudes(amplitudes: &[f64]) -> Result<f64, LossError> {
    let top = amplitudes.iter().copied().fold(0.0, f64::max);
    if top <= 0.0 || !amplitudes.iter().all(|&a| a > 0.0) {
        return Err(LossError::Spec("amplitudes must be > 0".into()));
    }
    Ok(top)
}

/// The power-loss curve of one model: the resonance (the grid's peak at the scene's
/// excitation, refined by golden section at the excitation of the largest amplitude;
/// the grid must hold one peak of the output there), then each
/// target amplitude at that frequency (largest first, each level starting from the
/// previous scale). Returns the samples in the order of `amplitudes`.
pub fn curve(
    op: &mut Operating,
    grid: &[f64],
    amplitudes: &[f64],
) -> Result<Vec<Sample>, LossError> {
    let top = check_amplitudes(amplitudes)?;
    let (k, peak) = grid_peak(op, grid)?;
    let mut scale = top / peak;
    let f = resonance_near(op, grid, k, scale)?;
    let mut order: Vec<usize> = (0..amplitudes.len()).collect();
    order.sort_by(|&a, &b| amplitudes[b].total_cmp(&amplitudes[a]));
    let mut out: Vec<Option<Sample>> = vec![None; amplitudes.len()];
    for i in order {
        let s = op.level(f, amplitudes[i], scale)?;
        scale = s.scale * 0.9;
        out[i] = Some(s);
    }
    Ok(out
        .into_iter()
        .map(|s| s.expect("every level solved"))
        .collect())
}

/// Each target amplitude at its own resonance (the grid's peak refined by golden
/// section at that amplitude's excitation), one grid sweep for all: what [`curve`] gives
/// for each amplitude alone, without repeating the static step and the sweep.
pub fn each_at_resonance(
    op: &mut Operating,
    grid: &[f64],
    amplitudes: &[f64],
) -> Result<Vec<Sample>, LossError> {
    check_amplitudes(amplitudes)?;
    let (k, peak) = grid_peak(op, grid)?;
    amplitudes
        .iter()
        .map(|&a| {
            let f = resonance_near(op, grid, k, a / peak)?;
            op.level(f, a, a / peak)
        })
        .collect()
}

/// The study of a scene: one curve per torque.
pub struct StudyResult {
    pub curves: Vec<(f64, Vec<Sample>)>,
    /// Total steady-state solves.
    pub solves: usize,
    /// The model at the scene's own torque and its sample at the largest amplitude (for
    /// the contact maps); `None` if the scene's torque is not among the study's.
    pub maps: Option<(Operating, Sample)>,
}

/// Runs the `[loss_study]` of a scene (or a [`Job`]). `progress(message)` reports each
/// torque.
pub fn run_study(job: impl Into<Job>, progress: &dyn Fn(&str)) -> Result<StudyResult, LossError> {
    let job: &Job = &job.into();
    let st = job.settings.loss_study.as_ref().ok_or(LossError::NoStudy)?;
    let grid = job.settings.frequencies();
    let own = job.screw_torque(&st.screw);
    let mut curves = Vec::new();
    let mut solves = 0;
    let mut maps = None;
    for &t in &st.torques {
        progress(&format!("torque {t}"));
        let sc = with_torque(job, &st.screw, t)?;
        let mut op = Operating::new(&sc, &st.output, st.model_share)?;
        let samples = curve(&mut op, &grid, &st.amplitudes)?;
        solves += op.solves;
        if Some(t) == own {
            let top = (0..samples.len())
                .max_by(|&a, &b| samples[a].amplitude.total_cmp(&samples[b].amplitude))
                .expect("at least one amplitude");
            maps = Some((op, samples[top].clone()));
        }
        curves.push((t, samples));
    }
    Ok(StudyResult {
        curves,
        solves,
        maps,
    })
}

/// The sample of one model at one torque and amplitude, at resonance (power in scene
/// units for the whole structure), with the model.
pub fn power_at(
    job: impl Into<Job>,
    torque: f64,
    amplitude: f64,
) -> Result<(Sample, Operating), LossError> {
    let (mut s, op) = powers_at(job, torque, &[amplitude])?;
    Ok((s.pop().expect("one amplitude"), op))
}

/// [`power_at`] for several amplitudes, each at its own resonance, on one model.
pub fn powers_at(
    job: impl Into<Job>,
    torque: f64,
    amplitudes: &[f64],
) -> Result<(Vec<Sample>, Operating), LossError> {
    let job: &Job = &job.into();
    let st = job.settings.loss_study.as_ref().ok_or(LossError::NoStudy)?;
    let sc = with_torque(job, &st.screw, torque)?;
    let mut op = Operating::new(&sc, &st.output, st.model_share)?;
    let s = each_at_resonance(&mut op, &job.settings.frequencies(), amplitudes)?;
    Ok((s, op))
}
