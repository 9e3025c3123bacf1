//! `jointlin reduce`: an FE scene or deck written as a `[[matrices]]` model with its
//! scene. The reduced scene runs as any lumped scene, and its numbers are the full
//! model's: stuck frequencies to round-off (every kept mode lies in the basis), the
//! first-order sweep of scenes/three-beams-coarse.toml against the FE fast sweep of the
//! same scene to the truncation of the interior modes (falling with their number), the
//! H = 1 EPMC backbone against the FE scene's own backbone.

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo(p: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(p)
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-reduce-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Runs `jointlin ARGS`; its stderr, and stdout; panics with stderr unless it exits 0.
fn jointlin_both(args: &[&str]) -> (String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "jointlin {args:?}: {err}");
    (err, String::from_utf8_lossy(&out.stdout).to_string())
}

/// Runs `jointlin ARGS`; its stderr.
fn jointlin(args: &[&str]) -> String {
    jointlin_both(args).0
}

/// `jointlin run SCENE --out OUT --no-plots [--set S]…`; the log.
fn run_scene(scene: &Path, out: &Path, set: &[&str]) -> String {
    let mut args = vec![
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-plots",
    ];
    for s in set {
        args.extend(["--set", s]);
    }
    jointlin(&args)
}

fn reduce(model: &str, name: &str, extra: &[&str]) -> PathBuf {
    let dir = tmp(name);
    let m = repo(model);
    let mut args = vec![
        "reduce",
        m.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    jointlin(&args);
    dir
}

/// Rows of a CSV as maps.
fn rows(path: &Path) -> Vec<std::collections::BTreeMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

fn num(r: &std::collections::BTreeMap<String, String>, k: &str) -> f64 {
    r[k].parse().unwrap_or_else(|_| panic!("{k}: `{}`", r[k]))
}

fn run_json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("run.json")).unwrap()).unwrap()
}

/// Largest relative difference of the two outputs' amplitudes over all frequencies of
/// two results.csv (the same frequencies); every row of `b` converged.
fn largest_difference(a: &Path, b: &Path) -> f64 {
    let (ra, rb) = (rows(a), rows(b));
    assert_eq!(ra.len(), rb.len());
    let mut worst = 0.0f64;
    for (x, y) in ra.iter().zip(&rb) {
        assert_eq!(y["status"], "converged", "{y:?}");
        let f = num(x, "frequency_Hz");
        assert!((num(y, "frequency_Hz") / f - 1.0).abs() < 1e-12);
        for k in ["middle_tip_amp_mm", "top_tip_amp_mm"] {
            worst = worst.max((num(y, k) / num(x, k) - 1.0).abs());
        }
    }
    worst
}

#[test]
fn three_beams_reduced_sweeps_as_the_full_model() {
    // The FE fast sweep, consistent to 1e-10 (the scene's 1e-3 would dominate).
    let fe = tmp("fe");
    let scene = repo("scenes/three-beams-coarse.toml");
    run_scene(&scene, &fe, &["iteration.tolerance=1e-10"]);
    let mut errors = Vec::new();
    for modes in ["4", "16"] {
        let dir = reduce("scenes/three-beams-coarse.toml", modes, &["--modes", modes]);
        let r = run_json(&dir);
        assert_eq!(r["closed_points"], 36);
        assert_eq!(r["joints"], 72);
        // 72 contact directions and the two outputs; the load acts on top_tip's z, the
        // same coordinate.
        assert_eq!(r["retained_coordinates"], 74);
        let text = std::fs::read_to_string(dir.join("scene.toml")).unwrap();
        assert!(
            text.contains("[[excitation]]\nkind = \"point\"\nbody = \"reduced.top_tip\""),
            "{text}"
        );
        assert!(
            r["largest_relative_difference"].as_f64().unwrap() < 1e-9,
            "{r}"
        );
        let dofs = std::fs::read_to_string(dir.join("dofs.csv")).unwrap();
        assert!(dofs.contains("\nlower_0,x\nlower_0,y\n"), "{dofs}");
        assert!(dofs.contains("\nmiddle_tip,z\n") && dofs.contains("\ntop_tip,z\n"));
        let out = dir.join("run");
        let log = run_scene(&dir.join("scene.toml"), &out, &[]);
        assert!(log.contains("100 of 100 frequencies converged"), "{log}");
        errors.push(largest_difference(
            &fe.join("results.csv"),
            &out.join("results.csv"),
        ));
    }
    // Measured: 4.6e-4 with 4 interior modes, 1.7e-8 with 16.
    assert!(errors[1] < 1e-7, "{errors:?}");
    assert!(errors[0] > 100.0 * errors[1], "{errors:?}");
}

/// `jointlin backbone` (with `args`) of `scene` and of its reduction in `reduced`: both
/// have `count` rows, equal in frequency to 1e-7 and in damping ratio to 1e-6.
fn same_backbones(scene: &str, reduced: &Path, name: &str, args: &[&str], count: usize) {
    let (a, b) = (tmp(&format!("{name}-fe")), tmp(&format!("{name}-reduced")));
    for (input, out) in [(repo(scene), &a), (reduced.join("scene.toml"), &b)] {
        let mut all = vec!["backbone", input.to_str().unwrap(), "--out"];
        all.extend([out.to_str().unwrap(), "--quiet"]);
        all.extend(args);
        jointlin(&all);
    }
    let (ra, rb) = (rows(&a.join("backbone.csv")), rows(&b.join("backbone.csv")));
    assert_eq!(ra.len(), count);
    assert_eq!(rb.len(), count);
    for (x, y) in ra.iter().zip(&rb) {
        for (k, tol) in [("frequency_Hz", 1e-7), ("damping_ratio", 1e-6)] {
            let d = (num(y, k) / num(x, k) - 1.0).abs();
            assert!(d < tol, "{k}: {x:?} {y:?}");
        }
    }
}

/// The H = 1 EPMC backbone of the reduced three-beams-coarse (16 interior modes) is the
/// FE scene's own. Measured: ≤ 6.3e-9 (frequency), ≤ 2.4e-8 (damping ratio) from 1174 Hz
/// stuck to 437 Hz sliding; the two reductions differ by the retained outputs and load.
#[test]
fn reduced_backbone_is_the_fe_backbone() {
    let scene = "scenes/three-beams-coarse.toml";
    let dir = reduce(scene, "backbone", &["--modes", "16"]);
    let epmc = ["--harmonics", "1", "--amplitudes", "1e-5,1e-2,12"];
    same_backbones(scene, &dir, "bb", &epmc, 12);
}

/// The first-order backbone (`jointlin backbone`, default amplitudes) of the reduced
/// three-beams-oblique (8 interior modes, 83 rows: above the dense mode search's size, so
/// its stuck mode is tracked) is the FE scene's own: every amplitude, measured 1.0e-9 in
/// frequency and 2.0e-8 in damping ratio (it stopped at once, "no oscillatory mode", while
/// the tracking's λ jittered at round-off).
#[test]
fn reduced_first_order_backbone_is_the_fe_backbone() {
    let scene = "scenes/three-beams-oblique.toml";
    let dir = reduce(scene, "backbone-first", &[]);
    same_backbones(scene, &dir, "bb1", &[], 60);
}

#[test]
fn a_deck_reduces_and_its_load_pattern_is_one_coordinate() {
    let dir = reduce("examples/abaqus/block-on-plane/block.inp", "deck", &[]);
    let r = run_json(&dir);
    assert_eq!(r["closed_points"], 9);
    assert!(
        r["largest_relative_difference"].as_f64().unwrap() < 1e-8,
        "{r}"
    );
    let dofs = std::fs::read_to_string(dir.join("dofs.csv")).unwrap();
    assert!(
        dofs.contains("# load: x along the load's pattern"),
        "{dofs}"
    );
    // The reduced scene reads as a lumped scene: `jointlin modes` of it (its joints
    // stuck) gives the full model's stuck frequencies, as printed (7 digits).
    let (_, table) = jointlin_both(&["modes", dir.join("scene.toml").to_str().unwrap()]);
    let printed: Vec<f64> = table
        .lines()
        .filter_map(|l| {
            l.strip_prefix("| ")?
                .split(" | ")
                .nth(1)?
                .trim_end_matches(" |")
                .parse()
                .ok()
        })
        .collect();
    let full = r["stuck_frequencies_full_model"].as_array().unwrap();
    assert!(printed.len() >= 6, "{table}");
    for (p, f) in printed.iter().zip(full) {
        let f = f.as_f64().unwrap();
        assert!((p / f - 1.0).abs() < 1e-6, "{p} against {f}\n{table}");
    }
}

#[test]
fn lumped_scenes_are_refused() {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args([
            "reduce",
            repo("scenes/jenkins-chain.toml").to_str().unwrap(),
            "--out",
        ])
        .arg(tmp("refused"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("reduced already"), "{err}");
}

/// With `[effects] normal_load_variation` and `coupled_slip` each closed point becomes
/// one three-direction joint (its opening retained, its normal spring moved from K₀ into
/// the joint, clamped by its static normal force): the reduced scene's harmonic balance
/// of `scenes/three-beams-oblique.toml` is the FE balance with both effects to the
/// balance's tolerance (measured 4.6e-6), not the thesis model's. The FE backbone, which
/// reduces onto one-direction joints, refuses the effects.
#[test]
fn three_direction_joints_reduce_as_the_fe_balance() {
    let effects = [
        "effects.normal_load_variation=true",
        "effects.coupled_slip=true",
    ];
    let sweep = "sweep.count=7";
    let scene = repo("scenes/three-beams-oblique.toml");
    let fe = tmp("fe3");
    run_scene(&scene, &fe, &[effects[0], effects[1], sweep]);
    let thesis = tmp("fe3-thesis");
    run_scene(&scene, &thesis, &[sweep]);
    let set: Vec<&str> = effects.iter().flat_map(|e| ["--set", *e]).collect();
    let dir = reduce("scenes/three-beams-oblique.toml", "three-direction", &set);
    let r = run_json(&dir);
    assert_eq!(r["closed_points"], 36);
    // One joint per point; its u1, u2 and opening, the two outputs and the load (the
    // oblique tip force: a pattern of its own).
    assert_eq!(r["joints"], 36);
    assert_eq!(r["three_direction_joints"], 36);
    assert_eq!(r["retained_coordinates"], 36 * 3 + 3);
    let text = std::fs::read_to_string(dir.join("scene.toml")).unwrap();
    assert!(
        text.contains("normal = [0.0, 0.0, 1.0]\nnormal_stiffness = "),
        "{text}"
    );
    assert!(text.contains("normal_load_variation = true\ncoupled_slip = true"));
    let out = dir.join("run");
    let log = run_scene(&dir.join("scene.toml"), &out, &[sweep]);
    assert!(log.contains("7 of 7 frequencies converged"), "{log}");
    let reduced = out.join("results.csv");
    let against_fe = largest_difference(&fe.join("results.csv"), &reduced);
    let against_thesis = largest_difference(&thesis.join("results.csv"), &reduced);
    println!("reduced three-direction joints: {against_fe:.1e} from the FE balance, {against_thesis:.1e} from the thesis model");
    assert!(against_fe < 1e-4, "{against_fe}");
    assert!(against_thesis > 100.0 * against_fe, "{against_thesis}");
    // The joints' normal forces vary within the cycle (results.csv's ranges).
    let row = &rows(&reduced)[3];
    let (lo, hi) = (
        num(row, "lower.0_normal_force_min_N"),
        num(row, "lower.0_normal_force_max_N"),
    );
    assert!(lo < hi && lo >= 0.0, "{lo} {hi}");
    for effect in effects {
        let err = refused_backbone(&scene, effect);
        assert!(err.contains("are not carried"), "{err}");
    }
}

/// `jointlin backbone SCENE --set EFFECT`, expected to exit 2; its stderr.
fn refused_backbone(scene: &Path, effect: &str) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args([
            "backbone",
            scene.to_str().unwrap(),
            "--set",
            effect,
            "--out",
        ])
        .arg(tmp("refused-backbone"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{effect}");
    String::from_utf8_lossy(&out.stderr).to_string()
}

/// knife-coarse: points on the symmetry plane have their lateral direction held by the
/// plane's clamp (both nodes' y fixed): no row, no joint (a zero row made B K_s⁻¹ Bᵀ
/// singular). The reduced sweep (3 face loads: one load pattern) is the FE sweep's.
#[test]
fn held_contact_directions_carry_no_joint() {
    let dir = reduce("scenes/knife-coarse.toml", "knife", &[]);
    let r = run_json(&dir);
    assert_eq!(r["held_contact_directions"], 6);
    assert_eq!(r["joints"], 30);
    assert!(
        r["largest_relative_difference"].as_f64().unwrap() < 1e-9,
        "{r}"
    );
    let (fe, red) = (tmp("knife-fe"), dir.join("run"));
    let scene = repo("scenes/knife-coarse.toml");
    run_scene(&scene, &fe, &["iteration.tolerance=1e-10"]);
    run_scene(&dir.join("scene.toml"), &red, &[]);
    let (a, b) = (
        rows(&fe.join("results.csv")),
        rows(&red.join("results.csv")),
    );
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(y["status"], "converged");
        // Measured: 6.8e-6 (19 interior modes, the default band).
        for k in ["end_face_amp_mm", "blade_tip_amp_mm"] {
            assert!(
                (num(y, k) / num(x, k) - 1.0).abs() < 1e-4,
                "{k}: {x:?} {y:?}"
            );
        }
    }
}
