//! The time-domain rungs of the ladder (the parent module's list): Newmark at several
//! steps per period and settling lengths, RK4 for small models, and the reference.

use std::time::Instant;

use super::Rung;
use crate::model::Job;
use crate::time::scene_run::{integrator_for, run_scene, FreqResult};
use crate::time::{Integrator, Start, TimeSettings};

/// The time-domain rungs of a model with `n_free` free DOFs, labelled; the reference
/// last.
pub(super) fn ladder(n_free: usize) -> Vec<(String, TimeSettings)> {
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
    all
}

/// Runs the `ladder` on `base` (one frequency), each named in `log` as it starts, and
/// appends its rungs; the lines of rungs that stopped (a rung that stops, e.g. Newton at
/// a coarse step, is reported as such, not as a number; only the reference, the last,
/// must reach the periodic state).
pub(super) fn run(
    base: &Job,
    ladder: Vec<(String, TimeSettings)>,
    log: &dyn Fn(&str),
    rungs: &mut Vec<Rung>,
) -> Result<Vec<String>, String> {
    let nref = ladder.len() - 1;
    let mut stopped = Vec::new();
    for (k, (label, s)) in ladder.into_iter().enumerate() {
        log(&label);
        let (r, secs) = match td(base, &s) {
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
    Ok(stopped)
}

fn td(scene: &Job, s: &TimeSettings) -> Result<(FreqResult, f64), String> {
    let t = Instant::now();
    let r = run_scene(scene, s, &|_, _| {}).map_err(|e| e.to_string())?;
    let secs = t.elapsed().as_secs_f64();
    Ok((r.results.into_iter().next().expect("one frequency"), secs))
}
