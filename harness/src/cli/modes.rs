//! `jointlin modes SCENE`: eigenfrequencies with every closed joint stuck.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::bench::stuck_modes;

use super::load_scene;

// The command's help is the doc comment of `Command::Modes`.
#[derive(clap::Args)]
pub struct Args {
    scene: PathBuf,
    /// Number of modes.
    #[arg(long, default_value_t = 6)]
    count: usize,
}

pub fn main(a: Args) -> ExitCode {
    let s = match load_scene(&a.scene) {
        Ok(s) => s,
        Err(code) => return code,
    };
    match stuck_modes(&s, a.count) {
        Ok(f) => {
            for (i, v) in f.iter().enumerate() {
                // Shortest round-trip form: the value can go into a scene's sweep.
                println!("mode {}: {v} (1/time)", i + 1);
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
