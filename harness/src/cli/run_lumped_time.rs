//! `jointlin run --time-domain` of a lumped scene: the static step, then per frequency
//! RK4 until periodic (`time::lumped_sweep`); results_time.csv, loops_time.csv, with plots
//! loops_time.svg (every joint's loop at the frequency of the largest response) and
//! run.json.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use jointlin_harness::input::scene::Scene;
use jointlin_harness::model::Job;
use jointlin_harness::report::lumped_run::plot_joint_loops;
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::time::lumped_sweep::{run_lumped, LumpedTimeRun};
use jointlin_harness::time::lumped_tables::{self, peak};
use jointlin_harness::time::TimeSettings;

use super::progress_bar;

/// Runs the lumped scene `s` in the time domain and writes its files into `out`.
pub fn main(s: &Scene, settings: &TimeSettings, out: &Path, plots: bool, quiet: bool) -> ExitCode {
    let mut pb = progress_bar(quiet);
    let r = run_lumped(s, settings, &|done, total| {
        pb.set_message("time domain");
        pb.set_length(total as u64);
        pb.set_position(done as u64);
    });
    pb.finish_and_clear();
    let r = match r {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(1);
        }
    };
    let fu = frequency_unit(&s.spec.units);
    eprintln!(
        "{}: time domain (RK4), lumped system, {} DOFs, {} elements, {} three-direction points, {:.3} s",
        s.file,
        r.lumped.dofs.len(),
        r.lumped.system.elements.len(),
        r.lumped.points.len(),
        r.seconds
    );
    for x in &r.results {
        match &x.result {
            Ok(st) => eprintln!(
                "  {:.6e} {}: {} steps/period, {} cycles ({}), energy/cycle {:.6e}, {:.2} s",
                fu.show(x.freq),
                fu.text,
                x.steps_per_cycle,
                st.cycles,
                if st.steady {
                    "periodic"
                } else {
                    "not periodic"
                },
                st.last.energy,
                st.seconds
            ),
            Err(e) => eprintln!("warning: {:.6e} {}: {e}", fu.show(x.freq), fu.text),
        }
    }
    let job = Job::from(s);
    let mut written = Vec::new();
    if plots {
        match plot_loops(&job, &r, out) {
            Ok(p) => written.extend(p),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    }
    let files = lumped_tables::write(out, &job, &r).map(|f| written.into_iter().chain(f).collect());
    let failed = r.results.iter().filter(|x| x.result.is_err()).count();
    match super::report_written(files) {
        ExitCode::SUCCESS if failed > 0 => {
            eprintln!(
                "error: {failed} of {} frequencies failed (results_time.csv says why)",
                r.results.len()
            );
            ExitCode::from(1)
        }
        code => code,
    }
}

/// loops_time.svg: every joint's loop over the last period at the frequency of the
/// largest response (nothing without joints or integrated frequencies).
fn plot_loops(job: &Job, r: &LumpedTimeRun, out: &Path) -> Result<Option<PathBuf>, String> {
    let Some((freq, settled)) = peak(&r.lumped, &r.results) else {
        return Ok(None);
    };
    let file = out.join("loops_time.svg");
    plot_joint_loops(job, &r.lumped, (freq, &settled.loops), &file, "time domain")
}
