//! run.json's provenance head (docs/outputs.md): the same keys first in every command's
//! run.json, the library's ABI version as the header states it, and every input file
//! read — the deck and its `*INCLUDE`, the scene as on disk before `--set` — with the
//! SHA-256 that coreutils' `sha256sum` prints for it. A study that fails leaves no
//! run.json (an earlier one is removed before it starts).

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use jointlin_harness::validate::matrices_ccx::{deck, tip_node};

const HEAD: [&str; 6] = [
    "schema_version",
    "command",
    "jointlin",
    "command_line",
    "written_at",
    "inputs",
];

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-provenance-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs jointlin in `cwd`; panics with its stderr unless it exits with `code`.
fn jointlin(cwd: &Path, args: &[&str], code: i32) {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .current_dir(cwd)
        .args(args)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(code),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `sha256sum FILE`'s digest.
fn sha256sum(file: &Path) -> String {
    let out = Command::new("sha256sum").arg(file).output().unwrap();
    assert!(out.status.success());
    String::from_utf8(out.stdout).unwrap()[..64].to_string()
}

/// The run.json in `out`, its head checked: keys first and in order, schema 1, `command`,
/// the ABI version of include/jointlin.h, a UTC time, and `inputs` equal to `files`
/// (names relative to `cwd`) with their sizes and digests.
fn checked_head(cwd: &Path, out: &str, command: &str, files: &[&str]) -> Value {
    let text = std::fs::read_to_string(cwd.join(out).join("run.json")).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    let keys: Vec<&str> = json
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(keys[..6], HEAD, "{keys:?}");
    assert_eq!(json["schema_version"], 1);
    assert_eq!(json["command"], command);
    let header = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../include/jointlin.h"),
    )
    .unwrap();
    let part = |name: &str| {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("#define {name} ")))
            .unwrap()
            .trim()
            .to_string()
    };
    assert_eq!(
        json["jointlin"]["library_abi"],
        format!(
            "{}.{}",
            part("JOINTLIN_ABI_VERSION_MAJOR"),
            part("JOINTLIN_ABI_VERSION_MINOR")
        )
    );
    let at = json["written_at"].as_str().unwrap();
    assert!(
        at.len() == 20 && at.ends_with('Z') && at.starts_with("20"),
        "{at}"
    );
    let inputs = json["inputs"].as_array().unwrap();
    let listed: Vec<&str> = inputs.iter().map(|i| i["file"].as_str().unwrap()).collect();
    assert_eq!(listed, files);
    for i in inputs {
        let f = cwd.join(i["file"].as_str().unwrap());
        assert_eq!(i["sha256"], sha256sum(&f), "{}", f.display());
        assert_eq!(i["bytes"], std::fs::metadata(&f).unwrap().len());
    }
    json
}

#[test]
fn a_deck_run_lists_the_deck_and_its_include_with_their_digests() {
    let d = dir("deck");
    let tip = tip_node();
    std::fs::write(d.join("tip.inp"), format!("*NSET, NSET=TIPN\n{tip}\n")).unwrap();
    let text = deck(
        "*INCLUDE, INPUT=tip.inp\n*STEP, PERTURBATION\n*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR\n100., 300., 3\n*CLOAD\nTIPN, 3, 1.\n*NODE PRINT, NSET=TIPN\nU\n*END STEP\n",
    )
    .replacen(
        "*HEADING\n",
        "*HEADING\n** jointlin units: length=mm force=N time=s mass=t\n",
        1,
    );
    std::fs::write(d.join("beam.inp"), text).unwrap();
    jointlin(
        &d,
        &["run", "beam.inp", "--out", "out", "--quiet", "--no-plots"],
        0,
    );
    let json = checked_head(&d, "out", "run", &["beam.inp", "tip.inp"]);
    let line: Vec<&str> = json["command_line"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    assert_eq!(
        line[1..],
        ["run", "beam.inp", "--out", "out", "--quiet", "--no-plots"]
    );
    // The body follows the head.
    assert!(json["static_step"]["backward_error"].is_number());
    // A scene over the deck: the scene first, then the deck and its include.
    std::fs::write(
        d.join("over.toml"),
        "model = \"beam.inp\"\n[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n",
    )
    .unwrap();
    jointlin(
        &d,
        &["run", "over.toml", "--out", "over", "--quiet", "--no-plots"],
        0,
    );
    checked_head(&d, "over", "run", &["over.toml", "beam.inp", "tip.inp"]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_scene_is_listed_as_on_disk_and_every_command_writes_the_same_head() {
    let d = dir("scene");
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    for s in ["duffing.toml", "jenkins-chain.toml"] {
        std::fs::copy(scenes.join(s), d.join(s)).unwrap();
    }
    // --set changes the text run.json echoes, not the file it lists.
    jointlin(
        &d,
        &[
            "run",
            "duffing.toml",
            "--out",
            "run",
            "--quiet",
            "--no-plots",
            "--set",
            "title='set on the command line'",
        ],
        0,
    );
    let json = checked_head(&d, "run", "run", &["duffing.toml"]);
    assert!(json["scene"]["text"]
        .as_str()
        .unwrap()
        .contains("set on the command line"));
    // The time domain's run.json, written last as the frequency domain's.
    std::fs::copy(scenes.join("block-stick.toml"), d.join("block-stick.toml")).unwrap();
    jointlin(
        &d,
        &[
            "run",
            "block-stick.toml",
            "--time-domain",
            "--out",
            "td",
            "--quiet",
        ],
        0,
    );
    let json = checked_head(&d, "td", "run --time-domain", &["block-stick.toml"]);
    assert_eq!(json["frequency_unit"], "1/s");
    // points_time.csv names each point's node and frame as points.csv does: an id of the
    // scene's numbering and an orthonormal frame (n, t1, t2).
    let points = std::fs::read_to_string(d.join("td/points_time.csv")).unwrap();
    let mut lines = points.lines();
    let header = lines.next().unwrap();
    assert!(
        header.ends_with(",node,n_x,n_y,n_z,t1_x,t1_y,t1_z,t2_x,t2_y,t2_z"),
        "{header}"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').skip(7).map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(!rows.is_empty());
    for r in &rows {
        assert!(r[0] >= 1.0 && r[0].fract() == 0.0, "node {}", r[0]);
        let axis = |k: usize| nalgebra::Vector3::new(r[1 + 3 * k], r[2 + 3 * k], r[3 + 3 * k]);
        let (n, t1, t2) = (axis(0), axis(1), axis(2));
        for (a, b, want) in [
            (n, n, 1.0),
            (t1, t1, 1.0),
            (t2, t2, 1.0),
            (n, t1, 0.0),
            (n, t2, 0.0),
        ] {
            assert!((a.dot(&b) - want).abs() < 1e-9, "{r:?}");
        }
    }
    // A lumped scene's run, a backbone, a study.
    jointlin(
        &d,
        &[
            "run",
            "jenkins-chain.toml",
            "--out",
            "lumped",
            "--quiet",
            "--no-plots",
        ],
        0,
    );
    checked_head(&d, "lumped", "run", &["jenkins-chain.toml"]);
    jointlin(
        &d,
        &["backbone", "jenkins-chain.toml", "--out", "backbone"],
        0,
    );
    checked_head(&d, "backbone", "backbone", &["jenkins-chain.toml"]);
    // A [[matrices]] model: the scene, then its mass, stiffness and DOF files.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    std::fs::create_dir_all(d.join("beam-cb")).unwrap();
    for f in [
        "beam-cb.toml",
        "beam-cb/M.mtx",
        "beam-cb/K.mtx",
        "beam-cb/dofs.csv",
    ] {
        std::fs::copy(root.join(f), d.join(f)).unwrap();
    }
    let cb = [
        "--out",
        "cb",
        "--quiet",
        "--no-plots",
        "--set",
        "sweep.count=3",
    ];
    jointlin(&d, &[&["run", "beam-cb.toml"][..], &cb[..]].concat(), 0);
    let files = [
        "beam-cb.toml",
        "beam-cb/M.mtx",
        "beam-cb/K.mtx",
        "beam-cb/dofs.csv",
    ];
    let json = checked_head(&d, "cb", "run", &files);
    // The body names what the FE run's names (model counts, mode, effects, convergence).
    assert_eq!(json["model"]["dofs"], 18);
    assert_eq!(json["model"]["joints"], 1);
    assert_eq!(json["mode"], "fast");
    assert_eq!(json["all_converged"], true);
    assert!(json["effects"]["contact_damping"].is_boolean());
    assert!(json["timings_s"]["sweep"].as_f64().unwrap() >= 0.0);
    jointlin(&d, &["effects", "duffing.toml", "--out", "effects"], 0);
    let json = checked_head(&d, "effects", "effects", &["duffing.toml"]);
    assert!(json["files"]
        .as_array()
        .unwrap()
        .iter()
        .any(|f| f == "effects.md"));
    // A study that fails leaves no run.json, not even an earlier one.
    std::fs::create_dir_all(d.join("failed")).unwrap();
    std::fs::write(d.join("failed/run.json"), "{}").unwrap();
    jointlin(&d, &["tradeoff", "duffing.toml", "--out", "failed"], 1);
    assert!(!d.join("failed/run.json").exists());
    let _ = std::fs::remove_dir_all(&d);
}
