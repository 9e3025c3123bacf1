//! Progress in a batch job (`jointlin run SCENE > log 2>&1`): off a terminal the run
//! prints plain lines — one as a stage starts (the build, the static step, the sweep;
//! at most one a second) and one at least every `JOINTLIN_PROGRESS_SECONDS` while a
//! stage runs — each with the elapsed time; `--quiet` prints none.

use std::path::Path;
use std::process::Command;

/// The progress lines (`[   1.2 s] …`) of a run of `scene` (and `extra` arguments) with
/// stderr a pipe, and the elapsed seconds each states.
fn progress_lines(scene: &str, extra: &[&str], interval: &str, quiet: bool) -> Vec<(f64, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::env::temp_dir().join(format!(
        "jointlin-batch-progress-{}-{quiet}",
        std::process::id()
    ));
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_jointlin"));
    cmd.args(["run", root.join(scene).to_str().unwrap(), "--out"])
        .arg(&out)
        .arg("--no-plots")
        .args(extra)
        .env("JOINTLIN_PROGRESS_SECONDS", interval);
    if quiet {
        cmd.arg("--quiet");
    }
    let run = cmd.output().unwrap();
    let _ = std::fs::remove_dir_all(&out);
    let log = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{log}");
    log.lines()
        .filter_map(|l| {
            let rest = l.strip_prefix('[')?;
            let (t, text) = rest.split_once(" s] ")?;
            Some((t.trim().parse().ok()?, text.to_string()))
        })
        .collect()
}

#[test]
fn a_batch_run_prints_each_stage_and_a_line_every_interval() {
    let lines = progress_lines("scenes/three-beams-coarse.toml", &[], "0.05", false);
    let text: Vec<&str> = lines.iter().map(|(_, l)| l.as_str()).collect();
    // The first stage at once; stages that follow within a second share its line.
    assert_eq!(text[0], "building the model", "{text:?}");
    assert!(
        text.iter().any(|l| l.starts_with("frequency: ")),
        "{text:?}"
    );
    // The first line at once, then none more than a few intervals apart (a tick every
    // quarter interval; 0.5 s leaves room for a loaded machine).
    assert!(lines[0].0 < 0.5, "{lines:?}");
    for w in lines.windows(2) {
        assert!(w[1].0 - w[0].0 < 0.5, "{:?} → {:?}", w[0], w[1]);
    }
    // Steps counted with the time left while the sweep runs.
    assert!(text.iter().any(|l| l.contains("s left")), "{text:?}");
    assert!(progress_lines("scenes/three-beams-coarse.toml", &[], "0.05", true).is_empty());
}

#[test]
fn every_pass_of_a_multi_pass_run_gets_its_time_left() {
    // Thesis mode runs the frequencies in passes, each counting from 1 again: the time
    // left is measured from where each pass starts, not from the first.
    let lines = progress_lines(
        "scenes/three-beams-coarse.toml",
        &["--set", "iteration.mode=thesis"],
        "0.02",
        false,
    );
    let later: Vec<&String> = lines
        .iter()
        .map(|(_, l)| l)
        .filter(|l| l.starts_with("pass ") && !l.starts_with("pass 1 "))
        .collect();
    assert!(later.iter().any(|l| l.contains("s left")), "{lines:?}");
}

/// The progress lines' texts of `jointlin ARGS` with stderr a pipe.
fn stage_lines(args: &[&str]) -> Vec<String> {
    let run = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .env("JOINTLIN_PROGRESS_SECONDS", "0.05")
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{args:?}: {log}");
    log.lines()
        .filter_map(|l| Some(l.strip_prefix('[')?.split_once(" s] ")?.1.to_string()))
        .collect()
}

/// `modes`, `reduce` and `backbone` say in a batch log what they are doing from the
/// start (the static step and the eigen solver of a large model take minutes), and the
/// backbone counts its amplitudes; `--quiet` prints none of it.
#[test]
fn modes_reduce_and_backbone_print_their_stages() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = root.join("scenes/three-beams-coarse.toml");
    let scene = scene.to_str().unwrap();
    let out = std::env::temp_dir().join(format!("jointlin-stages-{}", std::process::id()));
    let (r, b) = (out.join("reduce"), out.join("backbone"));
    let (r, b) = (r.to_str().unwrap(), b.to_str().unwrap());
    let cases: [(Vec<&str>, &str); 3] = [
        (vec!["modes", scene], "stuck modes: building the model"),
        (vec!["reduce", scene, "--out", r], "building the model"),
        (
            vec!["backbone", scene, "--out", b],
            "building the model (an FE model",
        ),
    ];
    for (args, first) in &cases {
        let lines = stage_lines(args);
        assert!(
            lines.first().is_some_and(|l| l.starts_with(first)),
            "{args:?}: {lines:?}"
        );
        let mut quiet = args.clone();
        quiet.push("--quiet");
        assert!(stage_lines(&quiet).is_empty(), "{quiet:?}");
    }
    let lines = stage_lines(&cases[2].0);
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("first-order backbone: modal amplitudes")),
        "{lines:?}"
    );
    let _ = std::fs::remove_dir_all(&out);
}
