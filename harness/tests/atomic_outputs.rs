//! Outputs are atomic: a file appears under its name only when complete, run.json last
//! marks a complete run, and a run that is interrupted (SIGINT) or fails while writing
//! leaves no run.json and says so. Through the `jointlin` binary.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
}

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-atomic-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn jointlin(scene: &Path, out: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_jointlin"));
    c.args(["run", "--quiet", "--out"]).arg(out).arg(scene);
    c
}

/// Every finished CSV in `dir` ends with a newline and has as many fields in each line as
/// in its header (no line cut short); no file is empty.
fn assert_whole(dir: &Path, tag: &str) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let text = std::fs::read_to_string(&p).unwrap();
        assert!(!text.is_empty(), "{tag}: {name} empty");
        if name.ends_with(".svg") {
            assert!(
                text.trim_end().ends_with("</svg>"),
                "{tag}: {name} cut short"
            );
        }
        if name.ends_with(".csv") {
            assert!(text.ends_with('\n'), "{tag}: {name} cut short");
            let mut lines = text.lines();
            let n = lines.next().unwrap().split(',').count();
            for l in lines {
                assert_eq!(l.split(',').count(), n, "{tag}: {name}: `{l}`");
            }
        }
    }
}

/// A failure while writing (points.csv cannot be renamed into place: a directory holds
/// its name) ends the run with an error naming the file, leaves no run.json (the earlier
/// run's is removed too) and no temporary file.
#[test]
fn a_failure_while_writing_leaves_no_marker() {
    let d = scratch("fail");
    let out = d.join("out");
    let block = scene("block-stick.toml");
    let ok = jointlin(&block, &out).output().unwrap();
    assert!(ok.status.success());
    assert!(out.join("run.json").exists());
    std::fs::remove_file(out.join("points.csv")).unwrap();
    std::fs::create_dir(out.join("points.csv")).unwrap();
    let o = jointlin(&block, &out).output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{stderr}");
    assert!(stderr.contains("points.csv"), "{stderr}");
    assert!(
        !out.join("run.json").exists(),
        "an earlier run's marker survived"
    );
    for e in std::fs::read_dir(&out).unwrap() {
        let name = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!name.ends_with(".partial"), "{name} left behind");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// SIGINT at many moments of a three-beams-coarse run (points.csv 0.6 MB): during the
/// sweep, as the first output appears and a little after. Either the run finished
/// (run.json and every file whole) or it ended with 130, said "interrupted" and left no
/// run.json; a finished file is never cut short.
#[test]
fn an_interrupted_run_leaves_nothing_that_looks_complete() {
    let d = scratch("sigint");
    let s = scene("three-beams-coarse.toml");
    let mut interrupted = 0;
    let mut while_writing = 0;
    for (k, delay_us) in [
        None,
        Some(0),
        Some(200),
        Some(1000),
        Some(3000),
        Some(10_000),
    ]
    .into_iter()
    .enumerate()
    {
        let out = d.join(format!("out{k}"));
        std::fs::create_dir_all(&out).unwrap();
        // An earlier complete run's marker, which the interrupted run must remove.
        std::fs::write(out.join("run.json"), "{}").unwrap();
        let child = jointlin(&s, &out)
            .stderr(Stdio::piped())
            .stdout(Stdio::null())
            .spawn()
            .unwrap();
        let t = Instant::now();
        let mut writing = false;
        match delay_us {
            // During the sweep.
            None => std::thread::sleep(Duration::from_millis(300)),
            // After the first output file (temporary or final) appears.
            Some(us) => {
                while t.elapsed() < Duration::from_secs(60) {
                    let any = std::fs::read_dir(&out).unwrap().any(|e| {
                        let n = e.unwrap().file_name().to_string_lossy().into_owned();
                        n != "run.json"
                    });
                    if any {
                        writing = true;
                        break;
                    }
                    std::thread::sleep(Duration::from_micros(100));
                }
                std::thread::sleep(Duration::from_micros(us));
            }
        }
        let _ = Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status();
        let o = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        let tag = format!("delay {delay_us:?}");
        if out.join("run.json").exists() {
            assert!(o.status.success(), "{tag}: {stderr}");
            let json: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(out.join("run.json")).unwrap())
                    .unwrap();
            assert!(
                json["converged"].is_array(),
                "{tag}: the old marker survived"
            );
        } else {
            assert_eq!(o.status.code(), Some(130), "{tag}: {stderr}");
            assert!(
                stderr.contains("interrupted") && stderr.contains("no complete run"),
                "{tag}: {stderr}"
            );
            interrupted += 1;
            while_writing += usize::from(writing);
        }
        assert_whole(&out, &tag);
    }
    // The sweep takes > 300 ms, so at least that one is interrupted; report the rest.
    eprintln!("interrupted {interrupted} of 6 runs, {while_writing} while writing");
    assert!(interrupted >= 1);
    std::fs::remove_dir_all(&d).unwrap();
}

/// SIGINT as run.json appears (block-stick): the marker means the run is complete, so the
/// run ends with 0 and every file whole; if the signal still found the process, it said
/// the run was complete (an interrupt during the marker's rename waits for it).
#[test]
fn an_interrupt_after_the_marker_keeps_the_complete_run() {
    let d = scratch("marker");
    let s = scene("block-stick.toml");
    for k in 0..5 {
        let out = d.join(format!("out{k}"));
        let child = jointlin(&s, &out)
            .stderr(Stdio::piped())
            .stdout(Stdio::null())
            .spawn()
            .unwrap();
        let t = Instant::now();
        while !out.join("run.json").exists() && t.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_micros(50));
        }
        let _ = Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status();
        let o = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(out.join("run.json").exists(), "run {k}: {stderr}");
        assert!(o.status.success(), "run {k}: {stderr}");
        if stderr.contains("interrupted") {
            assert!(stderr.contains("was complete"), "run {k}: {stderr}");
        }
        assert_whole(&out, &format!("run {k}"));
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// A second run into the same directory leaves only its own outputs: the first run's
/// field and contact maps at another frequency, its plots and the reference sweep they
/// need (the second has `--no-plots`) are gone; a file of the user's stays.
#[test]
fn a_second_run_leaves_no_outputs_of_the_first() {
    let d = scratch("rerun");
    let base = std::fs::read_to_string(scene("three-beams-coarse.toml")).unwrap();
    let out = d.join("out");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    for (k, (freq, plots)) in [(1000.0, true), (1100.0, false)].iter().enumerate() {
        let p = d.join(format!("s{k}.toml"));
        std::fs::write(
            &p,
            format!("{base}\n[field_output]\nfrequencies = [{freq:.1}]\n"),
        )
        .unwrap();
        let mut c = jointlin(&p, &out);
        if !plots {
            c.arg("--no-plots");
        }
        let o = c.output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "field_1100.000_Hz.vtu",
            "fields.pvd",
            "notes.txt",
            "points.csv",
            "results.csv",
            "run.json",
            "stick_slip.csv",
        ],
        "{names:?}"
    );
}

/// `--out` naming a file: a message that says so (was "File exists (os error 17)"), the
/// file untouched.
#[test]
fn an_output_directory_that_is_a_file_is_named_as_such() {
    let d = scratch("out-file");
    let out = d.join("results.csv");
    std::fs::write(&out, "mine").unwrap();
    let o = jointlin(&scene("block-stick.toml"), &out).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("results.csv: is a file, not a directory"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "mine");
}
