//! What the modal route saves on a loss study (`jointlin loss`), in one run on this
//! machine: the scene's `[loss_study]` is run once by the direct route (a sparse
//! factorization of the dynamic stiffness per solve) and once by the modal route with its
//! default band (every stuck mode below four times the sweep's top frequency, and the
//! omitted modes' residual flexibility). The table gives each route's wall time and
//! steady-state solves, and the modal route's largest relative differences from the
//! direct one over every row of the study (resonance frequency, power) and over the
//! study's predictions of its reference points (the power interpolated at each reference
//! amplitude, as `jointlin loss` reports it).
//!
//! Run: `cargo run --release -p jointlin-harness --example loss_bench [-- SCENE.toml]`
//! (default: scenes/knife.toml; about 40 min for both routes with the two cores free).

use std::path::Path;
use std::time::Instant;

use jointlin_harness::input;
use jointlin_harness::input::scene::Scene;
use jointlin_harness::loss::report::interpolate;
use jointlin_harness::loss::{run_study, StudyResult};
use jointlin_harness::settings::SweepMethod;

/// The study by one route, with its wall time (s).
fn study(scene: &Scene, method: SweepMethod) -> Result<(StudyResult, f64), String> {
    let mut s = scene.clone();
    s.spec.sweep.method = method;
    s.spec.field_output = None;
    let t = Instant::now();
    let r = run_study(&s, &|_| {}).map_err(|e| format!("{}: {e}", scene.file))?;
    Ok((r, t.elapsed().as_secs_f64()))
}

fn rel(a: f64, b: f64) -> f64 {
    if b != 0.0 {
        (a - b).abs() / b.abs()
    } else {
        (a - b).abs()
    }
}

/// Largest relative differences of `a` from `b`: (resonance frequency, power) over the
/// rows, and the predictions at the study's reference points.
fn differences(scene: &Scene, a: &StudyResult, b: &StudyResult) -> (f64, f64, Option<f64>) {
    let rows = a
        .curves
        .iter()
        .zip(&b.curves)
        .flat_map(|((_, x), (_, y))| x.iter().zip(y));
    let (freq, power) = rows.fold((0.0f64, 0.0f64), |(f, p), (x, y)| {
        (f.max(rel(x.freq, y.freq)), p.max(rel(x.power, y.power)))
    });
    let st = scene.spec.loss_study.as_ref().expect("a loss study");
    let at = |r: &StudyResult, torque: f64, amplitude: f64| {
        let (_, c) = r.curves.iter().find(|(t, _)| *t == torque)?;
        interpolate(c, amplitude, st.power_factor)
    };
    let predictions = st
        .reference
        .iter()
        .filter_map(|p| {
            Some(rel(
                at(a, p.torque, p.amplitude)?,
                at(b, p.torque, p.amplitude)?,
            ))
        })
        .reduce(f64::max);
    (freq, power, predictions)
}

fn main() -> Result<(), String> {
    let file = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "scenes/knife.toml".to_string());
    let scene = input::load(Path::new(&file))
        .map_err(|e| e.to_string())?
        .into_scene();
    let (direct, direct_s) = study(&scene, SweepMethod::Direct)?;
    let (modal, modal_s) = study(&scene, SweepMethod::Modal)?;
    let (freq, power, predictions) = differences(&scene, &modal, &direct);
    let name = Path::new(&file)
        .file_name()
        .map_or(file.clone(), |n| n.to_string_lossy().into_owned());
    let rows: usize = direct.curves.iter().map(|(_, c)| c.len()).sum();
    println!("| scene | route | solves | study (s) | modal / direct time | largest difference, resonance | largest difference, power ({rows} rows) | largest difference, predictions |");
    println!("|---|---|---:|---:|---:|---:|---:|---:|");
    println!(
        "| {name} | direct | {} | {direct_s:.0} | – | – | – | – |",
        direct.solves
    );
    println!(
        "| {name} | modal | {} | {modal_s:.0} | {:.2} | {freq:.1e} | {power:.1e} | {} |",
        modal.solves,
        modal_s / direct_s,
        predictions.map_or("–".to_string(), |p| format!("{p:.1e}"))
    );
    Ok(())
}
