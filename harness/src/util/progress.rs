//! The commands' progress bar (on stderr; hidden when quiet).

use indicatif::{ProgressBar, ProgressStyle};

/// A bar of unknown length (the caller sets it) with a message, position, elapsed time
/// and the estimated time left; [`ProgressBar::hidden`] when `quiet`.
pub fn progress_bar(quiet: bool) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(1);
    pb.set_style(
        ProgressStyle::with_template("{msg:40} [{bar:40}] {pos}/{len} {elapsed} (ETA {eta})")
            .expect("static template")
            .progress_chars("=> "),
    );
    pb
}
