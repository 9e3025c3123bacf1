//! Lumped scenes for `jointlin backbone`: springs `between`, `[[joints]]`, the lumped
//! system they build (against the hand-built chain of `jointlin mhb`), the backbone and
//! its reports, and named errors for bad joints.

use std::path::Path;

use jointlin_harness::backbone::{first_order, log_space};
use jointlin_harness::bench::mhb_chain::jenkins_chain;
use jointlin_harness::input;
use jointlin_harness::model::lumped;

fn scene_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/jenkins-chain.toml")
}

#[test]
fn jenkins_chain_scene_is_the_hand_built_chain() {
    let scene = input::load(&scene_path()).unwrap().into_scene();
    let l = lumped::build(&scene).unwrap();
    let hand = jenkins_chain(0.0);
    // y and z of every mass carry nothing and are left out.
    assert_eq!(l.dofs, ["m1.x", "m2.x", "m3.x"]);
    assert_eq!(l.system.m, hand.m);
    assert_eq!(l.system.k, hand.k);
    assert!((&l.system.d - &hand.d).abs().max() < 1e-15);
    assert_eq!(l.elements, ["j1", "j2"]);
    // Element ends may be listed the other way round: compare as sets of DOF pairs.
    let pairs = |s: &jointlin_harness::mhb::System| {
        let mut v: Vec<(usize, Option<usize>)> = s
            .elements
            .iter()
            .map(|e| match e.j {
                Some(j) => (e.i.min(j), Some(e.i.max(j))),
                None => (e.i, None),
            })
            .collect();
        v.sort();
        v
    };
    assert_eq!(pairs(&l.system), pairs(&hand));
    let q = log_space(0.01, 10.0, 12);
    let a = first_order::backbone(&l.system, 1, &q).unwrap();
    let b = first_order::backbone(&hand, 1, &q).unwrap();
    for (x, y) in a.iter().zip(&b) {
        assert!((x.omega / y.omega - 1.0).abs() < 1e-12);
        assert!((x.damping_ratio - y.damping_ratio).abs() < 1e-12);
    }
    assert_eq!(l.outputs[0].0, "m3_x");
    assert_eq!(l.outputs[0].1, [0.0, 0.0, 1.0]);
}

#[test]
fn bad_joints_are_named_errors() {
    let text = std::fs::read_to_string(scene_path()).unwrap();
    let dir = std::env::temp_dir().join(format!("jointlin-backbone-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (from, to, key) in [
        (
            "direction = [1.0, 0.0, 0.0]\nlaw",
            "direction = [1.0, 1.0, 0.0]\nlaw",
            "joints[0].direction",
        ),
        (
            "normal_force = 0.1\nk_t0 = 2.0\n\n[[joints]]",
            "normal_force = -0.1\nk_t0 = 2.0\n\n[[joints]]",
            "joints[0].normal_force",
        ),
        (
            "between = [\"m2\", \"m3\"]\ndirection = [1.0, 0.0, 0.0]\nlaw",
            "between = [\"m2\", \"m9\"]\ndirection = [1.0, 0.0, 0.0]\nlaw",
            "joints[1].between[1]",
        ),
        (
            "between = [\"m1\", \"m2\"]",
            "between = [\"m1\", \"m1\"]",
            "springs[1].between",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let bad = text.replacen(from, to, 1);
        let path = dir.join("bad.toml");
        std::fs::write(&path, bad).unwrap();
        let e = match input::load(&path) {
            Ok(_) => panic!("{key}: accepted"),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(key), "{key}: {e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_reduced_fe_backbone_accepts_consistency_at_the_round_off_floor() {
    // The block on the plane, reduced onto its 9 contact points: at the lowest modal
    // amplitudes the elements moving 3e-5 of the largest carry the mode shape's
    // round-off (~1e-8 relative), which Anderson cannot lower to 1e-10; that is
    // consistency to working accuracy, so the amplitudes up to the onset of sliding
    // are traced (the command once stopped at the first of them).
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::env::temp_dir().join(format!("jointlin-backbone-floor-{}", std::process::id()));
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .arg("backbone")
        .arg(root.join("scenes/block-on-plane.toml"))
        .args(["--amplitudes", "3e-6,1.5e-4,6", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{log}");
    let csv = std::fs::read_to_string(out.join("backbone.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(3).map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 6, "{csv}");
    // Below the stuck 127.370 Hz, softening and damping more as the amplitude grows
    // (measured 126.70 Hz, ζ = 5.3e-3 at the first).
    assert!(rows[0][1] < 127.371 && rows[0][1] > 120.0, "{rows:?}");
    assert!(rows.windows(2).all(|w| w[1][1] < w[0][1]), "{rows:?}");
    assert!(rows.windows(2).all(|w| w[1][2] > w[0][2]), "{rows:?}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_first_order_backbone_that_stops_keeps_the_amplitudes_before() {
    // The block on the plane slides as a whole near q = 1.9e-4 mm·t^½ (its sliding
    // frequency is 0: no mode to be consistent with): the amplitude there fails, the one
    // below it is written with its run.json, the failure is printed and the exit code
    // is 1 (the command once wrote nothing).
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::env::temp_dir().join(format!("jointlin-backbone-stop-{}", std::process::id()));
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .arg("backbone")
        .arg(root.join("scenes/block-on-plane.toml"))
        .args(["--amplitudes", "1.5e-4,2.5e-4,3", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{log}");
    assert!(
        log.contains("not consistent at modal amplitude 1.936492e-4")
            && log.contains("the amplitude below it is written"),
        "{log}"
    );
    let csv = std::fs::read_to_string(out.join("backbone.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), 1, "{csv}");
    assert!(rows[0].starts_with("1.5000000000000004e-4,"), "{csv}");
    assert!(out.join("run.json").exists());
    let _ = std::fs::remove_dir_all(&out);
}
