//! `jointlin tradeoff SCENE`: one scene at a ladder of fidelities, error vs wall time.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::model::{self, Kind};
use jointlin_harness::tradeoff::{lumped, markdown, study, write};

use super::{study_main, SceneOverrides};

// The command's help is the doc comment of `Command::Tradeoff`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML, see scenes/).
    scene: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Output directory.
    #[arg(long, default_value = "out/tradeoff")]
    out: PathBuf,
    /// Frequency (1/time); default the scene's only one, else its response peak.
    #[arg(long)]
    freq: Option<f64>,
}

pub fn main(a: Args) -> ExitCode {
    study_main(
        "tradeoff",
        &a.scene,
        &a.overrides.set,
        &a.out,
        |s| {
            let log = |l: &str| eprintln!("{l}");
            if model::kind(s) == Kind::Lumped {
                lumped::study(s, a.freq, &log)
            } else {
                study(s, a.freq, &log)
            }
        },
        markdown,
        write,
    )
}
