//! A mode-based steady-state deck run by CalculiX and by jointlin, side by side in one run
//! on this machine: the tied tet-on-hex blocks of `validate::tied_blocks` with a
//! `*FREQUENCY, STORAGE=YES` step of 20 modes and a `*STEADY STATE DYNAMICS` step without
//! DIRECT (FREQUENCY SCALE=LINEAR, 5 points per eigenfrequency interval from 100 Hz to
//! 20 kHz, `*MODAL DAMPING, RAYLEIGH`), 1 N along z at the block's far corner. Wall
//! times from reading the deck to the FRF (ccx as a user runs it, `ccx -i JOB`; jointlin
//! in this process, no output files); the last column is the largest relative difference
//! of the corner's amplitude over the frequencies both list.
//!
//! Run: `cargo run --release -p jointlin-harness --example modal_deck_bench`.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use jointlin_harness::input;
use jointlin_harness::run::{run, Extras};
use jointlin_harness::validate::ccx::{ccx_missing, parse_steady_state};
use jointlin_harness::validate::tied_blocks::tied_blocks_deck;

/// The node with the largest x (then y, then z) of the deck's `*NODE` lines.
fn far_corner(deck: &str) -> Option<usize> {
    let mut best: Option<(usize, [f64; 3])> = None;
    let mut inside = false;
    for line in deck.lines() {
        if line.starts_with('*') {
            inside = line.to_ascii_uppercase().starts_with("*NODE") && !line.contains("NSET=CLAMP");
            continue;
        }
        if !inside {
            continue;
        }
        let v: Vec<f64> = line
            .split(',')
            .filter_map(|f| f.trim().parse().ok())
            .collect();
        if v.len() == 4 {
            let p = [v[1], v[2], v[3]];
            if best.is_none_or(|(_, q)| p > q) {
                best = Some((v[0] as usize, p));
            }
        }
    }
    best.map(|(id, _)| id)
}

fn main() -> Result<(), String> {
    if let Some(why) = ccx_missing() {
        return Err(why);
    }
    let dir =
        std::env::temp_dir().join(format!("jointlin-modal-deck-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    println!("| deck | free DOFs | frequencies | ccx (s) | jointlin (s) | jointlin / ccx | largest relative difference |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for r in [3, 4, 5] {
        let (base, dofs) = tied_blocks_deck(r, 20);
        let corner = far_corner(&base).ok_or("no nodes")?;
        let step = format!(
            "*NSET, NSET=CORNER\n{corner}\n*STEP\n*FREQUENCY, STORAGE=YES\n20\n*END STEP\n\
             *STEP\n*STEADY STATE DYNAMICS, FREQUENCY SCALE=LINEAR\n100., 20000., 5\n\
             *MODAL DAMPING, RAYLEIGH\n,,100.,1e-7\n*CLOAD\nCORNER, 3, 1.\n\
             *NODE PRINT, NSET=CORNER\nU\n*END STEP\n"
        );
        let deck = base.replace("*STEP\n*FREQUENCY\n20\n*END STEP", &step);
        let name = format!("modal-{r}");
        let path = dir.join(format!("{name}.inp"));
        std::fs::write(&path, &deck).map_err(|e| e.to_string())?;

        let t = Instant::now();
        let out = Command::new("ccx")
            .arg("-i")
            .arg(&name)
            .current_dir(&dir)
            .output()
            .map_err(|e| format!("ccx: {e}"))?;
        let t_ccx = t.elapsed().as_secs_f64();
        if let Some(l) = String::from_utf8_lossy(&out.stdout)
            .lines()
            .find(|l| l.contains("*ERROR"))
        {
            return Err(format!("ccx: {l}"));
        }
        let dat =
            std::fs::read_to_string(dir.join(format!("{name}.dat"))).map_err(|e| e.to_string())?;
        let ccx = parse_steady_state(&dat, corner);

        let t = Instant::now();
        let scene = input::load(Path::new(&path))
            .map_err(|e| e.to_string())?
            .into_scene();
        let r_ours = run(&scene, Extras::default(), &|_, _, _| {}).map_err(|e| e.to_string())?;
        let t_ours = t.elapsed().as_secs_f64();
        let k = (r_ours.problem.outputs.iter())
            .position(|o| o.name.ends_with("_u3"))
            .ok_or("no u3 output")?;
        let mut worst = 0.0f64;
        let mut shared = 0;
        for (i, f) in r_ours.main.freqs.iter().enumerate() {
            if let Some((_, u)) = ccx.iter().find(|(fc, _)| (fc / f - 1.0).abs() < 1e-6) {
                let ours = r_ours.main.outputs[i][k].norm();
                worst = worst.max((ours / u[2].norm() - 1.0).abs());
                shared += 1;
            }
        }
        println!(
            "| tied blocks, level {r} | {dofs} | {shared} of {} | {t_ccx:.2} | {t_ours:.2} | {:.2} | {worst:.1e} |",
            r_ours.main.freqs.len(),
            t_ours / t_ccx
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
