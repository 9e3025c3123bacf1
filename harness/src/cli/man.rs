//! `jointlin man --out DIR`: the man pages of the program and of every command
//! (`jointlin.1`, `jointlin-run.1`, …), generated from the clap definitions by
//! clap_mangen; `make install` writes them to `$(PREFIX)/share/man/man1`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::CommandFactory;

use super::{report_written, Cli};

// The command's help is the doc comment of `Command::Man`.
#[derive(clap::Args)]
pub struct Args {
    /// Directory the pages are written to (created if missing).
    #[arg(long)]
    out: PathBuf,
}

pub fn main(a: Args) -> ExitCode {
    report_written(write_pages(&a.out))
}

/// Writes `jointlin.1` and `jointlin-<command>.1` for every command into `dir`.
fn write_pages(dir: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut cmd = Cli::command();
    cmd.build();
    let mut written = Vec::new();
    let mut page = |c: &clap::Command, name: &str| -> Result<(), String> {
        let path = dir.join(format!("{name}.1"));
        let mut text = Vec::new();
        clap_mangen::Man::new(
            c.clone()
                .name(name.to_string())
                .version(env!("CARGO_PKG_VERSION")),
        )
        .render(&mut text)
        .map_err(|e| format!("{name}: {e}"))?;
        let text = String::from_utf8(text).map_err(|e| format!("{name}: {e}"))?;
        jointlin_harness::util::atomic::write_text(&path, &text)?;
        written.push(path);
        Ok(())
    };
    page(&cmd, "jointlin")?;
    // clap's own `help` command has no page of its own (`jointlin help X` = `X --help`).
    for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
        page(sub, &format!("jointlin-{}", sub.get_name()))?;
        for nested in sub.get_subcommands().filter(|s| s.get_name() != "help") {
            page(
                nested,
                &format!("jointlin-{}-{}", sub.get_name(), nested.get_name()),
            )?;
        }
    }
    Ok(written)
}
