//! `jointlin run --time-domain` of a lumped scene: the static step, then per frequency
//! RK4 until periodic (`time::lumped_sweep`); results_time.csv, loops_time.csv, with plots
//! loops_time.svg (every joint's loop at the frequency of the largest response) and
//! run.json.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use jointlin_harness::input::scene::Scene;
use jointlin_harness::model::lumped::Lumped;
use jointlin_harness::model::Job;
use jointlin_harness::report::loop_plot::{self, JointLoop};
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::time::lumped::LoopSample;
use jointlin_harness::time::lumped_sweep::{run_lumped, LumpedTimeRun};
use jointlin_harness::time::lumped_tables::{self, joint_sample, peak};
use jointlin_harness::time::TimeSettings;
use jointlin_harness::util::atomic;

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
    let mut written = Vec::new();
    if plots {
        match plot_loops(s, &r, out) {
            Ok(p) => written.extend(p),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    }
    let files = lumped_tables::write(out, &Job::from(s), &r)
        .map(|f| written.into_iter().chain(f).collect());
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
fn plot_loops(s: &Scene, r: &LumpedTimeRun, out: &Path) -> Result<Option<PathBuf>, String> {
    let Some((freq, settled)) = peak(&r.lumped, &r.results) else {
        return Ok(None);
    };
    let file = out.join("loops_time.svg");
    plot_joint_loops(s, &r.lumped, (freq, &settled.loops), &file, "time domain")
}

/// Draws every joint's loop of `samples` (per sample, per element) at `freq` into `file`
/// (nothing without joints); `what` names the method in the title.
pub(super) fn plot_joint_loops(
    s: &Scene,
    l: &Lumped,
    (freq, samples): (f64, &[Vec<LoopSample>]),
    file: &Path,
    what: &str,
) -> Result<Option<PathBuf>, String> {
    if l.joints.is_empty() || samples.is_empty() {
        return Ok(None);
    }
    let loops: Vec<JointLoop> = (0..l.joints.len())
        .map(|j| {
            let at: Vec<_> = samples.iter().map(|x| joint_sample(l, j, x)).collect();
            JointLoop {
                name: l.joints[j].name.clone(),
                t1: at.iter().map(|s| (s.displacement[0], s.force[0])).collect(),
                t2: at.iter().map(|s| (s.displacement[1], s.force[1])).collect(),
            }
        })
        .collect();
    let fu = frequency_unit(&s.spec.units);
    let title = format!(
        "{}: {what}, one period at {:.4} {}",
        s.title(),
        fu.show(freq),
        fu.text
    );
    if let Some(dir) = file.parent() {
        std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    }
    atomic::with_temp(file, |t| loop_plot::draw(t, &title, &s.spec.units, &loops))?;
    Ok(Some(file.to_path_buf()))
}
