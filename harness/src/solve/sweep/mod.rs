//! The steady-state step: per frequency f (ω = 2πf)
//!
//!   (K + K_c(k*) + iω(D + D_c(d*)) − ω²M) û = f̂,   u(t) = Re(û e^{iωt}),
//!
//! with the contact springs of every closed point: k_N along n (from the static step) and,
//! per tangential direction, κ = k* + iω d* (per area, × tributary area) from the C API for
//! the point's amplitude |δ̂_t|. Open points stay open (no springs). Two modes:
//! - [`fast`]: one factorization per frequency, contact iteration on the condensed system;
//! - [`thesis`]: the multi-pass UEXTERNALDB scheme through the library's store.
//!
//! [`Setup`] holds what both share: the symbolic analysis (once per sweep), the frequency-
//! independent real part, the per-point unit blocks, and the scratch matrix S(ω).

pub mod anderson;
pub mod bracket;
pub mod driver;
pub mod fast;
mod fast_coupled;
mod fast_results;
mod fast_unknowns;
mod fast_update;
mod fast_workspace;
pub mod harmonic;
pub mod harmonic_check;
pub mod harmonic_fe;
pub mod harmonic_fe_point3d;
pub mod harmonic_loops;
pub mod krylov;
mod modal_residual;
pub mod modal_route;
pub mod posteriori;
pub mod receptance;
mod regular;
pub mod scale;
pub mod thesis;

use std::collections::BTreeMap;
use std::sync::OnceLock;
use std::time::Instant;

use nalgebra::{Complex, Matrix3, Vector3};
use serde::Serialize;
use thiserror::Error;

use crate::capi::CapiError;
use crate::fe::csc::Csc;
use crate::fe::pair_blocks::to_global;
use crate::model::Problem;
use crate::settings::{Effects, IterationSpec};
use crate::solve::contact::normal_stiffness;
use crate::solve::static_step::StaticState;
use crate::solve::umfpack::{Symbolic, UmfpackError};
use crate::util::number::sig;

pub type C64 = Complex<f64>;

pub use regular::{PIVOT_RATIO_SCREEN, SINGULAR_RCOND, SINGULAR_RCOND_ESTIMATE};

/// Absolute amplitude tolerance relative to the problem's own amplitude scale (never to
/// the user's start estimate `initial_amplitude`): both modes accept
/// |a − a*| ≤ rtol·max(a, a*) + atol with atol = ATOL_REL × scale. Fast mode's scale is
/// the largest amplitude of the frequency's current iterate (a and a* of every contact
/// direction), thesis mode's the stuck linear response's ([`scale::stuck_scale`], one
/// number for the store). Without atol a direction that is never excited (a* = 0) could
/// never converge in relative terms. A scale tied to `initial_amplitude` (1e-6 of it)
/// accepted any amplitude below it: the block of scenes/block-stick.toml with
/// k_T0 = 1e12 N/mm³ converged at 1.40e-11 mm instead of 5.49e-13 mm.
pub const ATOL_REL: f64 = 1e-6;

/// Errors of a sweep.
#[derive(Debug, Error)]
pub enum SweepError {
    #[error(transparent)]
    Capi(#[from] CapiError),
    #[error("at {} Hz: {source}", sig(*freq))]
    Umfpack {
        freq: f64,
        #[source]
        source: UmfpackError,
    },
    #[error("at {} Hz: the response is not finite", sig(*freq))]
    NotFinite { freq: f64 },
    #[error("at {} Hz: the condensed contact system is singular", sig(*freq))]
    Condensed { freq: f64 },
    #[error("at {} Hz: harmonic balance: {source}", sig(*freq))]
    Balance {
        freq: f64,
        #[source]
        source: crate::mhb::MhbError,
    },
    #[error(transparent)]
    Modal(#[from] modal_route::ModalRouteError),
    #[error("at {} Hz: modal route: {source}", sig(*freq))]
    ModalField {
        freq: f64,
        #[source]
        source: crate::solve::cholmod::CholmodError,
    },
    #[error("a modal basis is built for the modal route only ([sweep] method = \"modal\")")]
    ModalBasisNeedsModalRoute,
    #[error("[sweep] method = \"modal\" is available in modes fast and harmonic_balance (the thesis scheme's store iterates over UINTER's own solves); set [iteration] mode = \"fast\" or method = \"direct\"")]
    ModalNeedsFastMode,
    #[error("modal damping damps the stuck modes of the modal route ([sweep] method = \"modal\", a deck's steady state without DIRECT); this sweep is direct")]
    ModalDampingNeedsModalRoute,
    #[error("the harmonic-balance mode does not include cubic springs (their linearization is first order); use mode fast or thesis")]
    CubicInHarmonicBalance,
    #[error("interfaces with `area_samples` are solved in mode fast only (the thesis store and the harmonic balance evaluate each point at its node)")]
    AreaSamplesNeedFastMode,
    #[error("[effects] normal_load_variation is computed by the harmonic balance only, coupled_slip by the harmonic balance or, first order, by mode fast: set [iteration] mode = \"harmonic_balance\" (or \"fast\" for coupled_slip alone)")]
    ContactEffectsNeedHarmonicBalance,
    #[error("[effects] normal_load_variation and coupled_slip use the library's three-direction point: interface {interface:?} needs {needs}")]
    ContactEffectsLaw {
        interface: String,
        needs: &'static str,
    },
}

/// What the sweep is asked to do (from the scene's iteration table and effects).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    pub iteration: IterationSpec,
    pub effects: Effects,
    /// Per-point results (points.csv, stick/slip map).
    pub point_results: bool,
    /// Fast mode: condense onto the contact unknowns up to this many (2 per closed
    /// point), else FGMRES with the factorization as preconditioner.
    pub condense_max: usize,
    /// Run the frequencies in descending order (results are still stored ascending).
    pub descending: bool,
    /// Fast mode: keep each converged frequency's displacement field
    /// ([`SweepResult::fields`]).
    pub keep_fields: bool,
    /// Fast mode: the linear part by a factorization per frequency or by the stuck
    /// structure's modes ([`modal_route`]).
    pub linear: modal_route::LinearRoute,
}

impl Options {
    pub fn from_scene(iteration: IterationSpec, effects: Effects) -> Self {
        Options {
            iteration,
            effects,
            point_results: effects.point_energy_output || effects.stick_slip_map,
            condense_max: fast::CONDENSE_MAX,
            descending: false,
            keep_fields: false,
            linear: modal_route::LinearRoute::Direct,
        }
    }
}

/// One contact point at one frequency.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct PointFreq {
    /// Computed tangential amplitudes |δ̂_t₁|, |δ̂_t₂| (length).
    pub amplitude: [f64; 2],
    /// k* per area (force/length³).
    pub k_star: [f64; 2],
    /// d* per area (force·time/length³); 0 without contact damping.
    pub d_star: [f64; 2],
    /// Energy dissipated per cycle by the point, both directions (force·length).
    pub energy: f64,
    /// A/δ* per direction.
    pub ratio: [f64; 2],
    /// JOINTLIN_REGIME_* per direction.
    pub regime: [i32; 2],
}

/// One pass of the thesis scheme (Fig. 4.33) or, in fast mode, the whole sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassRecord {
    pub pass: i32,
    /// "first", "rerun", "final" (thesis) or "fast".
    pub kind: String,
    /// Frequencies (Hz) run in the pass.
    pub frequencies: Vec<f64>,
    pub converged: usize,
}

/// Results of a sweep.
#[derive(Debug, Clone, Default)]
pub struct SweepResult {
    pub freqs: Vec<f64>,
    /// `[frequency][output]` complex displacement amplitude (first harmonic).
    pub outputs: Vec<Vec<C64>>,
    /// Harmonic balance only: `[frequency][output][h]` complex amplitude of harmonic
    /// h = 0..H (h = 0: the mean deviation from the static state, real).
    pub harmonics: Vec<Vec<Vec<C64>>>,
    /// Power dissipated in the joints (force·length/time): Σ energy per cycle × f.
    pub power: Vec<f64>,
    /// `[frequency][contact point]`; empty unless per-point results were asked for.
    pub points: Vec<Vec<PointFreq>>,
    /// Fast: contact iterations per frequency; thesis: passes that ran the frequency;
    /// harmonic balance: Newton iterations.
    pub iterations: Vec<usize>,
    pub converged: Vec<bool>,
    /// Per frequency: the dynamic stiffness was singular ([`SINGULAR_RCOND`]); outputs
    /// and power there are zeros standing for "no response computed" (the reports write
    /// empty fields and status `singular`), and the frequency counts as not converged.
    pub singular: Vec<bool>,
    /// Per frequency: why it failed (a library call or a solve returned an error there);
    /// outputs and power are zeros standing for "no response computed" (status `failed`,
    /// empty fields), and the frequency counts as not converged. Empty: none failed.
    pub failed: Vec<Option<String>>,
    /// Per frequency (fast and thesis modes): the independent check of the converged
    /// solution ([`posteriori`]; `None` where not converged or not checked); a frequency
    /// that fails it is not converged.
    pub checks: Vec<Option<posteriori::Verdict>>,
    /// Fast mode with [`Options::keep_fields`]: (frequency, the complex displacement
    /// amplitude of every free DOF in length) of each converged frequency, in run order.
    /// Else empty.
    pub fields: Vec<(f64, Vec<C64>)>,
    pub passes: Vec<PassRecord>,
    pub factorizations: usize,
    /// Fast mode with FGMRES: preconditioner applications (solves) in all.
    pub gmres_solves: usize,
    /// Amplitudes capped at δ* because macroslip is off.
    pub macroslip_caps: usize,
    /// Seconds per named cost.
    pub timings: BTreeMap<String, f64>,
    /// The modal route's basis, when the sweep used it.
    pub modal: Option<modal_route::ModalSummary>,
    /// The harmonic balance's contact loops at its largest converged response.
    pub loops: Option<harmonic_loops::BalanceLoops>,
}

impl SweepResult {
    /// Reverses every per-frequency list (not the pass records, which keep run order).
    fn reverse_frequencies(&mut self) {
        self.freqs.reverse();
        self.outputs.reverse();
        self.harmonics.reverse();
        self.power.reverse();
        self.points.reverse();
        self.iterations.reverse();
        self.converged.reverse();
        self.singular.reverse();
        self.failed.reverse();
        self.checks.reverse();
    }

    /// Adds `seconds` to the cost `key`; nothing for 0 s (nothing was done).
    pub(crate) fn add_seconds(&mut self, key: &str, seconds: f64) {
        if seconds > 0.0 {
            *self.timings.entry(key.to_string()).or_default() += seconds;
        }
    }

    pub(crate) fn time(&mut self, key: &str, since: Instant) {
        *self.timings.entry(key.to_string()).or_default() += since.elapsed().as_secs_f64();
    }
}

/// Shared per-sweep data.
pub struct Setup<'a> {
    pub problem: &'a Problem,
    /// The symbolic analysis of S(ω)'s pattern, made at the first factorization
    /// ([`Setup::symbolic`]; the modal route never needs it).
    symbolic: OnceLock<Symbolic>,
    /// K + normal springs (+ stick springs k_T0 when microslip is off), on the pattern.
    pub base: Vec<f64>,
    /// Contact indices with varying tangential springs (closed, microslip on).
    pub active: Vec<usize>,
    /// Per active point: global unit blocks t₁t₁ᵀA and t₂t₂ᵀA.
    pub unit_blocks: Vec<[Matrix3<f64>; 2]>,
    /// Base pressure per contact point.
    pub pressure: Vec<f64>,
    /// Normal spring per area of each contact point in `base` (force/length³; 0 open).
    pub normal_k: Vec<f64>,
    /// How the harmonic balance models its points (`[effects]` normal_load_variation,
    /// coupled_slip).
    pub point_model: harmonic_fe_point3d::PointModel,
    /// Per contact point: (area fraction, normal stress) of its friction samples
    /// (`StaticState::friction_samples`; empty: node-based).
    pub friction_samples: Vec<Vec<(f64, f64)>>,
    pub damping: Option<&'a Csc<f64>>,
    /// Structural damping ([`Problem::structural`]), `None` when `material_damping` is off.
    pub structural: Option<&'a Csc<f64>>,
    /// S(ω) scratch.
    pub s: Csc<C64>,
}

impl<'a> Setup<'a> {
    /// Symbolic analysis and the frequency-independent part.
    pub fn new(
        problem: &'a Problem,
        stat: &StaticState,
        effects: &Effects,
    ) -> Result<Self, UmfpackError> {
        let mut base = problem.sys.k.values.clone();
        let mut active = Vec::new();
        let mut unit_blocks = Vec::new();
        let mut normal_k = vec![0.0; problem.contacts.len()];
        for (i, c) in problem.contacts.iter().enumerate() {
            if !stat.closed[i] {
                continue;
            }
            let itf = &problem.interfaces[c.interface];
            let kn = if effects.normal_contact_nonlinearity {
                stat.normal_stiffness[i]
            } else {
                normal_stiffness(itf)
            };
            normal_k[i] = kn;
            let kt = if effects.tangential_microslip {
                0.0
            } else {
                itf.contact.k_t0_per_area
            };
            let local = Matrix3::from_diagonal(&Vector3::new(kn, kt, kt)) * c.area;
            problem
                .sys
                .pairs
                .add(&mut base, c.pair, &to_global(&c.frame, &local));
            if effects.tangential_microslip {
                active.push(i);
                let unit = |d: usize| {
                    let t = c.frame.column(d);
                    t * t.transpose() * c.area
                };
                unit_blocks.push([unit(1), unit(2)]);
            }
        }
        let (damping, structural) = if effects.material_damping {
            (problem.damping.as_ref(), problem.structural.as_ref())
        } else {
            (None, None)
        };
        Ok(Setup {
            problem,
            symbolic: OnceLock::new(),
            base,
            active,
            friction_samples: stat.friction_samples.clone(),
            unit_blocks,
            pressure: stat.pressure.clone(),
            normal_k,
            point_model: harmonic_fe_point3d::PointModel::from_effects(effects),
            damping,
            structural,
            s: problem.sys.complex_zeros(),
        })
    }

    /// The symbolic analysis of S(ω)'s pattern (UMFPACK's symmetric strategy, the
    /// least-fill ordering: [`Symbolic::symmetric_best`]), made once per sweep.
    pub fn symbolic(&self) -> Result<&Symbolic, UmfpackError> {
        if let Some(s) = self.symbolic.get() {
            return Ok(s);
        }
        let mut s = Symbolic::symmetric_best(self.problem.sys.pattern.clone())?;
        // Refinement would triple the cost of the m receptance solves; the amplitude
        // tolerance (≥ 1e-6 relative) is far above the unrefined solve's error.
        s.set_refinement_steps(0);
        Ok(self.symbolic.get_or_init(|| s))
    }

    /// Writes S(ω) with tangential κ (per area) for every active point and k* for every
    /// cubic spring (`Problem::cubic_springs`) into `self.s`.
    pub fn fill(&mut self, omega: f64, kappa: &[[C64; 2]], spring_k: &[f64]) {
        let w2 = omega * omega;
        let m = &self.problem.sys.m.values;
        for ((s, k), mv) in self.s.values.iter_mut().zip(&self.base).zip(m) {
            *s = C64::new(k - w2 * mv, 0.0);
        }
        if let Some(d) = self.damping {
            for (s, dv) in self.s.values.iter_mut().zip(&d.values) {
                s.im += omega * dv;
            }
        }
        if let Some(h) = self.structural.filter(|_| omega > 0.0) {
            for (s, hv) in self.s.values.iter_mut().zip(&h.values) {
                s.im += hv;
            }
        }
        for (j, &i) in self.active.iter().enumerate() {
            let [b1, b2] = &self.unit_blocks[j];
            let blk: Matrix3<C64> = b1.map(|v| kappa[j][0] * v) + b2.map(|v| kappa[j][1] * v);
            self.problem
                .sys
                .pairs
                .add(&mut self.s.values, self.problem.contacts[i].pair, &blk);
        }
        for (sp, &k) in self.problem.cubic_springs.iter().zip(spring_k) {
            // K holds k·d dᵀ already; k* replaces it.
            let blk = sp.block.map(|v| C64::new((k - sp.stiffness) * v, 0.0));
            self.problem
                .sys
                .pairs
                .add(&mut self.s.values, sp.pair, &blk);
        }
    }

    /// Tangential relative displacement amplitudes (complex) of active point j.
    pub fn tangential(&self, j: usize, u: &[C64]) -> [C64; 2] {
        let c = &self.problem.contacts[self.active[j]];
        [c.relative(1, u), c.relative(2, u)]
    }
}

/// Runs the scene's mode over `freqs` (ascending) in the order `opts.descending` asks
/// for; the result lists the frequencies ascending.
pub fn run(
    problem: &Problem,
    stat: &StaticState,
    freqs: &[f64],
    opts: &Options,
    progress: &dyn Fn(&str, usize, usize),
) -> Result<SweepResult, SweepError> {
    run_cached(problem, stat, freqs, opts, progress, &mut None)
}

/// [`run`] keeping the modal route's basis in `cache` for the next sweep of the same
/// `problem` and `stat` (a study that sweeps it many times, e.g. with other loads).
pub fn run_cached(
    problem: &Problem,
    stat: &StaticState,
    freqs: &[f64],
    opts: &Options,
    progress: &dyn Fn(&str, usize, usize),
    cache: &mut Option<modal_route::ModalRoute>,
) -> Result<SweepResult, SweepError> {
    let t = Instant::now();
    let mut setup =
        Setup::new(problem, stat, &opts.effects).map_err(|source| SweepError::Umfpack {
            freq: freqs.first().copied().unwrap_or(0.0),
            source,
        })?;
    let analysis = t.elapsed().as_secs_f64();
    let order: Vec<f64> = if opts.descending {
        freqs.iter().rev().copied().collect()
    } else {
        freqs.to_vec()
    };
    if opts.iteration.mode != crate::settings::Mode::Fast && problem.has_area_samples() {
        return Err(SweepError::AreaSamplesNeedFastMode);
    }
    harmonic_fe_point3d::check_effects(problem, &opts.effects, opts.iteration.mode)?;
    if opts.linear != modal_route::LinearRoute::Direct
        && opts.iteration.mode == crate::settings::Mode::Thesis
    {
        return Err(SweepError::ModalNeedsFastMode);
    }
    if opts.linear == modal_route::LinearRoute::Direct && !problem.modal_damping.is_empty() {
        return Err(SweepError::ModalDampingNeedsModalRoute);
    }
    let zero_load = scale::is_zero_load(&setup);
    let mut r = match opts.iteration.mode {
        _ if zero_load => scale::zero_load(&mut setup, &order, opts)?,
        crate::settings::Mode::Fast => fast::sweep(&mut setup, &order, opts, progress, cache)?,
        crate::settings::Mode::Thesis => thesis::sweep(&mut setup, stat, &order, opts, progress)?,
        crate::settings::Mode::HarmonicBalance if !problem.cubic_springs.is_empty() => {
            return Err(SweepError::CubicInHarmonicBalance)
        }
        crate::settings::Mode::HarmonicBalance => {
            harmonic::sweep(&mut setup, &order, opts, progress)?
        }
    };
    if opts.descending {
        r.reverse_frequencies();
    }
    *r.timings.entry("symbolic analysis".into()).or_default() += analysis;
    Ok(r)
}

/// The model of scenes/three-beams-coarse.toml after its static step, for unit tests.
#[cfg(test)]
pub(crate) fn three_beams_coarse() -> (crate::input::scene::Scene, Problem, StaticState) {
    let path = format!(
        "{}/../scenes/three-beams-coarse.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let scene = crate::input::scene::Scene::load(std::path::Path::new(&path)).unwrap();
    let p = crate::model::build(&scene).unwrap();
    let stat = crate::solve::static_step::solve(&p, true).unwrap();
    (scene, p, stat)
}
