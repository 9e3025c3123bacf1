//! The FE time domain on a scene whose joints slide and whose contact pressures vary
//! during the cycle: `scenes/three-beams-oblique.toml` (Jenkins points, Masing, an oblique
//! 0.5 N tip force) at 1150 Hz, just below its peak, where the outer points slide. Newmark
//! (HHT-α) with 128 steps per period must reach the periodic state, with the thesis's
//! point model and with both contact effects, and that state must be the harmonic
//! balance's (H = 7) of the same scene: an independent method (Fourier–Galerkin in the
//! frequency domain against step-by-step integration) on the same contact law.

use std::path::Path;

use jointlin_harness::input::scene::overrides::Override;
use jointlin_harness::input::scene::Scene;
use jointlin_harness::run::{run, Extras};
use jointlin_harness::time::scene_run::run_scene;
use jointlin_harness::time::TimeSettings;

const FREQ: f64 = 1150.0;

fn oblique(effects: bool, extra: &[&str]) -> Scene {
    oblique_at(FREQ, effects, extra)
}

/// The scene at one frequency `f` (Hz), 128 steps per period unless `extra` says
/// otherwise, with both contact effects if `effects`.
fn oblique_at(f: f64, effects: bool, extra: &[&str]) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/three-beams-oblique.toml");
    let mut set = vec![
        "sweep.count=1".to_string(),
        format!("sweep.f_min={f}"),
        format!("sweep.f_max={f}"),
        "time_domain.steps_per_cycle=128".to_string(),
    ];
    if effects {
        set.push("effects.coupled_slip=true".into());
        set.push("effects.normal_load_variation=true".into());
    }
    set.extend(extra.iter().map(|s| s.to_string()));
    let set: Vec<Override> = set.iter().map(|s| s.parse().unwrap()).collect();
    Scene::load_with(&path, &set).unwrap()
}

#[test]
fn the_time_domain_of_sliding_oblique_beams_is_periodic_and_is_the_balances() {
    for effects in [false, true] {
        let s = oblique(effects, &[]);
        let settings = TimeSettings::from_spec(s.spec.time_domain.as_ref()).unwrap();
        let td = run_scene(&s, &settings, &|_, _| {}).unwrap();
        let r = &td.results[0];
        assert!(
            r.steady,
            "effects {effects}: not periodic after {} cycles (distance {:e})",
            r.cycles, r.distance
        );
        // The library's accumulated dissipation against the trapezoid ∮F·dδ of the same
        // steps: one periodic motion, two sums.
        let trapezoid = (r.last.energy - r.last.energy_trapezoid).abs() / r.last.energy;
        let hb = run(
            &oblique(effects, &["iteration.harmonics=7"]),
            Extras::default(),
            &|_, _, _| {},
        )
        .unwrap();
        assert!(hb.main.converged[0], "effects {effects}: balance");
        let amplitude = hb.main.outputs[0][0].norm();
        let energy = hb.main.power[0] / FREQ;
        let da = (r.last.outputs[0].amplitude - amplitude).abs() / amplitude;
        let de = (r.last.energy - energy).abs() / energy;
        println!(
            "effects {effects}: periodic after {} cycles, {} loose steps; middle_tip {:.5e} mm, \
             energy {:.5e} N·mm per cycle: {da:.1e} and {de:.1e} from the balance (H = 7), \
             trapezoid within {trapezoid:.1e}",
            r.cycles, r.loose_steps, r.last.outputs[0].amplitude, r.last.energy
        );
        assert!(trapezoid < 1e-2, "effects {effects}: {trapezoid:e}");
        assert!(da < 2e-2 && de < 2e-2, "effects {effects}: {da:e} {de:e}");
    }
}

#[test]
fn without_numerical_damping_the_sliding_beams_do_not_settle() {
    // HHT-α = 0 (average acceleration) leaves the stiff normal penalties' modes, excited
    // at every stick–slip transition, undamped: after 150 periods the estimated distance
    // to a periodic state is still 0.25 (cycle-to-cycle changes of 2e-2…5e-1 in the
    // energy), where α = −0.05 settles in about 50. The default makes the reference usable.
    let s = oblique(
        false,
        &["time_domain.alpha=0.0", "time_domain.max_cycles=150"],
    );
    let settings = TimeSettings::from_spec(s.spec.time_domain.as_ref()).unwrap();
    let td = run_scene(&s, &settings, &|_, _| {}).unwrap();
    let r = &td.results[0];
    println!(
        "α = 0: steady {} after {} cycles, distance {:.2e}",
        r.steady, r.cycles, r.distance
    );
    assert!(!r.steady && r.distance > 1e-3, "{}", r.distance);
}

#[test]
fn a_step_whose_newton_fails_is_cut_and_the_run_goes_on() {
    // Ten times the scene's force (5 N: the joint slides grossly, the pressures swing) with
    // both contact effects at a coarse 16 steps per period from the stuck linear state
    // (1154 Hz): the contact Newton fails at two steps (the run used to stop at the first).
    // Cut into halves they converge and the run reaches the periodic state, whose
    // dissipation and ∮F·dδ agree to the coarse steps' accuracy (measured 2.0e-2).
    let f = 1154.0;
    let s = oblique_at(
        f,
        true,
        &[
            "excitation.0.amplitude=5.0",
            "time_domain.steps_per_cycle=16",
            "time_domain.start=\"linear\"",
        ],
    );
    let settings = TimeSettings::from_spec(s.spec.time_domain.as_ref()).unwrap();
    let td = run_scene(&s, &settings, &|_, _| {}).unwrap();
    let r = &td.results[0];
    let trapezoid = (r.last.energy - r.last.energy_trapezoid).abs() / r.last.energy;
    println!(
        "5 N, 16 steps/period, both effects: {} cut steps, {} loose, steady {} after {} \
         cycles; energy {:.4e} N·mm, trapezoid within {trapezoid:.1e}",
        r.cut_steps, r.loose_steps, r.steady, r.cycles, r.last.energy
    );
    assert!(r.cut_steps >= 1 && r.steady);
    assert!(trapezoid < 5e-2, "{trapezoid:e}");
}
