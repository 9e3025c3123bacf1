//! `jointlin reduce` against the full FE sweep, side by side in one run on this machine:
//! per scene the FE fast sweep (consistent to 1e-10, so that the difference is the
//! reduction's), then per interior-mode count the reduction and the reduced scene's
//! first-order sweep (`jointlin run` of the written scene.toml). Wall times of the
//! commands as a user runs them (in this process, plots off); the last columns are the
//! largest relative difference of the outputs' amplitudes over all frequencies and the
//! frequencies converged.
//!
//! Run: `cargo run --release -p jointlin-harness --example reduce_bench`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use jointlin_harness::cli::run_args;

/// Runs `jointlin ARGS` in this process; its wall time (s).
fn jointlin(args: &[&str]) -> Result<f64, String> {
    let t = Instant::now();
    let code = run_args(std::iter::once("jointlin").chain(args.iter().copied()));
    match code {
        0 => Ok(t.elapsed().as_secs_f64()),
        c => Err(format!("jointlin {args:?} exited {c}")),
    }
}

type Row = BTreeMap<String, String>;

fn rows(path: &Path) -> Result<Vec<Row>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text.lines();
    let head: Vec<String> = lines
        .next()
        .ok_or("empty results")?
        .split(',')
        .map(String::from)
        .collect();
    Ok(lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect())
}

/// Largest relative difference of the output amplitudes both tables have, and the rows
/// of `b` that converged.
fn compare(a: &[Row], b: &[Row]) -> (f64, usize) {
    let mut worst = 0.0f64;
    for (x, y) in a.iter().zip(b) {
        for (k, v) in x.iter().filter(|(k, _)| k.contains("_amp_")) {
            let (Some(p), Some(q)) = (
                v.parse::<f64>().ok(),
                y.get(k).and_then(|s| s.parse::<f64>().ok()),
            ) else {
                continue;
            };
            worst = worst.max((q / p - 1.0).abs());
        }
    }
    let converged = b.iter().filter(|r| r["status"] == "converged").count();
    (worst, converged)
}

fn main() -> Result<(), String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let tmp = std::env::temp_dir().join(format!("jointlin-reduce-bench-{}", std::process::id()));
    let out = |name: &str| -> PathBuf { tmp.join(name) };
    println!("| scene | closed points | interior modes | FE sweep [s] | reduce [s] | reduced sweep [s] | frequencies converged | largest relative difference |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|");
    // Per scene: the FE sweep's overrides (the tolerance; a scene over a deck may have
    // no [iteration] table; no field output) and the interior-mode counts.
    let cases: [(&str, Vec<&str>, Vec<&str>); 2] = [
        (
            "three-beams-coarse.toml",
            vec!["iteration.tolerance=1e-10"],
            vec!["4", "8", "16", "32"],
        ),
        (
            "bolted-lap.toml",
            vec!["iteration={ tolerance = 1e-10 }", "field_output="],
            vec!["8", "16"],
        ),
    ];
    for (scene, sets, counts) in cases {
        let path = root.join("scenes").join(scene);
        let path = path.to_str().ok_or("path")?;
        let fe = out(&format!("{scene}-fe"));
        let fe_dir = fe.to_str().ok_or("path")?;
        let mut args = vec!["run", path, "--out", fe_dir, "--no-plots", "--quiet"];
        for s in &sets {
            args.extend(["--set", s]);
        }
        let fe_s = jointlin(&args)?;
        let full = rows(&fe.join("results.csv"))?;
        for modes in counts {
            let dir = out(&format!("{scene}-{modes}"));
            let d = dir.to_str().ok_or("path")?;
            let reduce_s = jointlin(&["reduce", path, "--out", d, "--modes", modes, "--quiet"])?;
            let json: serde_json::Value = serde_json::from_str(
                &std::fs::read_to_string(dir.join("run.json")).map_err(|e| e.to_string())?,
            )
            .map_err(|e| e.to_string())?;
            let run = dir.join("run");
            let scene_toml = dir.join("scene.toml");
            let run_s = jointlin(&[
                "run",
                scene_toml.to_str().ok_or("path")?,
                "--out",
                run.to_str().ok_or("path")?,
                "--no-plots",
                "--quiet",
            ])?;
            let (worst, converged) = compare(&full, &rows(&run.join("results.csv"))?);
            println!(
                "| {scene} | {} | {modes} | {fe_s:.2} | {reduce_s:.2} | {run_s:.2} | {converged}/{} | {worst:.1e} |",
                json["closed_points"],
                full.len()
            );
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);
    Ok(())
}
