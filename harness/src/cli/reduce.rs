//! `jointlin reduce MODEL --out DIR`: an FE scene or deck reduced onto its contact
//! directions, outputs and load (`reduce`), written as a `[[matrices]]` model with the
//! scene that runs it; the log compares the stuck frequencies with the full model's.

use std::path::PathBuf;
use std::process::ExitCode;

use serde_json::json;

use jointlin_harness::capi;
use jointlin_harness::export::reduced;
use jointlin_harness::model::{self, Kind};
use jointlin_harness::reduce::{self, Interior, Reduction};
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::util::progress::progress_bar;
use jointlin_harness::util::{atomic, provenance};

use super::{load_scene_with, print_findings, report_written, SceneOverrides};

// The command's help is the doc comment of `Command::Reduce`.
#[derive(clap::Args)]
pub struct Args {
    /// FE scene (box bodies with [[interfaces]]) or deck (.inp).
    model: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Output directory: K.mtx, M.mtx, D.mtx (with material damping), dofs.csv,
    /// scene.toml, run.json.
    #[arg(long)]
    out: PathBuf,
    /// Interior modes to keep; default every stuck mode below 4 × the sweep's highest
    /// frequency (at least 8).
    #[arg(long)]
    modes: Option<usize>,
    /// No progress (the stage and elapsed time, on stderr).
    #[arg(long)]
    quiet: bool,
}

pub fn main(a: Args) -> ExitCode {
    let scene = match load_scene_with(&a.model, &a.overrides.set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if model::kind(&scene) == Kind::Lumped {
        eprintln!(
            "error: {}: a lumped scene ([[matrices]], [[joints]]) is reduced already; reduce takes an FE scene or deck",
            a.model.display()
        );
        return ExitCode::from(2);
    }
    let f_top = scene.frequencies().into_iter().fold(0.0f64, f64::max);
    let interior = match a.modes {
        Some(0) => {
            eprintln!("error: --modes: at least 1");
            return ExitCode::from(2);
        }
        Some(n) => Interior::Count(n),
        None if f_top > 0.0 => Interior::Below(reduce::BAND_FACTOR * f_top),
        None => Interior::Count(reduce::MIN_MODES),
    };
    let mut pb = progress_bar(a.quiet);
    pb.set_message("building the model");
    let p = match jointlin_harness::model::build(&scene) {
        Ok(p) => p,
        Err(e) => {
            pb.finish_and_clear();
            eprintln!("error: {}: {e}", a.model.display());
            return ExitCode::from(2);
        }
    };
    pb.set_message("reducing: static step, stuck modes, constraint modes, projection");
    let r = reduce::reduce(&p, &scene.spec.effects, interior);
    pb.finish_and_clear();
    print_findings(&p);
    let r = match r {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {}: {e}", a.model.display());
            return ExitCode::from(1);
        }
    };
    let unit = frequency_unit(&scene.spec.units);
    log(&r, interior, &unit);
    let e = &scene.spec.effects;
    if !(e.tangential_microslip && e.macroslip && e.contact_damping) {
        eprintln!(
            "warning: the reduced scene's joints have microslip, macroslip and contact damping on: a lumped system does not switch them"
        );
    }
    if let Err(e) = atomic::begin(&a.out) {
        eprintln!("error: {}: {e}", a.out.display());
        return ExitCode::from(1);
    }
    let origin = format!("jointlin reduce {}", a.model.display());
    report_written(reduced::write(&r, &scene.spec, &a.out, &origin).and_then(|mut files| {
        let largest = largest_difference(&r);
        let head = provenance::head("reduce", &capi::abi_version(), &scene.sources);
        let run = provenance::with_head(
            head,
            json!({
                "model": {"file": scene.file, "spec": scene.spec},
                "units": scene.spec.units,
                "closed_points": r.closed,
                "open_points": r.open,
                "joints": r.set.joints.len() + r.set.points.len(),
                "three_direction_joints": r.set.points.len(),
                "held_contact_directions": r.set.held,
                "retained_coordinates": r.set.rows.len(),
                "interior_modes": r.interior,
                "frequency_unit": unit.text,
                "stuck_frequencies_full_model": r.stuck_full.iter().map(|&f| unit.show(f)).collect::<Vec<_>>(),
                "stuck_frequencies_reduced": r.stuck_reduced.iter().map(|&f| unit.show(f)).collect::<Vec<_>>(),
                "largest_relative_difference": largest,
            }),
        );
        let text = serde_json::to_string_pretty(&run).map_err(|e| e.to_string())?;
        files.push(atomic::write_marker(&a.out, &text)?);
        Ok(files)
    }))
}

/// Largest |f_reduced − f_full| / f_full over the kept stuck modes.
fn largest_difference(r: &Reduction) -> f64 {
    r.stuck_full
        .iter()
        .zip(&r.stuck_reduced)
        .map(|(a, b)| ((b - a) / a).abs())
        .fold(0.0, f64::max)
}

fn log(r: &Reduction, interior: Interior, unit: &jointlin_harness::settings::units::FrequencyUnit) {
    let fu = &unit.text;
    let why = match interior {
        Interior::Count(n) => format!("{n} asked"),
        Interior::Below(f) => format!("the stuck modes below {:.6} {fu}", unit.show(f)),
    };
    eprintln!(
        "reduced: {} closed contact points ({} open, no joint), {} joints, {} retained coordinates, \
         {} interior modes ({why})",
        r.closed,
        r.open,
        r.set.joints.len() + r.set.points.len(),
        r.set.rows.len(),
        r.interior
    );
    if r.set.held > 0 {
        eprintln!(
            "{} contact directions are held at zero relative displacement by clamps: no joint",
            r.set.held
        );
    }
    eprintln!(
        "stuck frequencies, full → reduced model ({fu}): {}; largest relative difference {:.1e}",
        r.stuck_full
            .iter()
            .zip(&r.stuck_reduced)
            .take(6)
            .map(|(a, b)| format!("{:.6} → {:.6}", unit.show(*a), unit.show(*b)))
            .collect::<Vec<_>>()
            .join(", "),
        largest_difference(r)
    );
}
