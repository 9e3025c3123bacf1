//! What the modal route of the first-order sweep costs and how far it is from the direct
//! route, in one run on this machine: each scene is swept once directly (a sparse
//! factorization per frequency) and then modally with the default band of modes (every
//! mode below four times the sweep's top frequency, at least 6) and with twice and four times
//! as many, each with and without the static residual flexibility. Times are the sweep's
//! wall time (the modal rows include their Lanczos run and residual solves); the
//! differences are the largest relative ones over the sweep's frequencies of the first
//! output's amplitude and of the joints' dissipated power.
//!
//! Run: `cargo run --release -p jointlin-harness --example sweep_bench [-- SCENE.toml ...]`
//! (default: scenes/three-beams-coarse.toml and scenes/bolted-lap.toml).

use std::path::Path;

use jointlin_harness::input;
use jointlin_harness::input::scene::Scene;
use jointlin_harness::run::{run, Extras, RunResult};
use jointlin_harness::settings::SweepMethod;

fn sweep(scene: &Scene, route: Option<(Option<usize>, bool)>) -> Result<RunResult, String> {
    let mut s = scene.clone();
    s.spec.field_output = None;
    if let Some((modes, residual)) = route {
        s.spec.sweep.method = SweepMethod::Modal;
        s.spec.sweep.modes = modes;
        s.spec.sweep.residual = Some(residual);
    }
    run(&s, Extras::default(), &|_, _, _| {}).map_err(|e| format!("{}: {e}", scene.file))
}

/// Largest relative differences (amplitude of the first output, power) of `a` from `b`.
fn difference(a: &RunResult, b: &RunResult) -> (f64, f64) {
    let rel = |x: f64, y: f64| {
        if y != 0.0 {
            (x - y).abs() / y.abs()
        } else {
            (x - y).abs()
        }
    };
    let (a, b) = (&a.main, &b.main);
    (0..a.freqs.len()).fold((0.0f64, 0.0f64), |(amp, pow), i| {
        (
            amp.max(rel(a.outputs[i][0].norm(), b.outputs[i][0].norm())),
            pow.max(rel(a.power[i], b.power[i])),
        )
    })
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scenes = if args.is_empty() {
        vec![
            "scenes/three-beams-coarse.toml".to_string(),
            "scenes/bolted-lap.toml".to_string(),
        ]
    } else {
        args
    };
    println!("| scene | free DOFs | contact points | route | modes | residual | sweep (s) | converged | largest difference, amplitude | largest difference, power |");
    println!("|---|---:|---:|---|---:|---|---:|---:|---:|---:|");
    for file in scenes {
        let scene = input::load(Path::new(&file))
            .map_err(|e| e.to_string())?
            .into_scene();
        let direct = sweep(&scene, None)?;
        let name = Path::new(&file)
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or(file.clone());
        let dofs = direct.problem.sys.dofs.n_free();
        let points = direct.problem.contacts.len();
        let converged = |r: &RunResult| {
            format!(
                "{}/{}",
                r.main.converged.iter().filter(|&&c| c).count(),
                r.main.freqs.len()
            )
        };
        println!(
            "| {name} | {dofs} | {points} | direct | – | – | {:.2} | {} | – | – |",
            direct.seconds[2],
            converged(&direct)
        );
        let band = sweep(&scene, Some((None, true)))?;
        let p0 = band.main.modal.as_ref().map_or(6, |m| m.modes);
        for count in [None, Some((2 * p0).min(dofs)), Some((4 * p0).min(dofs))] {
            for residual in [true, false] {
                let r = sweep(&scene, Some((count, residual)))?;
                let (amp, power) = difference(&r, &direct);
                let modes = r.main.modal.as_ref().map_or(0, |m| m.modes);
                println!(
                    "| {name} | {dofs} | {points} | modal | {modes} | {} | {:.2} | {} | {amp:.1e} | {power:.1e} |",
                    if residual { "yes" } else { "no" },
                    r.seconds[2],
                    converged(&r)
                );
            }
        }
    }
    Ok(())
}
