//! `jointlin export SCENE --inp FILE`: the scene as an Abaqus/Standard job: FILE, the
//! frequency list `sweep.frq` and the UEXTERNALDB configuration `jointlin.cfg` beside it
//! (`jointlin_harness::export`).

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::export::{check_target, export, write, ExportError};

use super::{load_scene_with, report_written, SceneOverrides};

// The command's help is the doc comment of `Command::Export`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML, see scenes/).
    scene: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// The deck to write (its directory is the job directory: sweep.frq and
    /// jointlin.cfg are written beside it).
    #[arg(long)]
    inp: PathBuf,
}

pub fn main(a: Args) -> ExitCode {
    let s = match load_scene_with(&a.scene, &a.overrides.set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut inputs = vec![a.scene.clone()];
    if let Some(model) = &s.spec.model {
        inputs.push(
            a.scene
                .parent()
                .unwrap_or(std::path::Path::new(""))
                .join(model),
        );
    }
    if let Err(e) = check_target(&a.inp, &inputs) {
        eprintln!("error: {e}");
        return ExitCode::from(2);
    }
    let name = a
        .inp
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let job = match export(&s, &name) {
        Ok(j) => j,
        Err(e @ ExportError::Solve(_)) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
        Err(e @ ExportError::Unsupported { .. }) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
        Err(ExportError::Build(e)) => {
            eprintln!("error: {}", jointlin_harness::model::locate(&s, &e));
            return ExitCode::from(2);
        }
    };
    for note in &job.left_out {
        eprintln!("not in the deck: {note}");
    }
    report_written(write(&job, &a.inp, &inputs))
}
