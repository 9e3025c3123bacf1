//! One study from scene to results: build the problem, the static preload step, the
//! steady-state sweep in the scene's mode and, when the FRF plot asks for it, the
//! reference sweep without contact damping. Records which effects are active and what
//! each step cost.

use std::time::Instant;

use serde::Serialize;
use thiserror::Error;

use crate::capi::{self, CallCounts};
use crate::model::{Job, Problem};
use crate::settings::{
    Direction, Effects, FieldOutputSpec, Interval, Mode, RunSettings, SweepMethod,
};
use crate::solve::modal::{lowest_modes, ModalOptions};
use crate::solve::modal_band::modes_below;
use crate::solve::modal_stuck::stuck_stiffness;
use crate::solve::prepared::{PrepareError, Prepared};
use crate::solve::static_step::StaticState;
use crate::solve::sweep::modal_route::{
    LinearRoute, ModalRoute, ModeChoice, BAND_FACTOR, MAX_MODES, MIN_MODES,
};
use crate::solve::sweep::{self, Options, SweepError, SweepResult};

/// Errors of a run.
#[derive(Debug, Error)]
pub enum RunError {
    #[error(transparent)]
    Prepare(#[from] PrepareError),
    #[error("steady-state step: {0}")]
    Sweep(#[from] SweepError),
    #[error("steady-state step: the stuck eigenfrequencies that divide the range: {0}")]
    Intervals(String),
}

/// What to run besides the scene's own sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Extras {
    /// Also sweep without contact damping (fast mode) for the FRF comparison plot; only
    /// done when the scene has contact damping on.
    pub reference_without_damping: bool,
    /// Override of the fast mode's condensation limit (contact unknowns).
    pub condense_max: Option<usize>,
}

/// An effect, whether it is on, and what it cost.
#[derive(Debug, Clone, Serialize)]
pub struct EffectLog {
    pub name: &'static str,
    pub active: bool,
    /// Seconds spent in the work this effect switches on (0 when off).
    pub seconds: f64,
    /// What that work was.
    pub work: String,
}

/// Everything a run produced.
#[derive(Debug)]
pub struct RunResult {
    pub problem: Problem,
    pub stat: StaticState,
    /// The scene's sweep (`[sweep] direction` up or down; up for `up_down`).
    pub main: SweepResult,
    /// The descending sweep of `direction = "up_down"`.
    pub down: Option<SweepResult>,
    pub reference: Option<SweepResult>,
    /// The `[field_output]` frequencies solved once more in fast mode with their
    /// displacement fields ([`SweepResult::fields`]) and point results.
    pub fields: Option<SweepResult>,
    pub effects: Vec<EffectLog>,
    /// C-API calls made by the run (this thread).
    pub calls: CallCounts,
    /// Seconds: build, static step, main sweep (with the down sweep of `up_down`),
    /// reference sweep.
    pub seconds: [f64; 4],
}

fn sum(r: &SweepResult, keys: &[&str]) -> f64 {
    keys.iter()
        .map(|k| r.timings.get(*k).copied().unwrap_or(0.0))
        .sum()
}

/// The run's route for the linear part of each frequency (`[sweep] method`): modal
/// with `modes` modes, or by default every mode below [`BAND_FACTOR`] × the highest
/// frequency the sweep solves at: the highest of `freqs` (1/time) times the harmonic
/// balance's H.
pub fn linear_route(settings: &RunSettings, freqs: &[f64]) -> LinearRoute {
    let sweep = &settings.sweep;
    let it = &settings.iteration;
    let top_harmonic = match it.mode {
        Mode::HarmonicBalance => it.harmonics.unwrap_or(1).max(1) as f64,
        _ => 1.0,
    };
    match sweep.method {
        SweepMethod::Direct => LinearRoute::Direct,
        SweepMethod::Modal => LinearRoute::Modal {
            modes: match sweep.modes {
                Some(n) => ModeChoice::Count(n),
                None => ModeChoice::Below(
                    BAND_FACTOR * top_harmonic * freqs.iter().fold(0.0, |a, &b| f64::max(a, b)),
                ),
            },
            residual: sweep.residual.unwrap_or(true),
        },
    }
}

/// The frequencies of the run's sweep: with `interval = "eigenfrequency"` divided at
/// the stuck structure's eigenfrequencies (as many modes as the modal route keeps, or
/// every mode below [`BAND_FACTOR`] × f_max), else the range's own.
pub fn sweep_frequencies(
    settings: &RunSettings,
    problem: &Problem,
    stat: &StaticState,
) -> Result<Vec<f64>, RunError> {
    let sw = &settings.sweep;
    if sw.interval == Interval::Range {
        return Ok(sw.frequencies());
    }
    let err = |e: String| RunError::Intervals(e);
    let k = stuck_stiffness(problem, stat, &settings.effects).map_err(err)?;
    let opts = ModalOptions::default();
    let modes = match sw.modes {
        Some(n) => lowest_modes(
            &k,
            &problem.sys.m,
            &ModalOptions {
                n_modes: n.clamp(1, k.n()),
                ..opts
            },
        ),
        None => {
            let top = sw.frequencies().into_iter().fold(0.0, f64::max);
            modes_below(
                &k,
                &problem.sys.m,
                BAND_FACTOR * top,
                MIN_MODES,
                MAX_MODES,
                &opts,
            )
            .map(|b| b.modes)
        }
    }
    .map_err(|e| err(e.to_string()))?;
    Ok(sw.frequencies_between(&modes.frequencies_hz()))
}

/// The sweep's frequencies and, when the fast modal route's eigenfrequencies divide the
/// range, its basis (built first, so the modes are computed once) with its cost in
/// seconds; `opts.linear` set for the basis.
fn frequencies_and_basis(
    settings: &RunSettings,
    problem: &Problem,
    stat: &StaticState,
    opts: &mut Options,
) -> Result<(Vec<f64>, Option<ModalRoute>, f64), RunError> {
    if !divides_by_fast_modal_route(settings) {
        return Ok((sweep_frequencies(settings, problem, stat)?, None, 0.0));
    }
    let t = Instant::now();
    let range = settings.frequencies();
    opts.linear = linear_route(settings, &range);
    // The sweep's first frequency, as the sweep will run them.
    let f0 = if opts.descending {
        range[range.len() - 1]
    } else {
        range[0]
    };
    let route = sweep::fast::modal_basis(problem, stat, opts, f0)?;
    let freqs = settings.sweep.frequencies_between(&route.frequencies());
    Ok((freqs, Some(route), t.elapsed().as_secs_f64()))
}

/// The main sweep's options: the settings' iteration and effects, the run's extras.
fn sweep_options(spec: &RunSettings, extras: Extras) -> Options {
    let mut opts = Options::from_scene(spec.iteration, spec.effects);
    if let Some(c) = extras.condense_max {
        opts.condense_max = c;
    }
    opts.descending = spec.sweep.direction == Direction::Down;
    opts
}

/// Whether the run's range is divided at the stuck eigenfrequencies and swept in mode
/// fast by the modal route: then the route's own basis gives the eigenfrequencies.
fn divides_by_fast_modal_route(s: &RunSettings) -> bool {
    s.sweep.interval == Interval::Eigenfrequency
        && s.sweep.method == SweepMethod::Modal
        && s.iteration.mode == Mode::Fast
}

/// Runs an input (a scene, a deck or a [`Job`]). `progress(label, done, total)` is called per frequency of each pass,
/// and with total 0 when the build, the static step and the basis begin.
pub fn run(
    job: impl Into<Job>,
    extras: Extras,
    progress: &dyn Fn(&str, usize, usize),
) -> Result<RunResult, RunError> {
    let calls0 = capi::counts();
    let steps3_0 = capi::point3d_steps();
    let job: Job = job.into();
    let spec = &job.settings;
    let eff: Effects = spec.effects;
    let Prepared {
        problem,
        stat,
        build_seconds: t_build,
        static_seconds: t_static,
    } = Prepared::new(&job, &|step| progress(step, 0, 0))?;
    let mut opts = sweep_options(spec, extras);
    // One modal basis for every sweep of the run (they share the problem).
    let t = Instant::now();
    progress("frequencies and the modal basis", 0, 0);
    let (freqs, mut cache, t_basis) = frequencies_and_basis(spec, &problem, &stat, &mut opts)?;
    opts.linear = linear_route(spec, &freqs);
    let mut main = sweep::run_cached(&problem, &stat, &freqs, &opts, progress, &mut cache)?;
    // A basis built before the sweep (its eigenfrequencies divided the range): its cost.
    main.add_seconds("modal basis (modes, residual)", t_basis);
    let down = if spec.sweep.direction == Direction::UpDown {
        let mut o = opts;
        o.descending = true;
        Some(sweep::run_cached(
            &problem,
            &stat,
            &freqs,
            &o,
            &|l, i, n| progress(&format!("sweep down: {l}"), i, n),
            &mut cache,
        )?)
    } else {
        None
    };
    let t_main = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let reference = if extras.reference_without_damping
        && eff.contact_damping
        && eff.tangential_microslip
        && !problem.contacts.is_empty()
    {
        let mut o = opts;
        o.effects = o.effects.first_order();
        o.effects.contact_damping = false;
        o.point_results = false;
        o.iteration.mode = Mode::Fast;
        Some(sweep::run_cached(
            &problem,
            &stat,
            &freqs,
            &o,
            &|l, i, n| progress(&format!("reference without contact damping: {l}"), i, n),
            &mut cache,
        )?)
    } else {
        None
    };
    let t_ref = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let fields = match &spec.field_output {
        Some(fo) => {
            let at = field_frequencies(fo, &main);
            let mut o = opts;
            o.effects = o.effects.first_order();
            o.iteration.mode = Mode::Fast;
            o.keep_fields = true;
            o.point_results = true;
            o.descending = false;
            Some(sweep::run_cached(
                &problem,
                &stat,
                &at,
                &o,
                &|l, i, n| progress(&format!("field output: {l}"), i, n),
                &mut cache,
            )?)
        }
        None => None,
    };
    let t_fields = t.elapsed().as_secs_f64();
    let c1 = capi::counts();
    let steps3 = capi::point3d_steps() - steps3_0;
    let calls = CallCounts {
        linearize: c1.linearize - calls0.linearize,
        linearize_cubic: c1.linearize_cubic - calls0.linearize_cubic,
        uinter_general: c1.uinter_general - calls0.uinter_general,
        uinter_linear: c1.uinter_linear - calls0.uinter_linear,
        uexternaldb: c1.uexternaldb - calls0.uexternaldb,
        store: c1.store - calls0.store,
    };
    let mut result = RunResult {
        problem,
        stat,
        main,
        down,
        reference,
        fields,
        effects: Vec::new(),
        calls,
        seconds: [t_build, t_static, t_main, t_ref],
    };
    result.effects = effect_logs(&result, eff, steps3, t_fields);
    Ok(result)
}

/// What each effect of `eff` did in the run `r` and what it cost (`steps3`: the
/// three-direction point steps of the run; `t_fields`: seconds of the field pass).
fn effect_logs(r: &RunResult, eff: Effects, steps3: u64, t_fields: f64) -> Vec<EffectLog> {
    let (problem, stat, main, calls) = (&r.problem, &r.stat, &r.main, &r.calls);
    let (down, reference, fields) = (&r.down, &r.reference, &r.fields);
    let [_, t_static, _, t_ref] = r.seconds;
    let contact_iter = sum(
        main,
        &[
            "linearization (C API)",
            "condensed iterations",
            "receptance solves",
            "store (C API)",
        ],
    );
    vec![
        EffectLog {
            name: "normal_contact_nonlinearity",
            active: eff.normal_contact_nonlinearity,
            seconds: if eff.normal_contact_nonlinearity { t_static } else { 0.0 },
            work: format!(
                "static Newton with UINTER LINPER=0: {} iterations, {} calls",
                stat.newton_iterations, calls.uinter_general
            ),
        },
        EffectLog {
            name: "tangential_microslip",
            active: eff.tangential_microslip,
            seconds: if eff.tangential_microslip { contact_iter } else { 0.0 },
            work: format!(
                "k*(A) by {} jointlin_linearize + {} UINTER LINPER=1 calls, receptances and contact iterations",
                calls.linearize, calls.uinter_linear
            ),
        },
        EffectLog {
            name: "macroslip",
            active: eff.macroslip,
            seconds: 0.0,
            work: if eff.macroslip {
                "Coulomb sliding inside the library's loops (no extra work)".into()
            } else {
                format!("amplitudes capped at δ*: {} caps", main.macroslip_caps)
            },
        },
        EffectLog {
            name: "contact_damping",
            active: eff.contact_damping,
            seconds: t_ref,
            work: if reference.is_some() {
                "d* in the dynamic stiffness; reference sweep without it for the FRF plot".into()
            } else {
                "d* in the dynamic stiffness".into()
            },
        },
        EffectLog {
            name: "material_damping",
            active: eff.material_damping,
            seconds: 0.0,
            work: material_damping_work(eff.material_damping, problem),
        },
        EffectLog {
            name: "cubic_springs",
            active: !problem.cubic_springs.is_empty(),
            seconds: sum(main, &[sweep::fast::CUBIC_TIMING])
                + down.as_ref().map_or(0.0, |d| sum(d, &[sweep::fast::CUBIC_TIMING])),
            work: format!(
                "k* = k + ¾αA² of {} cubic springs by {} jointlin_linearize_cubic calls (not an [effects] switch: on when a spring has `cubic`)",
                problem.cubic_springs.len(),
                calls.linearize_cubic
            ),
        },
        EffectLog {
            name: "normal_load_variation",
            active: eff.normal_load_variation,
            seconds: 0.0,
            work: point3d_work(eff.normal_load_variation, steps3, "each closed point's normal direction in the harmonic balance, N(t) from the normal law"),
        },
        EffectLog {
            name: "coupled_slip",
            active: eff.coupled_slip,
            seconds: 0.0,
            work: point3d_work(eff.coupled_slip, steps3, "both tangential directions of a point under one circular slip limit"),
        },
        EffectLog {
            name: "point_energy_output",
            active: eff.point_energy_output,
            seconds: sum(main, &["point outputs", "reporting and point outputs"]),
            work: "per-point amplitude, k*, d*, energy, A/δ* (points.csv)".into(),
        },
        EffectLog {
            name: "stick_slip_map",
            active: eff.stick_slip_map,
            seconds: 0.0,
            work: "regime per point and frequency (stick_slip.csv/svg), from the point results".into(),
        },
        EffectLog {
            name: "field_output",
            active: fields.is_some(),
            seconds: t_fields,
            work: match &fields {
                Some(f) => format!(
                    "displacement and contact fields at {} frequencies, each solved once more in fast mode (field_*.vtu)",
                    f.freqs.len()
                ),
                None => "none ([field_output] not in the scene)".into(),
            },
        },
    ]
}

/// The frequencies of `[field_output]`: the `peaks` highest local maxima of the first
/// output's amplitude over the converged frequencies of `main` (an end of the sweep
/// counts when it is higher than its one neighbour), then the named ones; ascending,
/// each once.
pub fn field_frequencies(fo: &FieldOutputSpec, main: &SweepResult) -> Vec<f64> {
    let amp: Vec<Option<f64>> = (0..main.freqs.len())
        .map(|i| {
            let ok = main.converged.get(i).copied().unwrap_or(false);
            let v = main
                .outputs
                .get(i)
                .and_then(|o| o.first())
                .map(|z| z.norm());
            v.filter(|_| ok)
        })
        .collect();
    let mut peaks: Vec<(f64, f64)> = (0..amp.len())
        .filter_map(|i| {
            let a = amp[i]?;
            let below = |j: Option<usize>| j.and_then(|j| amp[j]).is_none_or(|b| b < a);
            let left = i.checked_sub(1);
            let right = (i + 1 < amp.len()).then_some(i + 1);
            (below(left) && below(right) && amp.len() > 1).then_some((a, main.freqs[i]))
        })
        .collect();
    peaks.sort_by(|x, y| y.0.total_cmp(&x.0));
    let mut at: Vec<f64> = peaks
        .into_iter()
        .take(fo.peaks)
        .map(|(_, f)| f)
        .chain(fo.frequencies.iter().copied())
        .collect();
    at.sort_by(f64::total_cmp);
    at.dedup();
    at
}

/// The log line of material damping: which damping matrices the model carries.
fn material_damping_work(on: bool, problem: &Problem) -> String {
    let parts: Vec<&str> = [
        (problem.damping.is_some(), "viscous D (Rayleigh, dashpots)"),
        (
            problem.structural.is_some(),
            "structural i·s·K (*DAMPING, STRUCTURAL=)",
        ),
    ]
    .into_iter()
    .filter_map(|(has, what)| (on && has).then_some(what))
    .collect();
    if parts.is_empty() {
        "none".into()
    } else {
        format!("{} assembled once with the model", parts.join(" and "))
    }
}

/// The log line of a three-direction point effect: what it does and the point's steps
/// (jointlin_point3d_step, shared by both effects) of the run.
fn point3d_work(on: bool, steps: u64, what: &str) -> String {
    if on {
        format!("{what}: {steps} jointlin_point3d_step calls (both effects together)")
    } else {
        "none".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::scene::Scene;
    use crate::model::build;
    use crate::solve::static_step;

    /// With `interval = "eigenfrequency"` the fast modal route's own basis divides the
    /// range (its modes computed once): at the very frequencies the stuck modes give.
    #[test]
    fn the_modal_basis_divides_the_range_as_the_stuck_modes_do() {
        let path = format!(
            "{}/../scenes/three-beams-coarse.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let text = std::fs::read_to_string(&path).unwrap().replace(
            "[sweep]\n",
            "[sweep]\nmethod = \"modal\"\ninterval = \"eigenfrequency\"\nbias = 3.0\n",
        );
        let scene = Scene::parse(&path, &text).unwrap();
        let job = Job::from(&scene);
        assert!(divides_by_fast_modal_route(&job.settings));
        let p = build(&scene).unwrap();
        let stat = static_step::solve(&p, true).unwrap();
        let mut opts = Options::from_scene(scene.spec.iteration, scene.spec.effects);
        let range = scene.frequencies();
        opts.linear = linear_route(&job.settings, &range);
        let route = sweep::fast::modal_basis(&p, &stat, &opts, range[0]).unwrap();
        let by_route = scene.frequencies_between(&route.frequencies());
        let by_modes = sweep_frequencies(&job.settings, &p, &stat).unwrap();
        assert!(
            by_route.len() > range.len(),
            "{} ≤ {}",
            by_route.len(),
            range.len()
        );
        assert_eq!(by_route.len(), by_modes.len());
        for (a, b) in by_route.iter().zip(&by_modes) {
            assert!((a - b).abs() <= 1e-9 * b, "{a} vs {b}");
        }
        // The sweep over the divided range with that basis.
        let mut cache = Some(route);
        let r = sweep::run_cached(&p, &stat, &by_route, &opts, &|_, _, _| {}, &mut cache).unwrap();
        assert!(r.converged.iter().all(|&c| c));
    }
}
