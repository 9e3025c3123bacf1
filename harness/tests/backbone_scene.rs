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

/// The backbone of scenes/block-stick.toml (a 2 kg mass on a Mindlin joint, the stiff
/// normal spring decoupled) is the single-DOF closed form at every written amplitude:
/// ω² = k*(A)/m and ζ = W/(2π k* A²) (the mode's damper d* = W/(π ω A²) over
/// 2√(k* m)), with k* and W from `jointlin_linearize` at the block's amplitude A. Its
/// stuck modes are the joint's directions, so the reduction keeps no interior mode from
/// them (it once kept their round-off and stopped: "mass matrix is not positive
/// definite"); it ends where ζ nears 1 and the block slides as a whole, said so.
#[test]
fn block_stick_backbone_is_the_single_dof_closed_form() {
    use jointlin_harness::capi::{linearize, Tangential};
    use jointlin_harness::names::{LawName, RuleName};
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::env::temp_dir().join(format!("jointlin-backbone-block-{}", std::process::id()));
    let scene = root.join("scenes/block-stick.toml");
    let args = [
        "backbone",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    let (code, log) = jointlin(&args);
    assert_eq!(code, Some(1), "{log}");
    assert!(
        log.contains("the mode nears critical damping") && log.contains("slide through"),
        "{log}"
    );
    let csv = std::fs::read_to_string(out.join("backbone.csv")).unwrap();
    let _ = std::fs::remove_dir_all(&out);
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (cf, cz, ca, cw) = (
        col("frequency_Hz"),
        col("damping_ratio"),
        col("block_x_amp_mm"),
        col("energy_per_cycle_N_mm"),
    );
    let joint = Tangential {
        law: LawName::Mindlin,
        rule: RuleName::Thesis,
        mu: 0.3,
        normal: 2.0,
        k_t0: 1282.7,
    };
    let (m, two_pi) = (0.002, 2.0 * std::f64::consts::PI);
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    // Measured: 43 amplitudes, the last at ζ = 0.992; 6.3e-11 (ω), 2.8e-10 (ζ) off.
    assert!(rows.len() >= 40, "{csv}");
    let (mut df, mut dz) = (0.0f64, 0.0f64);
    for r in &rows {
        let (f, zeta, a, w) = (r[cf], r[cz], r[ca], r[cw]);
        let l = linearize(&joint, a, two_pi * f).unwrap();
        let f_closed = (l.k_star / m).sqrt() / two_pi;
        let zeta_closed = l.energy_per_cycle / (two_pi * l.k_star * a * a);
        assert!(
            (f / f_closed - 1.0).abs() < 1e-8,
            "{f} Hz vs {f_closed}: {r:?}"
        );
        assert!(
            (zeta / zeta_closed - 1.0).abs() < 1e-8,
            "ζ {zeta} vs {zeta_closed}: {r:?}"
        );
        assert!((w / l.energy_per_cycle - 1.0).abs() < 1e-9, "{r:?}");
        df = df.max((f / f_closed - 1.0).abs());
        dz = dz.max((zeta / zeta_closed - 1.0).abs());
    }
    eprintln!(
        "{} amplitudes: frequency {df:.1e}, ζ {dz:.1e} from the closed form",
        rows.len()
    );
    assert!(rows.last().unwrap()[cz] > 0.9);
}

/// `jointlin` with `args`: (exit code, stderr).
fn jointlin(args: &[&str]) -> (Option<i32>, String) {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .output()
        .unwrap();
    (
        run.status.code(),
        String::from_utf8_lossy(&run.stderr).into_owned(),
    )
}

/// `backbone` and `modes` read the free structure: a scene without `[sweep]`,
/// `[[excitation]]` and `[[outputs]]` runs and gives the same backbone as with them;
/// `run` still names the missing sweep.
#[test]
fn backbone_and_modes_need_no_sweep_excitation_or_outputs() {
    let scene = scene_path();
    let scene = scene.to_str().unwrap();
    let free = [
        "--set",
        "sweep=",
        "--set",
        "excitation=",
        "--set",
        "outputs=",
    ];
    let dir = std::env::temp_dir().join(format!("jointlin-backbone-free-{}", std::process::id()));
    let (a, b) = (dir.join("with"), dir.join("free"));
    let (code, log) = jointlin(&["backbone", scene, "--quiet", "--out", a.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{log}");
    let mut args = vec!["backbone", scene, "--quiet", "--out", b.to_str().unwrap()];
    args.extend(free);
    let (code, log) = jointlin(&args);
    assert_eq!(code, Some(0), "{log}");
    let first3 = |d: &Path| -> Vec<String> {
        std::fs::read_to_string(d.join("backbone.csv"))
            .unwrap()
            .lines()
            .map(|l| l.split(',').take(3).collect::<Vec<_>>().join(","))
            .collect()
    };
    let (with, without) = (first3(&a), first3(&b));
    assert!(with.len() > 10);
    assert_eq!(with, without);
    let mut args = vec!["modes", scene];
    args.extend(free);
    let (code, log) = jointlin(&args);
    assert_eq!(code, Some(0), "{log}");
    let mut args = vec!["run", scene, "--out", b.to_str().unwrap()];
    args.extend(free);
    let (code, log) = jointlin(&args);
    assert_eq!(code, Some(2), "{log}");
    assert!(log.contains("key `sweep`: missing"), "{log}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The rows of a backbone.csv and the index of each named column.
fn backbone_table(dir: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let csv = std::fs::read_to_string(dir.join("backbone.csv")).unwrap();
    let head = csv
        .lines()
        .next()
        .unwrap()
        .split(',')
        .map(String::from)
        .collect();
    let rows = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (head, rows)
}

/// The block on the plane is held tangentially only by its joints (sliding frequency 0)
/// and its x and y sliding modes share one frequency. Its multi-harmonic backbone once
/// stopped at the first amplitude (the free mean made the Jacobian singular, and the
/// stuck start was resonant in the partner direction); now modes 1 and 2 run every
/// default amplitude, each sliding along one axis only (the pair turned to a branch's
/// start: the t1 joints' energy is round-off on mode 1, the t2 joints' on mode 2), and
/// at H = 1 they equal the first-order backbone up to the O(ζ²) of joint damping.
#[test]
fn block_on_plane_multi_harmonic_backbones_slide_along_one_axis_each() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = root.join("scenes/block-on-plane.toml");
    let scene = scene.to_str().unwrap();
    let dir = std::env::temp_dir().join(format!("jointlin-backbone-pair-{}", std::process::id()));
    let mut energies = Vec::new();
    for mode in ["1", "2"] {
        let out = dir.join(mode);
        let args = [
            "backbone",
            scene,
            "--harmonics",
            "3",
            "--mode",
            mode,
            "--quiet",
        ];
        let (code, log) = jointlin(&[&args[..], &["--out", out.to_str().unwrap()]].concat());
        assert_eq!(code, Some(0), "mode {mode}: {log}");
        let (head, rows) = backbone_table(&out);
        assert_eq!(rows.len(), 60, "mode {mode}");
        let sum = |r: &[f64], dir: &str| {
            head.iter()
                .zip(r)
                .filter(|(h, _)| {
                    h.starts_with("joint.") && h.ends_with(&format!(".{dir}_energy_N_mm"))
                })
                .map(|(_, v)| v)
                .sum::<f64>()
        };
        let ratio = rows
            .iter()
            .map(|r| {
                let (t1, t2) = (sum(r, "t1"), sum(r, "t2"));
                t1.min(t2) / t1.max(t2)
            })
            .fold(0.0, f64::max);
        let along = if sum(&rows[0], "t1") > sum(&rows[0], "t2") {
            "t1"
        } else {
            "t2"
        };
        eprintln!(
            "mode {mode}: slides along {along}, the other direction's energy ≤ {ratio:.1e} of it"
        );
        assert!(ratio < 1e-9, "mode {mode}: {ratio:e}");
        energies.push(along);
    }
    assert_ne!(energies[0], energies[1]);
    let amplitudes = ["--amplitudes", "3e-6,3e-5,3"];
    let (first, epmc) = (dir.join("first"), dir.join("epmc"));
    for (out, extra) in [(&first, &[][..]), (&epmc, &["--harmonics", "1"][..])] {
        let args = ["backbone", scene, "--quiet", "--out", out.to_str().unwrap()];
        let (code, log) = jointlin(&[&args[..], &amplitudes, extra].concat());
        assert_eq!(code, Some(0), "{log}");
    }
    let ((_, a), (_, b)) = (backbone_table(&first), backbone_table(&epmc));
    assert_eq!(a.len(), 3);
    for (x, y) in a.iter().zip(&b) {
        let (df, zeta) = ((y[1] / x[1] - 1.0).abs(), x[2]);
        eprintln!(
            "q = {:.1e}: first order {:.6} Hz, EPMC H = 1 {:.6} Hz, ζ = {zeta:.3}",
            x[0], x[1], y[1]
        );
        assert!(df <= zeta * zeta + 1e-7, "{x:?} {y:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
