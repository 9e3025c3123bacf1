//! The `jointlin` command: parses the command line and hands it to the command's file
//! under [`cli`] (one file per command; the harness reaches the library only through
//! its C API).

use std::process::ExitCode;

use jointlin_harness::cli;

fn main() -> ExitCode {
    #[cfg(unix)]
    cli::default_sigpipe();
    ExitCode::from(cli::run_args(std::env::args_os()))
}
