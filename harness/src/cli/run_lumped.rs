//! `jointlin run` of a lumped scene (mass bodies, `[[matrices]]`, springs, joints): the
//! lumped system built, then its sweep and files (`report::lumped_run`: first order or
//! the harmonic balance; results.csv, harmonics.csv, loops.csv, frf.svg, loops.svg,
//! run.json).

use std::path::Path;
use std::process::ExitCode;

use jointlin_harness::input::scene::Scene;
use jointlin_harness::model::Job;
use jointlin_harness::report::lumped_run;

/// Builds the lumped system of `s` (an error: exit 2), runs its sweep and writes its
/// files into `out` (a file that cannot be written: exit 1).
pub fn main(s: &Scene, out: &Path, plots: bool) -> ExitCode {
    let job = Job::from(s);
    let l = match job.lumped() {
        Ok(l) => l,
        Err(e) => {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(2);
        }
    };
    match lumped_run::run(&job, &l, out, plots) {
        Ok(r) => {
            eprintln!(
                "{}: lumped system, {} DOFs, {} elements; {} of {} frequencies converged",
                s.file,
                l.dofs.len(),
                l.elements.len(),
                r.solved - r.failed,
                r.solved,
            );
            for w in &r.written {
                eprintln!("wrote {}", w.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
