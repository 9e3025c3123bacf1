//! Scenes too big for the machine: `jointlin check` and `jointlin run` estimate the
//! memory from the scene's tables before allocating anything and refuse beyond the
//! available memory (or `JOINTLIN_MAX_MEMORY`) with exit code 2, `file:line:col`, the
//! key and the estimate — never an abort in an allocation or a panic.
//!
//! Before: `count = 1e9` made `check` abort allocating 8 GB of frequencies; `count` near
//! the largest integer panicked with "capacity overflow" (exit 101).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use jointlin_harness::fe::elements::box_mesh::box_mesh;
use jointlin_harness::fe::elements::ElementKind;

/// scenes/hard/stiffness-ratio.toml (two boxes in contact, 144 DOFs) with `from`
/// replaced by `to`, written to a fresh directory; the path and the 1-based line of `to`.
fn scene_with(name: &str, from: &str, to: &str) -> (PathBuf, usize) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/hard/stiffness-ratio.toml");
    let text = std::fs::read_to_string(src).unwrap();
    assert!(text.contains(from), "{from}");
    let text = text.replacen(from, to, 1);
    let line = text.lines().position(|l| l.starts_with(to)).unwrap() + 1;
    let dir = std::env::temp_dir().join(format!("jointlin-size-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    (path, line)
}

fn jointlin(args: &[&str], limit: Option<&str>) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_jointlin"));
    c.args(args);
    match limit {
        Some(l) => c.env("JOINTLIN_MAX_MEMORY", l),
        None => c.env_remove("JOINTLIN_MAX_MEMORY"),
    };
    c.output().unwrap()
}

/// `check` and `run` both exit 2 naming `file:line:1`, the key and an estimate in GB
/// above `at_least` GB; `run` writes nothing.
fn refused(path: &Path, line: usize, key: &str, limit: Option<&str>, at_least: f64) {
    let p = path.to_str().unwrap();
    let out_dir = path.with_file_name("out");
    for args in [
        vec!["check", p],
        vec!["run", p, "--out", out_dir.to_str().unwrap()],
    ] {
        let out = jointlin(&args, limit);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(&format!("{p}:{line}:1: key `{key}`")), "{err}");
        let gb: f64 = err
            .split("needs about ")
            .nth(1)
            .and_then(|r| r.split(" GB").next())
            .and_then(|g| g.parse().ok())
            .unwrap_or_else(|| panic!("no estimate in {err}"));
        assert!(gb >= at_least, "{gb} GB: {err}");
        assert!(err.contains("JOINTLIN_MAX_MEMORY"), "{err}");
        assert!(!out_dir.join("results.csv").exists());
    }
}

#[test]
fn a_billion_frequencies_are_refused_at_the_sweep_count() {
    let (path, line) = scene_with("1e9", "count = 12", "count = 1000000000");
    // 8 GB of frequencies alone; the results per frequency and contact point more.
    refused(&path, line, "sweep.count", Some("16G"), 16.0);
}

#[test]
fn the_largest_count_is_refused_against_the_machines_memory() {
    let (path, line) = scene_with("max", "count = 12", "count = 9223372036854775807");
    refused(&path, line, "sweep.count", None, 1e9);
}

#[test]
fn huge_divisions_are_refused_at_the_body() {
    let (path, line) = scene_with(
        "div",
        "divisions = [4, 2, 1]",
        "divisions = [2000, 2000, 2000]",
    );
    refused(&path, line, "bodies[0].divisions", None, 1e3);
    // Large enough to abort the mesh's allocations on a small machine (1.2e6 DOFs).
    let (path, line) = scene_with(
        "div2",
        "divisions = [4, 2, 1]",
        "divisions = [200, 100, 20]",
    );
    refused(&path, line, "bodies[0].divisions", Some("4G"), 4.0);
}

#[test]
fn the_limit_can_be_raised_and_a_bad_limit_is_named() {
    let (path, _) = scene_with("limit", "count = 12", "count = 13");
    let p = path.to_str().unwrap();
    let ok = jointlin(&["check", p], Some("1T"));
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let small = jointlin(&["check", p], Some("1M"));
    assert_eq!(small.status.code(), Some(2));
    let bad = jointlin(&["check", p], Some("lots"));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert_eq!(bad.status.code(), Some(2), "{err}");
    assert!(
        err.contains("JOINTLIN_MAX_MEMORY=`lots` is not a size"),
        "{err}"
    );
}

#[test]
fn every_scene_of_the_repository_passes_against_the_machines_memory() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut n = 0;
    for d in [dir.clone(), dir.join("hard")] {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "toml") {
                let out = jointlin(&["check", p.to_str().unwrap()], None);
                let err = String::from_utf8_lossy(&out.stderr);
                assert_eq!(out.status.code(), Some(0), "{}: {err}", p.display());
                n += 1;
            }
        }
    }
    assert!(n >= 15, "{n} scenes");
}

/// `check --forecast` forecasts the run's time from one factorization and solve timed on the
/// machine; the factorization counts it gives hold what the run then does
/// (three-beams-coarse, fast and thesis mode: the main sweep's count from run.json,
/// doubled for the plots' reference sweep the forecast includes).
#[test]
fn check_forecasts_the_factorizations_a_run_needs() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/three-beams-coarse.toml");
    let scene = scene.to_str().unwrap();
    for mode in ["fast", "thesis"] {
        let text = std::fs::read_to_string(scene)
            .unwrap()
            .replace("mode = \"fast\"", &format!("mode = \"{mode}\""));
        assert!(text.contains(&format!("mode = \"{mode}\"")), "{mode}");
        let dir =
            std::env::temp_dir().join(format!("jointlin-forecast-{}-{mode}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.toml");
        std::fs::write(&path, text).unwrap();
        let p = path.to_str().unwrap();
        let out = jointlin(&["check", "--forecast", p], None);
        let said = String::from_utf8_lossy(&out.stdout).to_string();
        assert!(out.status.success(), "{said}");
        let line = said
            .lines()
            .find(|l| l.starts_with("time forecast: one factorization of the dynamic stiffness"))
            .unwrap_or_else(|| panic!("{said}"));
        let range = line.split(" factorizations,").next().unwrap();
        let range = range.rsplit(": ").next().unwrap();
        let (lo, hi) = range.split_once('–').unwrap();
        let (lo, hi): (f64, f64) = (lo.parse().unwrap(), hi.parse().unwrap());
        let o = dir.join("out");
        let run = jointlin(
            &[
                "run",
                "--quiet",
                "--no-plots",
                "--out",
                o.to_str().unwrap(),
                p,
            ],
            None,
        );
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(o.join("run.json")).unwrap()).unwrap();
        let done = 2.0 * json["factorizations"].as_f64().unwrap();
        assert!(lo <= done && done <= hi, "{mode}: {lo}–{hi} against {done}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// The modal route's basis counts: mode shapes and residual columns are full vectors
/// (as many modes as asked, never more than the DOFs; 500 when not given), so 100 000
/// modes of a two-box scene of 340k DOFs (272 GB) are refused at `sweep.modes`, and a
/// deck's `*FREQUENCY` asking for as many of its 176k DOFs at its step.
#[test]
fn a_modal_basis_too_large_is_refused_at_its_mode_count() {
    let (path, _) = scene_with(
        "modal",
        "divisions = [4, 2, 1]",
        "divisions = [100, 50, 10]",
    );
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replacen("divisions = [4, 2, 1]", "divisions = [100, 50, 10]", 1)
        .replacen(
            "count = 12",
            "count = 12\nmethod = \"modal\"\nmodes = 100000",
            1,
        );
    std::fs::write(&path, &text).unwrap();
    let line = text.lines().position(|l| l.starts_with("modes =")).unwrap() + 1;
    refused(&path, line, "sweep.modes", None, 100.0);
    // A deck of 61 × 31 × 31 nodes asking for 1e6 modes (capped at its DOFs: 245 GB).
    // (The harness's own box mesher writes it: the estimate, not the mesh, is tested.)
    let mesh = box_mesh(ElementKind::C3D8, [60.0, 30.0, 30.0], [60, 30, 30], 0.0, 0);
    let mut deck =
        String::from("*HEADING\nbig\n** jointlin units: length=mm force=N time=s mass=t\n*NODE\n");
    for (n, x) in mesh.nodes.iter().enumerate() {
        deck += &format!("{}, {}, {}, {}\n", n + 1, x[0], x[1], x[2]);
    }
    deck += "*ELEMENT, TYPE=C3D8, ELSET=ALL\n";
    for (e, nodes) in mesh.elements.iter().enumerate() {
        let ids: Vec<String> = nodes.iter().map(|n| (n + 1).to_string()).collect();
        deck += &format!("{}, {}\n", e + 1, ids.join(", "));
    }
    deck += "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n7.85e-9\n*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n*BOUNDARY\n1, 1, 3\n";
    let line = deck.lines().count() + 1;
    deck += "*STEP\n*FREQUENCY\n1000000\n*END STEP\n";
    let p = path.with_file_name("modal.inp");
    std::fs::write(&p, &deck).unwrap();
    let out = jointlin(&["check", p.to_str().unwrap()], None);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains(&format!("modal.inp:{line}: *FREQUENCY"))
            && err.contains("175863 mode shapes of 175863 DOFs"),
        "{err}"
    );
}
