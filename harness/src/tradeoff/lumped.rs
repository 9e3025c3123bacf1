//! `jointlin tradeoff` of a lumped scene (mass bodies, `[[matrices]]`, springs, joints):
//! the same two quantities (the first output's first-harmonic amplitude, the joints'
//! energy per cycle) at a ladder of fidelities against the most accurate time-domain run.
//!
//! Rungs: linear stick (every joint stuck, every point closed); the thesis's first-order
//! method (`mhb::first_order`, which computes the thesis's model whatever the scene's
//! `[effects]`) with the Simpson rule at several interval counts and with the default
//! quadrature; the harmonic balance at H = 1, 3, 7, 15 with the scene's point model; for a
//! scene in the thesis's model whose joints have a `normal`, the balance with
//! `normal_load_variation` at H = 1, 3, 7; the time domain by RK4 (`time::lumped_sweep`,
//! from rest with a one-period ramp) at 64…4096 steps per period settled to 1e-4 and at
//! fixed settling lengths; the reference: RK4 at 16384 steps per period settled to 1e-8.
//! Every step count is raised to RK4's stability bound where that is higher.
//!
//! Wall time: the whole computation at that frequency (the lumped system's build with its
//! static step, the solve); frequency-domain rungs are repeated until 0.2 s have passed and
//! averaged. The first-order and balance rungs start from the stuck response (no
//! continuation from a neighbouring frequency).

use std::time::Instant;

use super::{
    against_reference, ladder_base, ratios, Rung, Tradeoff, HARMONICS, HARMONICS_NORMAL_LOAD,
};
use crate::capi::{set_quadrature, Quadrature};
use crate::mhb::default_samples;
use crate::mhb::lumped_sweep::Sweep;
use crate::model::lumped::Lumped;
use crate::model::Job;
use crate::settings::Mode;
use crate::time::lumped_sweep::run_lumped;
use crate::time::{Integrator, Start, TimeSettings};

/// A rung's solve of a lumped system at ω: (amplitude of the first output, joint energy
/// per cycle).
type Solver = dyn Fn(&Lumped, f64) -> Result<(f64, f64), String>;

/// Steps per period of the time-domain rungs (each raised to RK4's stability bound).
const STEPS: [usize; 4] = [64, 256, 1024, 4096];

/// (amplitude of the first output, joint energy per cycle) of a solve of `l` at ω with
/// (H, N) or first order.
fn solve(l: &Lumped, harmonic: Option<(usize, usize)>, omega: f64) -> Result<(f64, f64), String> {
    let sys = l.system3();
    let s = Sweep::new(l, &sys, harmonic)
        .solve(omega)
        .map_err(|e| e.to_string())?;
    let w = &l.outputs.first().ok_or("the scene has no [[outputs]]")?.1;
    let amplitude = w
        .iter()
        .zip(&s.x)
        .map(|(w, x)| x * *w)
        .sum::<nalgebra::Complex<f64>>()
        .norm();
    let energy =
        s.element_energy.iter().sum::<f64>() + s.points.iter().map(|p| p.energy).sum::<f64>();
    Ok((amplitude, energy))
}

/// The stuck linear response's amplitude at the first output (energy 0).
fn stuck(l: &Lumped, omega: f64) -> Result<(f64, f64), String> {
    let sys = l.system3();
    let (k, f0) = sys.stuck();
    let u = crate::mhb::linear_coefficients(&sys.linear, &k, &f0, omega, 3);
    let w = &l.outputs.first().ok_or("the scene has no [[outputs]]")?.1;
    let (a, b) = w.iter().enumerate().fold((0.0, 0.0), |(a, b), (d, w)| {
        (a + w * u[3 * d + 1], b + w * u[3 * d + 2])
    });
    Ok((f64::hypot(a, b), 0.0))
}

/// A frequency-domain rung of `scene` at ω, repeated until 0.2 s: (amplitude, energy,
/// converged, seconds per run). A solve that fails is a rung that did not converge.
fn fd(
    scene: &Job,
    omega: f64,
    q: Option<Quadrature>,
    how: &Solver,
) -> Result<(f64, f64, bool, f64), String> {
    let prev = set_quadrature(q);
    let t = Instant::now();
    let mut reps = 0;
    let res = loop {
        let out = scene.lumped().map(|l| how(&l, omega));
        reps += 1;
        if t.elapsed().as_secs_f64() >= 0.2 || !matches!(out, Ok(Ok(_))) {
            break out;
        }
    };
    set_quadrature(prev);
    let secs = t.elapsed().as_secs_f64() / reps as f64;
    Ok(match res? {
        Ok((a, e)) => (a, e, true, secs),
        Err(_) => (0.0, 0.0, false, secs),
    })
}

/// The frequency of the largest first-output response in the job's own sweep (its
/// mode, each frequency continued from the last).
pub fn peak_frequency(job: &Job) -> Result<f64, String> {
    let l = job.lumped()?;
    let sys = l.system3();
    let it = &job.settings.iteration;
    let harmonic = (it.mode == Mode::HarmonicBalance).then(|| {
        let h = it.harmonics.unwrap_or(1);
        (h, it.samples.unwrap_or_else(|| default_samples(h)))
    });
    let w = &l.outputs.first().ok_or("the scene has no [[outputs]]")?.1;
    let mut sweep = Sweep::new(&l, &sys, harmonic);
    let mut best: Option<(f64, f64)> = None;
    for f in job.settings.frequencies() {
        let Ok(s) = sweep.solve(std::f64::consts::TAU * f) else {
            continue;
        };
        let a = w
            .iter()
            .zip(&s.x)
            .map(|(w, x)| x * *w)
            .sum::<nalgebra::Complex<f64>>()
            .norm();
        if best.is_none_or(|(_, b)| a > b) {
            best = Some((f, a));
        }
    }
    best.map(|b| b.0)
        .ok_or_else(|| "no frequency of the scene's sweep converged".into())
}

/// Runs the ladder of a lumped scene (or a [`Job`] of one) at `freq` (default: the
/// sweep's only frequency, else its peak).
pub fn study(
    job: impl Into<Job>,
    freq: Option<f64>,
    log: &dyn Fn(&str),
) -> Result<Tradeoff, String> {
    let job: Job = job.into();
    let (f, base) = ladder_base(&job, freq, log, peak_frequency)?;
    let (mut rungs, failed) = frequency_rungs(&base, std::f64::consts::TAU * f, log)?;
    rungs.extend(time_rungs(&base, log)?);
    against_reference(&mut rungs);
    Ok(Tradeoff {
        scene: job.file().to_string(),
        freq: f,
        output: base
            .settings
            .outputs
            .first()
            .map_or_else(String::new, |o| o.name.clone()),
        units: base.settings.units.clone(),
        summary: ratios(&rungs).into_iter().chain(failed).collect(),
        rungs,
    })
}

/// The frequency-domain rungs of `base` at ω, and the labels of those that failed.
fn frequency_rungs(
    base: &Job,
    omega: f64,
    log: &dyn Fn(&str),
) -> Result<(Vec<Rung>, Vec<String>), String> {
    let effects = &base.settings.effects;
    let thesis = base.with_settings(base.settings.thesis_points());
    let mut rungs = Vec::new();
    let mut failed = Vec::new();
    let mut push = |family, label: String, s: &Job, q, how: &Solver| -> Result<(), String> {
        log(&label);
        let (amplitude, energy, converged, seconds) = fd(s, omega, q, how)?;
        if !converged {
            // A solve that fails has no numbers: named in the summary, not plotted.
            log(&format!("{label}: did not converge"));
            failed.push(format!("{label}: did not converge"));
            return Ok(());
        }
        rungs.push(Rung {
            family,
            label,
            seconds,
            amplitude,
            energy,
            amplitude_error: 0.0,
            energy_error: 0.0,
            converged,
            frequency_domain: true,
        });
        Ok(())
    };
    push(
        "linear",
        "linear stick (k_T0, points closed)".into(),
        &thesis,
        None,
        &stuck,
    )?;
    let first_order = |l: &Lumped, w: f64| solve(l, None, w);
    for n in [4, 16, 64, 256, 1024] {
        push(
            "simpson",
            format!("first order, Simpson {n} intervals"),
            &thesis,
            Some(Quadrature::Simpson(n)),
            &first_order,
        )?;
    }
    push(
        "default",
        "first order (thesis's model, graded Gauss)".into(),
        &thesis,
        None,
        &first_order,
    )?;
    let with = super::report::effects_label(effects.coupled_slip, effects.normal_load_variation);
    for h in HARMONICS {
        let n = default_samples(h);
        push(
            "harmonic",
            format!("harmonic balance H = {h} (N = {n}){with}"),
            base,
            None,
            &move |l: &Lumped, w| solve(l, Some((h, n)), w),
        )?;
    }
    let has_normal = (base.lumped()?.joints.iter()).any(|j| j.static_normal.is_some());
    if !effects.normal_load_variation && !effects.coupled_slip && has_normal {
        let mut with_normal = base.settings.clone();
        with_normal.effects.normal_load_variation = true;
        let normal = base.with_settings(with_normal);
        for h in HARMONICS_NORMAL_LOAD {
            let n = default_samples(h);
            push(
                "normal_load",
                format!("harmonic balance H = {h} (N = {n}) with normal_load_variation"),
                &normal,
                None,
                &move |l: &Lumped, w| solve(l, Some((h, n)), w),
            )?;
        }
    }
    Ok((rungs, failed))
}

/// The time-domain rungs, the reference last (it must reach the periodic state; another
/// rung that stops is left out with the reason logged).
fn time_rungs(base: &Job, log: &dyn Fn(&str)) -> Result<Vec<Rung>, String> {
    let settled = TimeSettings {
        integrator: Integrator::Rk4,
        start: Start::Rest,
        ramp_cycles: 1.0,
        tolerance: 1e-4,
        min_cycles: 3,
        max_cycles: 4000,
        ..TimeSettings::default()
    };
    let mut ladder: Vec<(String, TimeSettings)> = STEPS
        .iter()
        .map(|&n| {
            (
                format!("RK4 {n} steps/period, settled to 1e-4"),
                TimeSettings {
                    steps_per_cycle: n,
                    ..settled
                },
            )
        })
        .collect();
    for cycles in [5usize, 20, 80] {
        ladder.push((
            format!("RK4 {} steps/period, {cycles} cycles", STEPS[2]),
            TimeSettings {
                steps_per_cycle: STEPS[2],
                tolerance: 0.0,
                min_cycles: cycles,
                max_cycles: cycles + 1,
                ..settled
            },
        ));
    }
    let reference = TimeSettings {
        steps_per_cycle: 4 * STEPS[3],
        tolerance: 1e-8,
        ..settled
    };
    ladder.push((
        format!(
            "reference: RK4 {} steps/period, settled to 1e-8",
            reference.steps_per_cycle
        ),
        reference,
    ));
    let last = ladder.len() - 1;
    let mut rungs = Vec::new();
    for (k, (label, s)) in ladder.into_iter().enumerate() {
        log(&label);
        let t = Instant::now();
        let run = run_lumped(base, &s, &|_, _| {}).map_err(|e| e.to_string())?;
        let seconds = t.elapsed().as_secs_f64();
        let one = run.results.into_iter().next().expect("one frequency");
        let settled = match one.result {
            Ok(x) if k != last || x.steady => x,
            Ok(x) => {
                return Err(format!(
                "the reference did not reach the periodic state (distance {:.1e} after {} cycles)",
                x.distance, x.cycles
            ))
            }
            Err(e) if k != last => {
                log(&format!("{label}: stopped: {e}"));
                continue;
            }
            Err(e) => return Err(format!("the reference: {e}")),
        };
        let output = run.lumped.dofs.len();
        rungs.push(Rung {
            family: if k == last { "reference" } else { "time" },
            label: format!(
                "{label} ({} cycles × {} steps)",
                settled.cycles, one.steps_per_cycle
            ),
            seconds,
            amplitude: settled
                .last
                .outputs
                .get(output)
                .map_or(0.0, |o| o.amplitude),
            energy: settled.last.energy,
            amplitude_error: 0.0,
            energy_error: 0.0,
            converged: settled.steady || s.tolerance == 0.0,
            frequency_domain: false,
        });
    }
    Ok(rungs)
}
