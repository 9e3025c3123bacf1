//! `jointlin validate`: the frequency domain against the time-domain reference.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::input::scene::Scene;
use jointlin_harness::validate::{markdown, run, write, CaseScenes, Cases};

use super::report_written;

// The command's help is the doc comment of `Command::Validate`.
#[derive(clap::Args)]
pub struct Args {
    /// Output directory.
    #[arg(long, default_value = "out/validation")]
    out: PathBuf,
    /// Directory with block-stick.toml, block-slip.toml, three-beams.toml.
    #[arg(long, default_value = "scenes")]
    scenes: PathBuf,
    /// Cases (default all): block-stick, block-slip, duffing, softening-friction, three-beams.
    #[arg(long, value_delimiter = ',')]
    cases: Vec<String>,
}

pub fn main(a: Args) -> ExitCode {
    let cases = match Cases::parse(&a.cases) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    // The scenes the selected cases start from, read through the input path.
    let load = |wanted: bool, file: &str| -> Result<Option<Scene>, String> {
        if !wanted {
            return Ok(None);
        }
        let path = a.scenes.join(file);
        jointlin_harness::input::load(&path)
            .map(|i| Some(i.into_scene()))
            .map_err(|e| e.to_string())
    };
    let scenes = (|| {
        Ok::<_, String>(CaseScenes {
            block_stick: load(cases.block_stick, "block-stick.toml")?,
            block_slip: load(cases.block_slip, "block-slip.toml")?,
            three_beams: load(cases.three_beams, "three-beams.toml")?,
        })
    })();
    let scenes = match scenes {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let rep = match run(&scenes, cases, &|l| eprintln!("{l}")) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    print!("{}", markdown(&rep));
    report_written(write(&a.out, &rep))
}
