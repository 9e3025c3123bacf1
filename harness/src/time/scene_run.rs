//! A scene in the time domain: the static preload step (as in the frequency domain), then
//! per sweep frequency an integration until the motion is periodic (or `max_cycles`), and
//! the last cycle's statistics. With `start = "rest"` the first frequency starts from the
//! static state with the excitation ramped in and every later one continues from the
//! previous end state (a slow sweep, which follows a branch as a physical sweep would);
//! with `start = "linear"` every frequency starts from the stuck linear steady state.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;

use super::contact::Contacts;
use super::newmark::{add_blocks, effective_stiffness, stuck_blocks, Hht, Newmark};
use super::periodic::{change, Cycle, CycleStats, SteadyTest};
use super::rk4::{max_frequency, stable_steps_per_cycle, SceneRk4};
use super::settings::AUTO_RK4_MAX_DOFS;
use super::{Forcing, Integrator, Start, State, Stepper, TimeError, TimeSettings, C64};
use crate::capi;
use crate::fe::csc::Csc;
use crate::input::scene::Scene;
use crate::model::{build, Problem};
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::Units;
use crate::solve::static_step::{self, StaticState};
use crate::solve::sweep::harmonic_fe_point3d::{check_laws, PointModel};
use crate::solve::umfpack::{to_complex, Symbolic};
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;
use crate::util::provenance;

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
    pub uinter_calls: u64,
    pub seconds: f64,
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
        let sym = Symbolic::new(p.sys.pattern.clone())?;
        let uhat = sym.factor(&s)?.solve(&p.excitation)?;
        for i in 0..n {
            st.u[i] += uhat[i].re;
            st.v[i] = (C64::new(0.0, omega) * uhat[i]).re;
        }
    }
    Ok(st)
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
    let mut steps_per_cycle = settings.steps_per_cycle;
    let mut k0vals = p.sys.k.values.clone();
    add_blocks(p, &mut k0vals, &stuck_blocks(p, stat));
    let k0 = Csc {
        pattern: p.sys.pattern.clone(),
        values: k0vals,
    };
    if kind == Integrator::Rk4 {
        let wmax = max_frequency(&mnum, &k0)?;
        steps_per_cycle = steps_per_cycle.max(stable_steps_per_cycle(omega, wmax));
    }
    let h = period / steps_per_cycle as f64;
    let rk = SceneRk4 {
        p,
        m: &mnum,
        damping: d,
        forcing,
        h,
    };
    st.a = rk.acceleration(0.0, &st.u.clone(), &st.v.clone(), contacts)?;
    // Newmark: K̂₀ = K + a₀M + a₁D + Bᵀ K_c0 B, one factorization.
    let kc0 = stuck_blocks(p, stat);
    let scheme = Hht::new(settings.alpha);
    let mut khat = effective_stiffness(p, d, h, scheme);
    add_blocks(p, &mut khat.values, &kc0);
    let knum;
    let mut rk_holder;
    let mut nm_holder;
    let stepper: &mut dyn Stepper = match kind {
        Integrator::Newmark => {
            knum = sym.factor(&khat)?;
            nm_holder = Newmark::new(
                p,
                &knum,
                kc0,
                d,
                forcing,
                (h, scheme),
                settings.newton_tolerance,
            )?;
            &mut nm_holder
        }
        _ => {
            rk_holder = rk;
            &mut rk_holder
        }
    };

    let nout = p.outputs.len();
    let sample = |u: &[f64]| -> Vec<f64> {
        p.outputs
            .iter()
            .map(|o| o.dofs.iter().map(|&(i, w)| w * u[i]).sum())
            .collect()
    };
    let mut test = SteadyTest::default();
    let mut prev: Option<CycleStats> = None;
    let (mut steps, mut newton) = (0usize, 0usize);
    let mut steady = false;
    let mut distance = f64::INFINITY;
    let mut cycles = 0;
    let ramp_end = ramp_cycles.ceil() as usize;
    while cycles < settings.max_cycles {
        let mut cyc = Cycle::new(omega, steps_per_cycle, nout, contacts.dissipated());
        for _ in 0..steps_per_cycle {
            let (f_old, d_old) = (contacts.force.clone(), contacts.delta.clone());
            newton += stepper.step(st, contacts)?;
            steps += 1;
            cyc.add_work(&f_old, &contacts.force, &d_old, &contacts.delta);
            cyc.push(st.t, &sample(&st.u));
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
    let loose_steps = stepper.loose_steps();
    Ok(FreqResult {
        freq,
        integrator: if kind == Integrator::Newmark {
            "newmark"
        } else {
            "rk4"
        },
        steps_per_cycle,
        cycles,
        steady,
        distance,
        last: prev.expect("max_cycles ≥ 2"),
        steps,
        newton_iterations: newton,
        loose_steps,
        uinter_calls: contacts.calls - calls0,
        seconds: clock.elapsed().as_secs_f64(),
    })
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

/// Runs the scene's sweep in the time domain. `progress(done, total)` per frequency.
pub fn run_scene(
    scene: &Scene,
    settings: &TimeSettings,
    progress: &dyn Fn(usize, usize),
) -> Result<TimeRun, TimeError> {
    let clock = Instant::now();
    let problem = build(scene)?;
    let stat = static_step::solve(&problem, scene.spec.effects.normal_contact_nonlinearity)?;
    let model = PointModel::from_effects(&scene.spec.effects);
    if !model.is_thesis() {
        check_laws(&problem, model).map_err(|e| TimeError::Settings(e.to_string()))?;
    }
    let results = sweep(
        &problem,
        &stat,
        model,
        &scene.frequencies(),
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
        results.push(simulate(
            problem,
            stat,
            &mut contacts,
            &mut st,
            f,
            settings,
            ramp,
        )?);
    }
    progress(freqs.len(), freqs.len());
    Ok(results)
}

/// results_time.csv (units as in results.csv, e.g. N, mm, s): frequency_Hz; per output
/// <name>_amp_mm, <name>_phase_deg (first harmonic, u ≈ x̄ + Re(û e^{iωt})),
/// <name>_half_range_mm ((max − min)/2), <name>_max_mm, <name>_min_mm;
/// dissipated_power_N_mm_per_s (Σ energy per cycle × f); energy_per_cycle_N_mm;
/// energy_trapezoid_N_mm (check); integrator, steps_per_cycle, cycles, steady, distance
/// (relative), wall_time_s (wall clock).
pub fn results_csv(p: &Problem, r: &[FreqResult], units: &Units) -> String {
    let u = ColumnUnits::new(units);
    let l = &u.length;
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    for o in &p.outputs {
        let n = &o.name;
        header.extend([
            format!("{n}_amp_{l}"),
            format!("{n}_phase_deg"),
            format!("{n}_half_range_{l}"),
            format!("{n}_max_{l}"),
            format!("{n}_min_{l}"),
        ]);
    }
    header.extend([
        format!("dissipated_power_{}", u.power),
        format!("energy_per_cycle_{}", u.energy),
        format!("energy_trapezoid_{}", u.energy),
    ]);
    header.extend(
        [
            "integrator",
            "steps_per_cycle",
            "cycles",
            "steady",
            "distance",
            "wall_time_s",
        ]
        .map(String::from),
    );
    let mut t = CsvTable::new(&header);
    for x in r {
        let mut row = vec![exact(fu.show(x.freq))];
        for o in &x.last.outputs {
            row.extend([
                exact(o.amplitude),
                exact(o.phase_deg),
                exact(o.half_range()),
                exact(o.max),
                exact(o.min),
            ]);
        }
        row.extend([
            exact(x.last.energy * x.freq),
            exact(x.last.energy),
            exact(x.last.energy_trapezoid),
            x.integrator.to_string(),
            x.steps_per_cycle.to_string(),
            x.cycles.to_string(),
            x.steady.to_string(),
            exact(x.distance),
            exact(x.seconds),
        ]);
        t.row(&row);
    }
    t.finish()
}

/// points_time.csv (e.g. N, mm, s): frequency_Hz, point, interface, x_mm, y_mm, z_mm,
/// energy_per_cycle_N_mm, then as points.csv the point's node (`node_ids` of its
/// upper/slave node) and its frame n_x … t2_z in global components.
pub fn points_csv(p: &Problem, r: &[FreqResult], units: &Units, node_ids: &[u64]) -> String {
    let u = ColumnUnits::new(units);
    let l = &u.length;
    let fu = frequency_unit(units);
    let mut header = vec![
        fu.column.clone(),
        "point".into(),
        "interface".into(),
        format!("x_{l}"),
        format!("y_{l}"),
        format!("z_{l}"),
        format!("energy_per_cycle_{}", u.energy),
        "node".into(),
    ];
    for axis in ["n", "t1", "t2"] {
        header.extend(["x", "y", "z"].map(|c| format!("{axis}_{c}")));
    }
    let mut t = CsvTable::new(&header);
    for x in r {
        for (i, (c, e)) in p.contacts.iter().zip(&x.last.point_energy).enumerate() {
            let mut row = vec![
                exact(fu.show(x.freq)),
                i.to_string(),
                p.interfaces[c.interface].name.clone(),
                c.position[0].to_string(),
                c.position[1].to_string(),
                c.position[2].to_string(),
                exact(*e),
                node_ids
                    .get(c.nodes[1])
                    .map_or(String::new(), u64::to_string),
            ];
            row.extend(c.frame.iter().map(|v| exact(v + 0.0)));
            t.row(&row);
        }
    }
    t.finish()
}

/// Writes results_time.csv, points_time.csv and, last, run.json into `dir`.
pub fn write(dir: &Path, scene: &Scene, run: &TimeRun) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut files = Vec::new();
    let mut put = |name: &str, text: String| -> std::io::Result<()> {
        let f = dir.join(name);
        crate::util::atomic::write_text(&f, &text).map_err(std::io::Error::other)?;
        files.push(f);
        Ok(())
    };
    let units = &scene.spec.units;
    put(
        "results_time.csv",
        results_csv(&run.problem, &run.results, units),
    )?;
    put(
        "points_time.csv",
        points_csv(
            &run.problem,
            &run.results,
            units,
            &crate::model::node_ids(scene, &run.problem),
        ),
    )?;
    let head = provenance::head("run --time-domain", &capi::abi_version(), &scene.sources);
    let json = provenance::with_head(
        head,
        serde_json::json!({
            "scene": scene.file,
            "title": scene.spec.title,
            // The frequencies below are cycles per time unit.
            "frequency_unit": format!("1/{}", units.time),
            "settings": run.settings,
            "free_dofs": run.problem.sys.dofs.n_free(),
            "contact_points": run.problem.contacts.len(),
            "seconds": run.seconds,
            "frequencies": run.results,
        }),
    );
    let text = serde_json::to_string_pretty(&json).map_err(std::io::Error::other)?;
    // Last: its presence marks a complete directory, as for a frequency-domain run.
    files.push(crate::util::atomic::write_marker(dir, &text).map_err(std::io::Error::other)?);
    Ok(files)
}
