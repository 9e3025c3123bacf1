//! A lumped scene's sweep in the time domain (`jointlin run --time-domain` of mass bodies,
//! `[[matrices]]`, springs and joints): the static step ([`crate::model::lumped_static`]:
//! points unilateral, every joint stuck), then per frequency RK4 ([`super::lumped`])
//! until the motion is periodic. With `start = "rest"` the first frequency starts at rest
//! in the static state with the excitation ramped in and every later one continues from
//! the previous end state (a slow sweep); with `start = "linear"` every frequency starts
//! from the static state plus the stuck linear steady state. The step is raised to RK4's
//! stability limit on the stuck system's highest mode.

use std::time::Instant;

use super::lumped::{settle, Integration, LumpedState, Settled};
use super::rk4::stable_steps_per_cycle;
use super::{Integrator, Start, TimeError, TimeSettings};
use crate::mhb::contact3d::System3;
use crate::mhb::{linear_coefficients, state_at_zero};
use crate::model::lumped::Lumped;
use crate::model::lumped_static;
use crate::model::Job;
use crate::settings::MAX_STEPS_PER_CYCLE;

/// One frequency of a lumped time-domain sweep.
#[derive(Debug, Clone)]
pub struct LumpedFreq {
    /// Excitation frequency (1/time).
    pub freq: f64,
    pub steps_per_cycle: usize,
    /// The integration's result, or why it stopped (the next frequency then starts
    /// again from rest).
    pub result: Result<Settled, String>,
}

/// A lumped scene run in the time domain.
#[derive(Debug)]
pub struct LumpedTimeRun {
    pub lumped: Lumped,
    pub settings: TimeSettings,
    /// The static displacement per DOF (length).
    pub static_x: Vec<f64>,
    /// The stuck system's highest natural frequency (1/time): RK4's stability bound.
    pub highest_frequency: f64,
    pub results: Vec<LumpedFreq>,
    pub seconds: f64,
}

/// Runs a lumped input's sweep in the time domain (a scene or a [`Job`]);
/// `progress(done, total)` per frequency.
pub fn run_lumped(
    job: impl Into<Job>,
    settings: &TimeSettings,
    progress: &dyn Fn(usize, usize),
) -> Result<LumpedTimeRun, TimeError> {
    let clock = Instant::now();
    let job: Job = job.into();
    if settings.integrator == Integrator::Newmark {
        return Err(TimeError::Settings(
            "a lumped system is integrated by RK4 (time_domain.integrator = \"rk4\" or \"auto\"), its step kept below the stability limit of its stiffest mode".into(),
        ));
    }
    let l = job.lumped().map_err(TimeError::Lumped)?;
    let sys = l.system3();
    let names: Vec<String> = l.joints.iter().map(|j| j.name.clone()).collect();
    let static_x = lumped_static::solve(&sys, &names)
        .map_err(TimeError::Lumped)?
        .x;
    let highest_frequency = l
        .stuck_frequencies()
        .map_err(TimeError::Lumped)?
        .last()
        .copied()
        .unwrap_or(0.0);
    let outputs: Vec<Vec<f64>> = l.outputs.iter().map(|(_, w)| w.clone()).collect();
    let freqs = job.settings.frequencies();
    let mut results = Vec::with_capacity(freqs.len());
    let mut state: Option<LumpedState> = None;
    for (i, &freq) in freqs.iter().enumerate() {
        progress(i, freqs.len());
        let omega = std::f64::consts::TAU * freq;
        let steps_per_cycle = settings.steps_per_cycle.max(stable_steps_per_cycle(
            omega,
            std::f64::consts::TAU * highest_frequency,
        ));
        if steps_per_cycle > MAX_STEPS_PER_CYCLE {
            // A period this long against the stiffest mode: no explicit integration ends.
            results.push(LumpedFreq {
                freq,
                steps_per_cycle,
                result: Err(format!(
                    "RK4 needs {steps_per_cycle} steps per period here (its stability bound on the stiffest stuck mode, {highest_frequency:.6e} per time unit), more than {MAX_STEPS_PER_CYCLE}"
                )),
            });
            state = None;
            continue;
        }
        let (mut st, ramp_cycles) = match (settings.start, state.take()) {
            (Start::Rest, Some(st)) => (st, 0.0),
            (Start::Rest, None) => (LumpedState::at_rest(&sys, &static_x)?, settings.ramp_cycles),
            (Start::Linear, _) => (linear_start(&sys, &static_x, omega)?, 0.0),
        };
        let run = Integration {
            omega,
            steps: steps_per_cycle,
            ramp_cycles,
            tolerance: settings.tolerance,
            min_cycles: settings.min_cycles,
            max_cycles: settings.max_cycles,
        };
        let result = settle(&sys, &mut st, &run, &outputs).map_err(|e| e.to_string());
        if result.is_ok() {
            state = Some(st);
        }
        results.push(LumpedFreq {
            freq,
            steps_per_cycle,
            result,
        });
    }
    progress(freqs.len(), freqs.len());
    Ok(LumpedTimeRun {
        lumped: l,
        settings: *settings,
        static_x,
        highest_frequency,
        results,
        seconds: clock.elapsed().as_secs_f64(),
    })
}

/// The static state plus the first harmonic of the stuck linear steady state at ω (every
/// joint stuck, every point closed): x(0) = x_s + Re x̂, ẋ(0) = Re(iω x̂); the elements
/// loaded to x_s, the jump to x(0) their first increment.
fn linear_start(sys: &System3, xs: &[f64], omega: f64) -> Result<LumpedState, TimeError> {
    let (k, f0) = sys.stuck();
    let u = linear_coefficients(&sys.linear, &k, &f0, omega, 3);
    let first: Vec<f64> = (0..xs.len())
        .flat_map(|d| [0.0, u[3 * d + 1], u[3 * d + 2]])
        .collect();
    let (x1, v) = state_at_zero(&first, 1, omega);
    let mut st = LumpedState::at_rest(sys, xs)?;
    st.x = xs.iter().zip(&x1).map(|(a, b)| a + b).collect();
    st.v = v;
    Ok(st)
}
