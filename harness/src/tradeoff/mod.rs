//! `jointlin tradeoff SCENE`: one scene at one frequency, run at a ladder of fidelities;
//! each rung's wall time and its error against the most accurate time-domain run, for two
//! quantities: the first-harmonic amplitude at the first output point and the total joint
//! energy per cycle. Written as tradeoff.csv, tradeoff.md and tradeoff.svg (Pareto plot of
//! error vs wall time).
//!
//! The scene's `[effects]` choose the point model of the harmonic-balance rungs and of the
//! time domain (the three-direction point with `coupled_slip` or `normal_load_variation`,
//! else UINTER); the first-order rungs compute the thesis's model (they have no other).
//!
//! Rungs (frequency domain, fast mode, through the C API):
//! - linear stick: k_T0, no contact damping (no linearization at all);
//! - the thesis's Simpson rule for k* and the loop area at several interval counts
//!   (`jointlin_method`), default iteration tolerance;
//! - the default quadrature at several amplitude-iteration tolerances (the scene's own is
//!   "default");
//! - the multi-harmonic balance (`mode = "harmonic_balance"`) with H = 1, 3, 7, 15 and the
//!   default samples per period, Newton to 1e-6;
//! - for the thesis's point model, where the scene's interfaces allow it (Masing's rule, a
//!   linear normal law), the
//!   harmonic balance with `[effects] normal_load_variation` at H = 1, 3, 7: the normal
//!   load follows the normal law within the cycle, as it does in the time domain (UINTER
//!   at LINPER = 0: the friction limit follows the current pressure), where the thesis's
//!   model holds it at the static value;
//!
//! and the time domain (UINTER LINPER = 0): Newmark at several steps per period (settled
//! to a tolerance), fixed settling lengths, RK4 for small models, and the reference: the
//! finest step (4 × the finest rung's), settled to 1e-6 (FE models, Newmark) or 1e-8
//! (small models, RK4).
//!
//! Wall time: the whole computation at that frequency (model build, static step, solve);
//! frequency-domain rungs are repeated until 0.2 s have passed and averaged.

mod compare;
pub mod lumped;
mod plot;
mod report;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;

use crate::capi::{set_quadrature, Quadrature};
use crate::input::scene::Scene;
use crate::mhb::default_samples;
use crate::run::{run, Extras};
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::{Mode, Units};
use crate::solve::sweep::harmonic_fe_point3d::{check_effects, PointModel};
use crate::time::scene_run::{integrator_for, run_scene, FreqResult};
use crate::time::{Integrator, Start, TimeSettings};
use crate::util::atomic;
use crate::util::csv_table::CsvTable;

use compare::{against_reference, ratios};
pub use report::{csv, markdown, write};

/// The harmonic-balance rungs.
pub const HARMONICS: [usize; 4] = [1, 3, 7, 15];
/// The harmonic-balance rungs with the normal load varying within the cycle.
pub const HARMONICS_NORMAL_LOAD: [usize; 3] = [1, 3, 7];
/// Their Newton tolerance (‖R‖ relative to the stuck response; far below the rungs'
/// differences).
const HB_TOLERANCE: f64 = 1e-6;

/// One rung of the ladder.
#[derive(Debug, Clone, Serialize)]
pub struct Rung {
    /// "linear", "simpson", "default", "tolerance", "harmonic", "normal_load", "time",
    /// "reference".
    pub family: &'static str,
    pub label: String,
    pub seconds: f64,
    /// First-harmonic amplitude at the first output (length).
    pub amplitude: f64,
    /// Total joint energy per cycle (force·length).
    pub energy: f64,
    /// |amplitude / reference − 1|.
    pub amplitude_error: f64,
    /// |energy / reference − 1| (1 when the rung has no joint dissipation).
    pub energy_error: f64,
    /// Converged (frequency domain) or periodic (time domain).
    pub converged: bool,
    pub frequency_domain: bool,
}

/// The study.
#[derive(Debug, Clone, Serialize)]
pub struct Tradeoff {
    pub scene: String,
    /// Frequency (1/time).
    pub freq: f64,
    pub output: String,
    /// The scene's units (column headers and table headings).
    pub units: Units,
    pub rungs: Vec<Rung>,
    /// Summary lines (speed ratios).
    pub summary: Vec<String>,
}

/// The scene at one frequency.
pub fn at_frequency(scene: &Scene, f: f64) -> Scene {
    let mut s = scene.clone();
    s.spec.sweep.f_min = f;
    s.spec.sweep.f_max = f;
    s.spec.sweep.count = 1;
    s.spec.sweep.refine.clear();
    s
}

/// The frequency of the largest response at the first output in the scene's own sweep.
pub fn peak_frequency(scene: &Scene) -> Result<f64, String> {
    let r = run(scene, Extras::default(), &|_, _, _| {}).map_err(|e| e.to_string())?;
    (0..r.main.freqs.len())
        .max_by(|&a, &b| {
            r.main.outputs[a][0]
                .norm()
                .total_cmp(&r.main.outputs[b][0].norm())
        })
        .map(|i| r.main.freqs[i])
        .ok_or_else(|| "the scene has no frequencies".into())
}

/// (amplitude, energy, converged, seconds) of the frequency domain, repeated until 0.2 s.
fn fd(scene: &Scene, q: Option<Quadrature>) -> Result<(f64, f64, bool, f64), String> {
    let prev = set_quadrature(q);
    let t = Instant::now();
    let mut reps = 0;
    let mut out = (0.0, 0.0, false);
    let res = loop {
        let r = match run(scene, Extras::default(), &|_, _, _| {}) {
            Ok(r) => r,
            Err(e) => break Err(e.to_string()),
        };
        out = (
            r.main.outputs[0][0].norm(),
            r.main.power[0] / r.main.freqs[0],
            r.main.converged[0],
        );
        reps += 1;
        if t.elapsed().as_secs_f64() >= 0.2 {
            break Ok(());
        }
    };
    set_quadrature(prev);
    res?;
    Ok((out.0, out.1, out.2, t.elapsed().as_secs_f64() / reps as f64))
}

fn td(scene: &Scene, s: &TimeSettings) -> Result<(FreqResult, f64), String> {
    let t = Instant::now();
    let r = run_scene(scene, s, &|_, _| {}).map_err(|e| e.to_string())?;
    let secs = t.elapsed().as_secs_f64();
    Ok((r.results.into_iter().next().expect("one frequency"), secs))
}

/// Runs the ladder of an FE scene or deck ([`lumped::study`] for lumped scenes). `freq`:
/// the frequency (default: the scene's only one, else its peak).
pub fn study(scene: &Scene, freq: Option<f64>, log: &dyn Fn(&str)) -> Result<Tradeoff, String> {
    let f = match freq {
        Some(f) => f,
        None if scene.frequencies().len() == 1 => scene.frequencies()[0],
        None => {
            log("finding the response peak of the scene's sweep");
            peak_frequency(scene)?
        }
    };
    let base = at_frequency(scene, f);
    let problem = crate::model::build(&base).map_err(|e| e.to_string())?;
    let n_free = problem.sys.dofs.n_free();
    // The first-order rungs: the thesis's point model.
    let first_order = base.thesis_points();
    let scene_model = PointModel::from_effects(&base.spec.effects);
    let mut rungs = Vec::new();
    let mut push_fd = |family, label: String, s: &Scene, q| -> Result<(), String> {
        log(&label);
        let (a, e, c, secs) = fd(s, q)?;
        rungs.push(Rung {
            family,
            label,
            seconds: secs,
            amplitude: a,
            energy: e,
            amplitude_error: 0.0,
            energy_error: 0.0,
            converged: c,
            frequency_domain: true,
        });
        Ok(())
    };
    let mut lin = first_order.clone();
    lin.spec.effects.tangential_microslip = false;
    lin.spec.effects.contact_damping = false;
    push_fd(
        "linear",
        "linear stick (k_T0, no contact damping)".into(),
        &lin,
        None,
    )?;
    for n in [4, 16, 64, 256, 1024] {
        push_fd(
            "simpson",
            format!("HBM/EBM, Simpson {n} intervals"),
            &first_order,
            Some(Quadrature::Simpson(n)),
        )?;
    }
    push_fd(
        "default",
        format!(
            "default (graded Gauss, tolerance {:.0e})",
            base.spec.iteration.tolerance
        ),
        &first_order,
        None,
    )?;
    for tol in [1e-1, 1e-2, 1e-4, 1e-6, 1e-8] {
        let mut s = first_order.clone();
        s.spec.iteration.tolerance = tol;
        s.spec.iteration.max_passes = s.spec.iteration.max_passes.max(200);
        push_fd(
            "tolerance",
            format!("default quadrature, tolerance {tol:.0e}"),
            &s,
            None,
        )?;
    }
    // The scene's point model, or `normal_load_variation` added to the thesis's.
    let harmonic = |h: usize, normal_load_variation: bool| {
        let mut s = base.clone();
        let it = &mut s.spec.iteration;
        it.mode = Mode::HarmonicBalance;
        (it.harmonics, it.samples) = (Some(h), None);
        it.tolerance = HB_TOLERANCE;
        it.max_passes = it.max_passes.max(50);
        s.spec.effects.normal_load_variation |= normal_load_variation;
        s
    };
    let with = report::effects_label(scene_model.coupled_slip, scene_model.normal_load_variation);
    for h in HARMONICS {
        push_fd(
            "harmonic",
            format!(
                "harmonic balance H = {h} (N = {}){with}, Newton to {HB_TOLERANCE:.0e}",
                default_samples(h)
            ),
            &harmonic(h, false),
            None,
        )?;
    }
    if scene_model.coupled_slip {
        // First order with the coupled element: the describing function of each point's
        // ellipse (docs/contact3d.md §4), no harmonic balance.
        let mut s = base.clone();
        s.spec.iteration.mode = Mode::Fast;
        s.spec.effects.normal_load_variation = false;
        push_fd(
            "coupled_first_order",
            "first order with coupled_slip (describing function of the ellipse, tabulated)".into(),
            &s,
            None,
        )?;
    }
    let normal = harmonic(1, true);
    match check_effects(&problem, &normal.spec.effects, Mode::HarmonicBalance) {
        _ if !scene_model.is_thesis() => {}
        Ok(()) => {
            for h in HARMONICS_NORMAL_LOAD {
                push_fd(
                    "normal_load",
                    format!(
                        "harmonic balance H = {h} (N = {}) with normal_load_variation, Newton to {HB_TOLERANCE:.0e}",
                        default_samples(h)
                    ),
                    &harmonic(h, true),
                    None,
                )?;
            }
        }
        Err(e) => log(&format!("no normal_load_variation rungs: {e}")),
    }

    // Time domain.
    let small = integrator_for(&TimeSettings::default(), n_free) == Integrator::Rk4;
    let (start, ramp) = if small {
        (Start::Rest, 1.0)
    } else {
        (Start::Linear, 0.0)
    };
    let base_td = TimeSettings {
        integrator: Integrator::Newmark,
        start,
        ramp_cycles: ramp,
        tolerance: 1e-4,
        min_cycles: 3,
        max_cycles: 4000,
        ..TimeSettings::default()
    };
    let mut td_rungs: Vec<(String, TimeSettings)> = Vec::new();
    let steps: &[usize] = if small {
        &[64, 256, 1024, 4096]
    } else {
        &[32, 64, 128, 256]
    };
    for &n in steps {
        td_rungs.push((
            format!("Newmark {n} steps/period, settled to 1e-4"),
            TimeSettings {
                steps_per_cycle: n,
                ..base_td
            },
        ));
    }
    let mid = steps[2];
    for cycles in [5usize, 20, 80] {
        td_rungs.push((
            format!("Newmark {mid} steps/period, {cycles} cycles"),
            TimeSettings {
                steps_per_cycle: mid,
                tolerance: 0.0,
                min_cycles: cycles.min(base_td.max_cycles),
                max_cycles: cycles + ramp as usize,
                ..base_td
            },
        ));
    }
    if small {
        td_rungs.push((
            "RK4 at its stability limit, settled to 1e-4".into(),
            TimeSettings {
                integrator: Integrator::Rk4,
                steps_per_cycle: 8,
                ..base_td
            },
        ));
    }
    // The reference resolves the contact's kinks in time as well: 4 × the finest rung's
    // steps (RK4 at its stability limit, 17 steps per period on the sliding point mass,
    // was 1 % off the converged periodic state there).
    let reference = if small {
        TimeSettings {
            integrator: Integrator::Rk4,
            steps_per_cycle: 4 * steps[3],
            tolerance: 1e-8,
            max_cycles: 200,
            ..base_td
        }
    } else {
        TimeSettings {
            steps_per_cycle: 4 * steps[3],
            tolerance: 1e-6,
            max_cycles: 20000,
            ..base_td
        }
    };
    let mut all = td_rungs;
    all.push((
        format!(
            "reference: {} settled to {:.0e}",
            if small {
                format!(
                    "RK4 at max({}, its stability limit) steps/period",
                    reference.steps_per_cycle
                )
            } else {
                format!("Newmark {} steps/period", reference.steps_per_cycle)
            },
            reference.tolerance
        ),
        reference,
    ));
    let nref = all.len() - 1;
    // A time-domain rung that stops (e.g. Newton at a coarse step) is reported as such,
    // not as a number; only the reference must reach the periodic state.
    let mut stopped = Vec::new();
    for (k, (label, s)) in all.into_iter().enumerate() {
        log(&label);
        let (r, secs) = match td(&base, &s) {
            Ok(v) => v,
            Err(e) if k != nref => {
                log(&format!("{label}: stopped: {e}"));
                stopped.push(format!("{label}: stopped ({e})"));
                continue;
            }
            Err(e) => return Err(e),
        };
        let label = format!(
            "{label} ({} cycles × {} steps)",
            r.cycles, r.steps_per_cycle
        );
        rungs.push(Rung {
            family: if k == nref { "reference" } else { "time" },
            label,
            seconds: secs,
            amplitude: r.last.outputs[0].amplitude,
            energy: r.last.energy,
            amplitude_error: 0.0,
            energy_error: 0.0,
            converged: r.steady || s.tolerance == 0.0,
            frequency_domain: false,
        });
    }
    against_reference(&mut rungs);
    let mut summary = ratios(&rungs);
    summary.extend(stopped);
    Ok(Tradeoff {
        scene: scene.file.clone(),
        freq: f,
        output: base.spec.outputs[0].name.clone(),
        units: base.spec.units.clone(),
        rungs,
        summary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rung(family: &'static str, seconds: f64, a: f64, e: f64, converged: bool) -> Rung {
        Rung {
            family,
            label: format!("{family} {seconds}"),
            seconds,
            amplitude: 0.0,
            energy: 0.0,
            amplitude_error: a,
            energy_error: e,
            converged,
            frequency_domain: family != "time" && family != "reference",
        }
    }

    #[test]
    fn speed_ratio_picks_the_cheapest_time_run_as_accurate_as_the_default() {
        let r = vec![
            rung("default", 0.01, 1e-3, 2e-2, true),
            // Too inaccurate in energy, cheapest: skipped.
            rung("time", 0.5, 1e-4, 5e-2, true),
            // As accurate but not periodic: skipped.
            rung("time", 1.0, 1e-4, 1e-3, false),
            rung("time", 2.0, 1e-4, 1e-2, true),
            rung("time", 3.0, 1e-5, 1e-3, true),
            rung("reference", 10.0, 0.0, 0.0, true),
        ];
        let s = ratios(&r);
        assert!(s[0].contains("200× slower"), "{}", s[0]);
        assert!(s[1].contains("1000×"), "{}", s[1]);
    }

    /// tradeoff.csv and tradeoff.md carry the scene's units (here m, kN, ms, angular).
    #[test]
    fn tables_carry_the_scene_units() {
        let t = Tradeoff {
            scene: "s.toml".into(),
            freq: 1.0,
            output: "tip".into(),
            units: Units {
                length: "m".into(),
                force: "kN".into(),
                time: "ms".into(),
                mass: "t".into(),
                frequency: Some("rad/ms".into()),
            },
            rungs: vec![rung("default", 0.01, 1e-3, 2e-2, true)],
            summary: Vec::new(),
        };
        let head = csv(&t).lines().next().unwrap().to_string();
        assert_eq!(
            head,
            "family,label,frequency_domain,wall_time_s,amplitude_m,amplitude_error,energy_per_cycle_kN_m,energy_error,converged"
        );
        let md = markdown(&t);
        assert!(md.contains("at 6.283185 rad/ms"), "{md}");
        assert!(
            md.contains("amplitude [m]") && md.contains("energy per cycle [kN·m]"),
            "{md}"
        );
    }
}
