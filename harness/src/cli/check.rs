//! `jointlin check SCENE`: validates a scene and prints a summary.

use std::path::PathBuf;
use std::process::ExitCode;

use super::load_scene;

// The command's help is the doc comment of `Command::Check`.
#[derive(clap::Args)]
pub struct Args {
    scene: PathBuf,
}

pub fn main(a: Args) -> ExitCode {
    let s = match load_scene(&a.scene) {
        Ok(s) => s,
        Err(code) => return code,
    };
    println!(
        "{}: ok — {} bodies, {} interfaces, {} frequencies ({} to {}), mode {:?}",
        s.file,
        s.spec.bodies.len(),
        s.spec.interfaces.len(),
        s.frequencies().len(),
        s.frequencies().first().copied().unwrap_or(0.0),
        s.frequencies().last().copied().unwrap_or(0.0),
        s.spec.iteration.mode
    );
    ExitCode::SUCCESS
}
