//! The `jointlin` command: parses the command line and hands it to the command's file
//! under [`cli`] (one file per command; the harness reaches the library only through
//! its C API).

mod cli;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    #[cfg(unix)]
    cli::default_sigpipe();
    cli::dispatch(cli::Cli::parse().command)
}
