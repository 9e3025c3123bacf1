//! `jointlin effects SCENE`: the contact point models beyond the thesis on one scene.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::effects::{markdown, study, write};

use super::{study_main, SceneOverrides};

// The command's help is the doc comment of `Command::Effects`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML, see scenes/), or a deck (.inp).
    scene: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Output directory.
    #[arg(long, default_value = "out/effects")]
    out: PathBuf,
}

pub fn main(a: Args) -> ExitCode {
    study_main(
        "effects",
        &a.scene,
        &a.overrides.set,
        &a.out,
        |s| study(s, &|l| eprintln!("{l}")),
        markdown,
        write,
    )
}
