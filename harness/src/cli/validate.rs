//! `jointlin validate`: the frequency domain against the time-domain reference.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::model::Job;
use jointlin_harness::validate::{markdown, run, write, CaseScenes, Cases};

use super::report_written;

// The command's help is the doc comment of `Command::Validate`.
#[derive(clap::Args)]
pub struct Args {
    /// Output directory.
    #[arg(long, default_value = "out/validation")]
    out: PathBuf,
    /// Directory with block-stick.toml, block-slip.toml, three-beams.toml (default:
    /// ./scenes where it holds them, else the installed PREFIX/share/jointlin/scenes).
    #[arg(long)]
    scenes: Option<PathBuf>,
    /// Cases (default all): block-stick, block-slip, duffing, softening-friction, three-beams.
    #[arg(long, value_delimiter = ',')]
    cases: Vec<String>,
}

/// The scenes directory: the one given, else ./scenes where it holds the validation
/// scenes, else the installed tree's share/jointlin/scenes beside the program's bin/.
fn scenes_dir(given: Option<PathBuf>) -> Result<PathBuf, String> {
    if let Some(d) = given {
        return Ok(d);
    }
    let local = PathBuf::from("scenes");
    if local.join("block-stick.toml").is_file() {
        return Ok(local);
    }
    let installed = std::env::current_exe().ok().and_then(|exe| {
        exe.parent()?
            .parent()
            .map(|p| p.join("share/jointlin/scenes"))
    });
    match installed {
        Some(d) if d.join("block-stick.toml").is_file() => Ok(d),
        other => Err(format!(
            "no validation scenes in ./scenes{}: give --scenes DIR",
            other.map_or(String::new(), |d| format!(" or {}", d.display()))
        )),
    }
}

pub fn main(a: Args) -> ExitCode {
    let scenes_dir = match scenes_dir(a.scenes.clone()) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let cases = match Cases::parse(&a.cases) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    // The scenes the selected cases start from, read through the input path.
    let load = |wanted: bool, file: &str| -> Result<Option<Job>, String> {
        if !wanted {
            return Ok(None);
        }
        let path = scenes_dir.join(file);
        Job::load(&path).map(Some).map_err(|e| e.to_string())
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
