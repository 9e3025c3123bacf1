//! `jointlin effects SCENE`: the contact point models beyond the thesis on one scene.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::effects::{markdown, study, write};

use super::{load_scene, report_written};

// The command's help is the doc comment of `Command::Effects`.
#[derive(clap::Args)]
pub struct Args {
    scene: PathBuf,
    /// Output directory.
    #[arg(long, default_value = "out/effects")]
    out: PathBuf,
}

pub fn main(a: Args) -> ExitCode {
    let s = match load_scene(&a.scene) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let t = match study(&s, &|l| eprintln!("{l}")) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    print!("{}", markdown(&t));
    report_written(write(&a.out, &t))
}
