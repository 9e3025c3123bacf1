//! A scene in the time domain: the static preload step (as in the frequency domain), then
//! per sweep frequency an integration until the motion is periodic (or `max_cycles`), and
//! the last cycle's statistics. With `start = "rest"` the first frequency starts from the
//! static state with the excitation ramped in and every later one continues from the
//! previous end state (a slow sweep, which follows a branch as a physical sweep would);
//! with `start = "linear"` every frequency starts from the stuck linear steady state.

use std::time::Instant;

use serde::Serialize;

use super::contact::Contacts;
use super::newmark::{add_blocks, stuck_blocks, Hht, Setup};
use super::periodic::{change, Cycle, CycleStats, SteadyTest};
use super::rk4::{max_frequency, stable_steps_per_cycle, SceneRk4};
use super::settings::AUTO_RK4_MAX_DOFS;
use super::step_control::{per_level, ControlledNewmark};
use super::{Forcing, Integrator, Start, State, Stepper, TimeError, TimeSettings, C64};
use crate::fe::csc::Csc;
use crate::mhb::loops::LoopSample;
use crate::model::{Job, Problem};
use crate::solve::prepared::Prepared;
use crate::solve::static_step::StaticState;
use crate::solve::sweep::harmonic_fe_point3d::{check_laws, PointModel};
use crate::solve::umfpack::{to_complex, Numeric, Symbolic};

/// The time-domain result at one frequency.
#[derive(Debug, Clone, Serialize)]
pub struct FreqResult {
    /// Excitation frequency (1/time).
    pub freq: f64,
    /// "rk4" or "newmark".
    pub integrator: &'static str,
    pub steps_per_cycle: usize,
    /// Cycles integrated at this frequency (ramp included).
    pub cycles: usize,
    /// Whether the steady-state test passed (always false with tolerance 0).
    pub steady: bool,
    /// Estimated relative distance to the periodic state after the last cycle.
    pub distance: f64,
    /// Statistics of the last cycle.
    pub last: CycleStats,
    pub steps: usize,
    pub newton_iterations: usize,
    /// Newton stops accepted at the loose tolerance (newmark::LOOSE_TOLERANCE).
    pub loose_steps: usize,
    /// Steps replaced by two half steps after a failed Newton iteration
    /// (`step_control`, at any depth).
    pub cut_steps: usize,
    pub uinter_calls: u64,
    pub seconds: f64,
    /// Per step of the last cycle, per contact point: its tangential relative
    /// displacements, overclosure −δ_n and forces (F₁, F₂, N) (kept by [`sweep`] for the
    /// frequency of the largest response only).
    #[serde(skip)]
    pub loops: Vec<Vec<LoopSample>>,
}

/// Which integrator `settings` means for a model with `n` free DOFs.
pub fn integrator_for(settings: &TimeSettings, n: usize) -> Integrator {
    match settings.integrator {
        Integrator::Auto if n <= AUTO_RK4_MAX_DOFS => Integrator::Rk4,
        Integrator::Auto => Integrator::Newmark,
        i => i,
    }
}

/// Material damping as the frequency domain uses it.
fn damping(p: &Problem) -> Option<&Csc<f64>> {
    p.damping.as_ref()
}

/// The initial state at frequency `freq`: the static state (rest) or static plus the stuck
/// linear steady state (`Start::Linear`).
pub fn initial_state(
    p: &Problem,
    stat: &StaticState,
    freq: f64,
    start: Start,
) -> Result<State, TimeError> {
    let n = p.sys.dofs.n_free();
    let mut st = State {
        t: 0.0,
        u: stat.u.clone(),
        v: vec![0.0; n],
        a: vec![0.0; n],
    };
    if start == Start::Linear {
        let omega = 2.0 * std::f64::consts::PI * freq;
        let mut k = p.sys.k.values.clone();
        add_blocks(p, &mut k, &stuck_blocks(p, stat));
        let mut s = to_complex(&Csc {
            pattern: p.sys.pattern.clone(),
            values: k,
        });
        for (x, m) in s.values.iter_mut().zip(&p.sys.m.values) {
            x.re -= omega * omega * m;
        }
        if let Some(d) = damping(p) {
            for (x, dv) in s.values.iter_mut().zip(&d.values) {
                x.im += omega * dv;
            }
        }
        let sym = Symbolic::symmetric_best(p.sys.pattern.clone())?;
        let uhat = sym.factor(&s)?.solve(&p.excitation)?;
        for i in 0..n {
            st.u[i] += uhat[i].re;
            st.v[i] = (C64::new(0.0, omega) * uhat[i]).re;
        }
    }
    Ok(st)
}

/// `wanted` steps per period of ω, raised to RK4's stability limit on the stiffest mode of
/// the stuck system (K + Bᵀ K_c0 B against M, factored as `m`).
fn rk4_steps_per_cycle(
    p: &Problem,
    stat: &StaticState,
    m: &Numeric<'_, f64>,
    omega: f64,
    wanted: usize,
) -> Result<usize, TimeError> {
    let mut k0 = Csc {
        pattern: p.sys.pattern.clone(),
        values: p.sys.k.values.clone(),
    };
    add_blocks(p, &mut k0.values, &stuck_blocks(p, stat));
    Ok(wanted.max(stable_steps_per_cycle(omega, max_frequency(m, &k0)?)))
}

/// Integrates at `freq` from `st` (whose contact state is `contacts`' committed one, at
/// st.u) until periodic; `ramp` in periods (0 = full excitation at once). Leaves `st` and
/// `contacts` at the end state.
pub fn simulate(
    p: &Problem,
    stat: &StaticState,
    contacts: &mut Contacts,
    st: &mut State,
    freq: f64,
    settings: &TimeSettings,
    ramp_cycles: f64,
) -> Result<FreqResult, TimeError> {
    if p.structural.is_some() {
        return Err(TimeError::Settings(
            "the model has structural damping (*DAMPING, STRUCTURAL=), which has no time-domain form (Abaqus applies it in steady-state steps only)".into(),
        ));
    }
    let clock = Instant::now();
    let calls0 = contacts.calls;
    let omega = 2.0 * std::f64::consts::PI * freq;
    let period = 1.0 / freq;
    let n = p.sys.dofs.n_free();
    st.t = 0.0;
    let forcing = Forcing {
        preload: &p.preload,
        excitation: &p.excitation,
        omega,
        ramp: ramp_cycles * period,
    };
    let d = damping(p);
    // The contacts at st.u (a jump from their committed δ is one increment).
    let delta = contacts.local(&st.u);
    contacts.evaluate(&delta, None)?;
    contacts.commit();
    // Consistent initial acceleration M a = f − K u − D v − Bᵀ q.
    // M and K̂₀ are real and symmetric: real LU on one symbolic analysis.
    let sym = Symbolic::<f64>::new(p.sys.pattern.clone())?;
    let mnum = sym.factor(&p.sys.m)?;
    let kind = integrator_for(settings, n);
    let steps_per_cycle = match kind {
        Integrator::Rk4 => rk4_steps_per_cycle(p, stat, &mnum, omega, settings.steps_per_cycle)?,
        _ => settings.steps_per_cycle,
    };
    let h = period / steps_per_cycle as f64;
    let rk = SceneRk4 {
        p,
        m: &mnum,
        damping: d,
        forcing,
        h,
    };
    st.a = rk.acceleration(0.0, &st.u.clone(), &st.v.clone(), contacts)?;
    // Newmark: K̂₀ = K + c a₀M + a₁D + Bᵀ K_c0 B, one factorization per step size (the
    // full one, and a half-size one where a step first had to be cut).
    let matrices = per_level();
    let factors = per_level();
    let mut rk_holder;
    let mut nm_holder;
    let stepper: &mut dyn Stepper = match kind {
        Integrator::Newmark => {
            let setup = Setup {
                p,
                kc0: stuck_blocks(p, stat),
                damping: d,
                forcing,
                h,
                scheme: Hht::new(settings.alpha),
                tol: settings.newton_tolerance,
            };
            nm_holder = ControlledNewmark::new(setup, &sym, (&matrices, &factors))?;
            &mut nm_holder
        }
        _ => {
            rk_holder = rk;
            &mut rk_holder
        }
    };

    let cycles = integrate_cycles(
        p,
        contacts,
        st,
        stepper,
        omega,
        steps_per_cycle,
        settings,
        ramp_cycles,
    )?;
    Ok(FreqResult {
        freq,
        integrator: ["rk4", "newmark"][usize::from(kind == Integrator::Newmark)],
        steps_per_cycle,
        cycles: cycles.cycles,
        steady: cycles.steady,
        distance: cycles.distance,
        last: cycles.last,
        steps: cycles.steps,
        newton_iterations: cycles.newton,
        loose_steps: stepper.loose_steps(),
        cut_steps: stepper.cut_steps(),
        uinter_calls: contacts.calls - calls0,
        seconds: clock.elapsed().as_secs_f64(),
        loops: cycles.loops,
    })
}

/// What [`integrate_cycles`] did.
struct Cycles {
    cycles: usize,
    steady: bool,
    distance: f64,
    last: CycleStats,
    steps: usize,
    newton: usize,
    loops: Vec<Vec<LoopSample>>,
}

/// Whole cycles of `steps_per_cycle` steps from `st` until the steady-state test passes
/// (after the ramp and `min_cycles`) or `max_cycles`; the last cycle's loops are kept.
#[allow(clippy::too_many_arguments)]
fn integrate_cycles(
    p: &Problem,
    contacts: &mut Contacts,
    st: &mut State,
    stepper: &mut dyn Stepper,
    omega: f64,
    steps_per_cycle: usize,
    settings: &TimeSettings,
    ramp_cycles: f64,
) -> Result<Cycles, TimeError> {
    let nout = p.outputs.len();
    let mut test = SteadyTest::default();
    let mut prev: Option<CycleStats> = None;
    let (mut steps, mut newton) = (0usize, 0usize);
    let mut steady = false;
    let mut distance = f64::INFINITY;
    let mut cycles = 0;
    let ramp_end = ramp_cycles.ceil() as usize;
    let mut loops = Vec::with_capacity(steps_per_cycle);
    while cycles < settings.max_cycles {
        let mut cyc = Cycle::new(omega, steps_per_cycle, nout, contacts.dissipated());
        loops.clear();
        for _ in 0..steps_per_cycle {
            let (f_old, d_old) = (contacts.force.clone(), contacts.delta.clone());
            newton += stepper.step(st, contacts)?;
            steps += 1;
            cyc.add_work(&f_old, &contacts.force, &d_old, &contacts.delta);
            cyc.push(st.t, &output_values(p, &st.u));
            loops.push(loop_samples(contacts));
        }
        cycles += 1;
        let stats = cyc.finish(&contacts.dissipated());
        if cycles > ramp_end {
            if let Some(pr) = &prev {
                distance = test.push(change(pr, &stats));
            }
        }
        prev = Some(stats);
        if settings.tolerance > 0.0
            && cycles >= settings.min_cycles
            && distance <= settings.tolerance
        {
            steady = true;
            break;
        }
    }
    Ok(Cycles {
        cycles,
        steady,
        distance,
        last: prev.expect("max_cycles ≥ 2"),
        steps,
        newton,
        loops,
    })
}

/// The outputs' values at the displacements `u`.
fn output_values(p: &Problem, u: &[f64]) -> Vec<f64> {
    p.outputs
        .iter()
        .map(|o| o.dofs.iter().map(|&(i, w)| w * u[i]).sum())
        .collect()
}

/// Every point's committed sample: (δ_t₁, δ_t₂, −δ_n) and (F₁, F₂, N = −q_n).
fn loop_samples(contacts: &Contacts) -> Vec<LoopSample> {
    contacts
        .delta
        .iter()
        .zip(&contacts.force)
        .map(|(d, q)| LoopSample {
            displacement: [d[1], d[2], -d[0]],
            force: [q[1], q[2], -q[0]],
        })
        .collect()
}

/// A scene run in the time domain.
#[derive(Debug)]
pub struct TimeRun {
    pub problem: Problem,
    pub stat: StaticState,
    pub settings: TimeSettings,
    pub results: Vec<FreqResult>,
    pub seconds: f64,
}

/// Runs an input's sweep in the time domain (a scene, a deck or a [`Job`]).
/// `progress(done, total)` per frequency.
pub fn run_scene(
    job: impl Into<Job>,
    settings: &TimeSettings,
    progress: &dyn Fn(usize, usize),
) -> Result<TimeRun, TimeError> {
    let clock = Instant::now();
    let job: Job = job.into();
    let Prepared { problem, stat, .. } = Prepared::new(&job, &|_| {})?;
    let model = PointModel::from_effects(&job.settings.effects);
    if !model.is_thesis() {
        check_laws(&problem, model).map_err(|e| TimeError::Settings(e.to_string()))?;
    }
    let results = sweep(
        &problem,
        &stat,
        model,
        &job.settings.frequencies(),
        settings,
        progress,
    )?;
    Ok(TimeRun {
        problem,
        stat,
        settings: *settings,
        results,
        seconds: clock.elapsed().as_secs_f64(),
    })
}

/// Time-domain results at `freqs` for a built problem and its static state, with the
/// contact point model `model` ([`Contacts::with_model`]).
pub fn sweep(
    problem: &Problem,
    stat: &StaticState,
    model: PointModel,
    freqs: &[f64],
    settings: &TimeSettings,
    progress: &dyn Fn(usize, usize),
) -> Result<Vec<FreqResult>, TimeError> {
    if !problem.cubic_springs.is_empty() {
        return Err(TimeError::CubicSprings);
    }
    if problem.has_area_samples() {
        return Err(TimeError::AreaSamples);
    }
    let mut results = Vec::new();
    let mut contacts = Contacts::with_model(problem, stat, model)?;
    let mut st = initial_state(
        problem,
        stat,
        freqs.first().copied().unwrap_or(1.0),
        Start::Rest,
    )?;
    for (i, &f) in freqs.iter().enumerate() {
        progress(i, freqs.len());
        let ramp = match settings.start {
            Start::Rest if i == 0 => settings.ramp_cycles,
            Start::Rest => 0.0,
            Start::Linear => {
                contacts = Contacts::with_model(problem, stat, model)?;
                st = initial_state(problem, stat, f, Start::Linear)?;
                0.0
            }
        };
        let mut r = simulate(problem, stat, &mut contacts, &mut st, f, settings, ramp)?;
        // The loops of the largest first-output response so far only (they take
        // points × steps per frequency).
        let amplitude = |x: &FreqResult| x.last.outputs.first().map_or(0.0, |o| o.amplitude);
        match results
            .iter_mut()
            .find(|x: &&mut FreqResult| !x.loops.is_empty())
        {
            Some(best) if amplitude(best) >= amplitude(&r) => r.loops = Vec::new(),
            Some(best) => best.loops = Vec::new(),
            None => {}
        }
        results.push(r);
    }
    progress(freqs.len(), freqs.len());
    Ok(results)
}
