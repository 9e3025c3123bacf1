//! What `jointlin modes` costs against CalculiX's `*FREQUENCY` on the same decks, in one
//! run on this machine: tied tet-on-hex blocks of growing size
//! (`validate::tied_blocks`) and, when given, further decks of the user's (each with a
//! `*FREQUENCY` step; the deck's own count of modes is asked of both). Wall times: ccx
//! as a user runs it (`ccx -i JOB`, its default threads), jointlin in this process from
//! reading the deck to the modes (static step and stuck stiffness included; no output
//! files). The last column is the largest relative difference of the frequencies.
//!
//! Run: `cargo run --release -p jointlin-harness --example modes_bench [-- DECK.inp ...]`.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use jointlin_harness::input;
use jointlin_harness::solve::modal_stuck::{stuck_modes, ModeCount};
use jointlin_harness::validate::ccx::{ccx_missing, parse_frequencies};
use jointlin_harness::validate::tied_blocks::tied_blocks_deck;

/// Modes asked of the generated decks.
const MODES: usize = 10;

/// ccx's frequencies (Hz) of `deck` and its wall time (s).
fn ccx(deck: &Path) -> Result<(Vec<f64>, f64), String> {
    let dir = deck.parent().expect("deck in a directory");
    let job = deck.file_stem().expect("deck name").to_string_lossy();
    let t = Instant::now();
    let out = Command::new("ccx")
        .arg("-i")
        .arg(job.as_ref())
        .current_dir(dir)
        .output()
        .map_err(|e| format!("ccx: {e}"))?;
    let seconds = t.elapsed().as_secs_f64();
    let log = String::from_utf8_lossy(&out.stdout);
    if let Some(line) = log.lines().find(|l| l.contains("*ERROR")) {
        return Err(format!("ccx on {}: {}", deck.display(), line.trim()));
    }
    let dat = dir.join(format!("{job}.dat"));
    let text = std::fs::read_to_string(&dat).map_err(|e| format!("{}: {e}", dat.display()))?;
    Ok((parse_frequencies(&text), seconds))
}

/// jointlin's frequencies (Hz) of `deck`, its free DOFs and wall time (s).
fn jointlin(deck: &Path) -> Result<(Vec<f64>, usize, f64), String> {
    let t = Instant::now();
    let scene = input::load(deck).map_err(|e| e.to_string())?.into_scene();
    let count = (scene.deck.as_ref())
        .and_then(|d| d.frequency_modes())
        .unwrap_or(MODES);
    let m = stuck_modes(&scene, ModeCount::Exactly(count))?;
    let seconds = t.elapsed().as_secs_f64();
    Ok((m.band.modes.frequencies_hz(), m.problem.sys.k.n(), seconds))
}

fn main() -> Result<(), String> {
    if let Some(why) = ccx_missing() {
        return Err(why);
    }
    let dir = std::env::temp_dir().join(format!("jointlin-modes-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let mut decks: Vec<(String, PathBuf)> = Vec::new();
    for r in [2, 3, 4, 5] {
        let (text, _) = tied_blocks_deck(r, MODES);
        let path = dir.join(format!("tied-blocks-{r}.inp"));
        std::fs::write(&path, text).map_err(|e| e.to_string())?;
        decks.push((format!("tied blocks, level {r}"), path));
    }
    for arg in std::env::args().skip(1) {
        let from = PathBuf::from(&arg);
        let name = from.file_name().ok_or(format!("{arg}: no file name"))?;
        let to = dir.join(name);
        std::fs::copy(&from, &to).map_err(|e| format!("{arg}: {e}"))?;
        // A deck's *INCLUDE files sit beside it.
        if let Some(parent) = from.parent() {
            for entry in std::fs::read_dir(parent)
                .map_err(|e| e.to_string())?
                .flatten()
            {
                let p = entry.path();
                if p.extension().is_some_and(|e| e == "inp") && p != from {
                    let _ = std::fs::copy(&p, dir.join(entry.file_name()));
                }
            }
        }
        decks.push((name.to_string_lossy().into_owned(), to));
    }
    println!("| deck | free DOFs | modes | ccx (s) | jointlin (s) | jointlin / ccx | largest relative difference |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for (name, path) in decks {
        let (f_ccx, t_ccx) = ccx(&path)?;
        let (f_ours, dofs, t_ours) = jointlin(&path)?;
        let n = f_ccx.len().min(f_ours.len());
        let diff = (0..n)
            .map(|i| ((f_ours[i] - f_ccx[i]) / f_ccx[i]).abs())
            .fold(0.0, f64::max);
        println!(
            "| {name} | {dofs} | {n} | {t_ccx:.2} | {t_ours:.2} | {:.2} | {diff:.1e} |",
            t_ours / t_ccx
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
