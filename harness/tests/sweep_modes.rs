//! The steady-state step end to end through the C API: the thesis's block (stick case),
//! fast vs thesis mode on a small FE stack, and the call counts of switched-off effects.
//! Units: N, mm, s, t.

use jointlin_harness::run::{run, Extras};
use jointlin_harness::scene::{Mode, Scene};

fn scene(path: &str) -> Scene {
    Scene::load(std::path::Path::new(&format!(
        "{}/../scenes/{path}",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap()
}

fn quiet(_: &str, _: usize, _: usize) {}

#[test]
fn block_stick_amplitude_matches_the_thesis_in_both_modes() {
    let mut amps = Vec::new();
    for mode in [Mode::Fast, Mode::Thesis] {
        let mut s = scene("block-stick.toml");
        s.spec.iteration.mode = mode;
        let r = run(&s, Extras::default(), &quiet).unwrap();
        assert!(r.main.converged[0], "{mode:?}");
        let a = r.main.outputs[0][0].norm();
        eprintln!(
            "{mode:?}: block amplitude {a:.5e} mm, passes {:?}",
            r.main.passes.len()
        );
        // Thesis (Appendix C): linearized 4.267e-4 mm. The library reproduces it within
        // 1 % (issue 2); the host adds a stiff normal spring and the mass (mω² ≪ k_T0).
        assert!((a / 4.267e-4 - 1.0).abs() < 0.01, "{mode:?}: {a}");
        amps.push(a);
    }
    // Same converged answer within the tolerance (1e-6 relative on the contact amplitude).
    assert!((amps[0] / amps[1] - 1.0).abs() < 1e-5, "{amps:?}");
}
