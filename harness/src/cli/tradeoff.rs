//! `jointlin tradeoff SCENE`: one scene at a ladder of fidelities, error vs wall time.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::tradeoff::{markdown, study, write};

use super::{load_scene, report_written};

// The command's help is the doc comment of `Command::Tradeoff`.
#[derive(clap::Args)]
pub struct Args {
    scene: PathBuf,
    /// Output directory.
    #[arg(long, default_value = "out/tradeoff")]
    out: PathBuf,
    /// Frequency (1/time); default the scene's only one, else its response peak.
    #[arg(long)]
    freq: Option<f64>,
}

pub fn main(a: Args) -> ExitCode {
    let s = match load_scene(&a.scene) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let t = match study(&s, a.freq, &|l| eprintln!("{l}")) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    print!("{}", markdown(&t));
    report_written(write(&a.out, &t))
}
