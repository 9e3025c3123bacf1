//! The Duffing oscillator of thesis §4.1 / App. B through `jointlin run`'s engine: the
//! cubic spring is linearized by the library (jointlin_linearize_cubic, (3.8)) and
//! iterated like a contact point. Checked against the closed-form first-order harmonic
//! balance of the harness's validate module (the cubic in A², independent of the sweep).

use jointlin_harness::input::scene::{Mode, Scene};
use jointlin_harness::run::{run, Extras, RunResult};
use jointlin_harness::validate::duffing::Duffing;

fn scene(name: &str, mode: Mode) -> Scene {
    let p = format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    let mut s = Scene::load(std::path::Path::new(&p)).unwrap();
    s.spec.iteration.mode = mode;
    s
}

fn go(s: &Scene) -> RunResult {
    run(s, Extras::default(), &|_, _, _| {}).unwrap()
}

/// (ω [rad/s], amplitude) per frequency of a sweep.
fn curve(r: &jointlin_harness::solve::sweep::SweepResult) -> Vec<(f64, f64)> {
    r.freqs
        .iter()
        .zip(&r.outputs)
        .map(|(f, o)| (2.0 * std::f64::consts::PI * f, o[0].norm()))
        .collect()
}

/// The closed-form folds (ω where three first-order amplitudes begin and end), by a
/// scan in steps of 1e-4 rad/s (the model.md / mhb values are 8.699 and 13.22).
fn folds() -> (f64, f64) {
    let d = Duffing::appendix_b();
    let three: Vec<f64> = (80_000..140_000)
        .map(|i| i as f64 * 1e-4)
        .filter(|&w| d.hbm_amplitudes(w).len() == 3)
        .collect();
    (three[0], *three.last().unwrap())
}

#[test]
fn thesis_point_at_10_rad_s_in_both_modes() {
    for mode in [Mode::Fast, Mode::Thesis] {
        let r = go(&scene("duffing-point.toml", mode));
        assert!(r.main.converged[0], "{mode:?}");
        let a = r.main.outputs[0][0].norm();
        // Thesis: 0.395 (first-order HB, rounded); the closed form 0.39482 (the low
        // branch, which a small start reaches). 1e-3: the required tolerance on 0.3948.
        assert!((a - 0.3948).abs() <= 1e-3, "{mode:?}: {a}");
        let low = Duffing::appendix_b().hbm_amplitudes(10.0)[0];
        // The scene's amplitude tolerance is 1e-6 relative; measured 1.3e-7 (fast),
        // 1e-11 (thesis) from the closed form.
        assert!((a / low - 1.0).abs() < 1e-5, "{mode:?}: {a} vs {low}");
        // One cubic linearization per contact iteration (fast) or per increment run
        // (thesis), and no contact calls.
        let runs = if mode == Mode::Fast {
            r.main.iterations[0]
        } else {
            r.main.passes.iter().map(|p| p.frequencies.len()).sum()
        };
        assert_eq!(r.calls.linearize_cubic as usize, runs, "{mode:?}");
        assert_eq!((r.calls.linearize, r.calls.uinter_linear), (0, 0));
    }
}

#[test]
fn sweeps_up_and_down_jump_at_the_first_order_folds() {
    let (lo, hi) = folds();
    assert!(
        (lo - 8.699).abs() < 1e-3 && (hi - 13.22).abs() < 1e-2,
        "{lo} {hi}"
    );
    let d = Duffing::appendix_b();
    for mode in [Mode::Fast, Mode::Thesis] {
        let r = go(&scene("duffing.toml", mode));
        let down = r.down.as_ref().expect("direction = up_down");
        assert!(r.main.converged.iter().all(|&c| c), "{mode:?}");
        assert!(down.converged.iter().all(|&c| c), "{mode:?}");
        // Every amplitude is a first-order solution: within 1e-4 of one of the closed
        // form's roots (iteration tolerance 1e-6; measured ≤ 2.0e-6 in fast mode, the
        // worst next to a fold where the consistency condition is flat; ≤ 1e-9 thesis).
        for (w, a) in curve(&r.main).into_iter().chain(curve(down)) {
            let near = d
                .hbm_amplitudes(w)
                .iter()
                .map(|x| (a / x - 1.0).abs())
                .fold(f64::INFINITY, f64::min);
            assert!(near < 1e-4, "{mode:?} ω = {w}: {a} ({near:e})");
        }
        // Sweep down: the low branch until the lower fold, then the jump up; the jump
        // must fall between the two frequencies that bracket the fold (± one step).
        let c = curve(down);
        let jump = c.windows(2).position(|p| p[0].1 > 2.0 * p[1].1).unwrap();
        assert!(
            c[jump].0 < lo && lo < c[jump + 1].0,
            "{mode:?} down: {:?}",
            &c[jump..jump + 2]
        );
        for &(w, a) in &c {
            let roots = d.hbm_amplitudes(w);
            let expect = if w > lo {
                roots[0]
            } else {
                *roots.last().unwrap()
            };
            assert!(
                (a / expect - 1.0).abs() < 1e-4,
                "{mode:?} down ω = {w}: {a} vs {expect}"
            );
        }
        // Sweep up, fast mode: the resonant branch until the upper fold, then the drop.
        // Thesis mode leaves the resonant branch earlier: its first pass hands every
        // increment the previous increment's computed amplitude, i.e. direct substitution,
        // which diverges on that branch (d ln a*/d ln a ≈ −7 at 9 rad/s) — measured drop
        // at 8.92–8.98 rad/s; the re-runs then converge on the low branch.
        let c = curve(&r.main);
        let drop = c.windows(2).position(|p| p[0].1 > 2.0 * p[1].1).unwrap();
        if mode == Mode::Fast {
            assert!(
                c[drop].0 < hi && hi < c[drop + 1].0,
                "up: {:?}",
                &c[drop..drop + 2]
            );
            for &(w, a) in &c {
                let roots = d.hbm_amplitudes(w);
                let expect = if w < hi {
                    *roots.last().unwrap()
                } else {
                    roots[0]
                };
                assert!(
                    (a / expect - 1.0).abs() < 1e-4,
                    "up ω = {w}: {a} vs {expect}"
                );
            }
        } else {
            let at = &c[drop..drop + 2];
            assert!(c[drop].0 > lo && c[drop].0 < hi, "thesis up: {at:?}");
        }
    }
}

#[test]
fn time_domain_refuses_cubic_springs_by_name() {
    use jointlin_harness::time::{scene_run, TimeError, TimeSettings};
    let s = scene("duffing-point.toml", Mode::Fast);
    let settings = TimeSettings::from_spec(None).unwrap();
    let r = scene_run::run_scene(&s, &settings, &|_, _| {});
    assert!(matches!(r, Err(TimeError::CubicSprings)), "{r:?}");
}
