//! `jointlin run SCENE --out DIR`: the static step, the steady-state sweep and the
//! reports; with `--time-domain` the time-domain reference instead.

use jointlin_harness::util::number::sig;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::ValueEnum;

use jointlin_harness::input::scene::{validate, Scene};
use jointlin_harness::model::{self, BuildError, Job, Kind};
use jointlin_harness::report::{self, ReportOptions};
use jointlin_harness::run::{run, Extras, RunError, RunResult};
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::settings::Mode;
use jointlin_harness::solve::prepared::PrepareError;
use jointlin_harness::util::progress::progress_bar;

use super::{load_scene_with, print_findings, report_written, SceneOverrides};

#[derive(Clone, Copy, ValueEnum)]
pub enum ModeArg {
    Fast,
    Thesis,
    HarmonicBalance,
}

// The command's help is the doc comment of `Command::Run`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML, see scenes/) or Abaqus-format deck (.inp).
    scene: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Override the scene's iteration mode (harmonic-balance needs --harmonics unless
    /// the scene sets harmonics).
    #[arg(long, value_enum)]
    mode: Option<ModeArg>,
    /// Override the scene's [iteration] harmonics (harmonic balance).
    #[arg(long)]
    harmonics: Option<usize>,
    /// Override the scene's [iteration] samples per period (harmonic balance).
    #[arg(long)]
    samples: Option<usize>,
    /// Skip the SVG plots (and the reference sweep without contact damping they need).
    #[arg(long)]
    no_plots: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// Run the time-domain reference instead (UINTER LINPER = 0 with the library's
    /// hysteresis, or with [effects] coupled_slip / normal_load_variation the library's
    /// three-direction point, the balance's model; RK4 or Newmark, the scene's
    /// [time_domain] table): per frequency until periodic; writes results_time.csv,
    /// points_time.csv, run.json. A lumped scene (mass bodies, [[matrices]], joints) is
    /// integrated by RK4 from its static state and writes results_time.csv,
    /// loops_time.csv (every joint's loop over the last period), loops_time.svg and
    /// run.json.
    #[arg(long)]
    time_domain: bool,
}

pub fn main(a: Args) -> ExitCode {
    let mut s = match load_scene_with(&a.scene, &a.overrides.set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if let Err(code) = apply_options(&mut s, &a) {
        return code;
    }
    if s.deck.is_some() && s.frequencies().is_empty() {
        eprintln!(
            "error: {}: a run needs a *STEADY STATE DYNAMICS, DIRECT step in the deck (the sweep)",
            s.file
        );
        return ExitCode::from(2);
    }
    // No earlier run's marker survives this one; an interrupt says so.
    if let Err(e) = jointlin_harness::util::atomic::begin(&a.out) {
        eprintln!("error: {}: {e}", a.out.display());
        return ExitCode::from(1);
    }
    if a.time_domain {
        return time_domain_run(&s, &a.out, !a.no_plots, a.quiet);
    }
    if model::kind(&s) == Kind::Lumped {
        if s.spec.iteration.mode == Mode::Thesis {
            eprintln!(
                "error: {}: a lumped system ([[matrices]], [[joints]]) is swept first order (mode \"fast\", the default) or by harmonic balance (mode \"harmonic_balance\"); the thesis's pass scheme is for FE scenes",
                s.file
            );
            return ExitCode::from(2);
        }
        return super::run_lumped::main(&s, &a.out, !a.no_plots);
    }
    let mut pb = progress_bar(a.quiet);
    let r = run(
        &s,
        Extras {
            reference_without_damping: !a.no_plots,
            condense_max: None,
        },
        &|label, done, total| {
            pb.set_message(label);
            pb.set_length(total as u64);
            pb.set_position(done as u64);
        },
    );
    pb.finish_and_clear();
    let r = match r {
        Ok(r) => r,
        // A deck the build cannot honour: its own file:line.
        Err(RunError::Prepare(PrepareError::Build(BuildError::Deck(e)))) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
        // A model that cannot be built is the scene's fault: its location, as `check`.
        Err(RunError::Prepare(PrepareError::Build(e))) => {
            eprintln!("error: {}", jointlin_harness::model::locate(&s, &e));
            return ExitCode::from(2);
        }
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    print_findings(&r.problem);
    print_summary(&s, &r);
    let unconverged = std::iter::once(&r.main)
        .chain(&r.down)
        .map(|sweep| sweep.converged.iter().filter(|&&c| !c).count())
        .sum::<usize>();
    match report::write_all(&a.out, &s, &r, ReportOptions { plots: !a.no_plots }) {
        Ok(files) => {
            for f in files {
                eprintln!("wrote {}", f.display());
            }
        }
        Err(e) => {
            eprintln!("error writing reports: {e}");
            return ExitCode::from(1);
        }
    }
    print_warnings(&s, &r, unconverged);
    ExitCode::SUCCESS
}

/// The command line's mode, harmonics and samples over the scene's, checked by the
/// scene's own rules (exit 2 naming the key).
fn apply_options(s: &mut Scene, a: &Args) -> Result<(), ExitCode> {
    if let Some(m) = a.mode {
        s.spec.iteration.mode = match m {
            ModeArg::Fast => Mode::Fast,
            ModeArg::Thesis => Mode::Thesis,
            ModeArg::HarmonicBalance => Mode::HarmonicBalance,
        };
    }
    let it = &mut s.spec.iteration;
    it.harmonics = a.harmonics.or(it.harmonics);
    it.samples = a.samples.or(it.samples);
    // The overrides are checked by the scene's own rules.
    let size = || validate::size::check(&s.spec);
    if let Some((key, msg)) = validate::validate(&s.spec).into_iter().next().or_else(size) {
        eprintln!(
            "error: {}: with the command-line overrides, `{key}`: {msg}",
            s.file
        );
        return Err(ExitCode::from(2));
    }
    Ok(())
}

/// The run's log: the model, the modal route, the effects with their costs, the passes
/// and the timings.
fn print_summary(s: &Scene, r: &RunResult) {
    eprintln!(
        "{}: {} free DOFs, {} contact points ({} closed), mode {}",
        s.file,
        r.problem.sys.dofs.n_free(),
        r.problem.contacts.len(),
        r.stat.closed.iter().filter(|&&c| c).count(),
        s.spec.iteration.mode.name()
    );
    if let Some(mr) = &r.main.modal {
        let fu = jointlin_harness::settings::units::frequency_unit(&s.spec.units);
        let band = match (mr.band_limit, mr.band_complete) {
            (Some(l), true) => format!("every mode below {} {}", sig(fu.show(l)), fu.text),
            (Some(l), false) => format!(
                "the band below {} {} cut at the cap of {} modes",
                sig(fu.show(l)),
                fu.text,
                mr.modes
            ),
            (None, _) => "the count asked for".into(),
        };
        eprintln!(
            "modal route: {} stuck modes up to {} {} ({band}), residual flexibility {}, largest backward error {:.1e}",
            mr.modes,
            sig(fu.show(mr.highest_mode_frequency)),
            fu.text,
            if mr.residual_flexibility { "on" } else { "off" },
            mr.largest_backward_error
        );
    }
    eprintln!("effects:");
    for e in &r.effects {
        eprintln!(
            "  {:28} {:3}  {:8.3} s  {}",
            e.name,
            if e.active { "on" } else { "off" },
            e.seconds,
            if e.active { e.work.as_str() } else { "" }
        );
    }
    for (label, sweep) in
        std::iter::once(("", &r.main)).chain(r.down.as_ref().map(|d| ("sweep down: ", d)))
    {
        for p in &sweep.passes {
            eprintln!(
                "{label}pass {} ({}): {} frequencies, {} converged",
                p.pass,
                p.kind,
                p.frequencies.len(),
                p.converged
            );
        }
    }
    eprintln!(
        "timings: build {:.3} s, static {:.3} s, sweep {:.3} s, reference {:.3} s; {} factorizations",
        r.seconds[0], r.seconds[1], r.seconds[2], r.seconds[3], r.main.factorizations
    );
}

/// The run's closing warnings: failed, singular and unconverged frequencies, and
/// amplitudes too large for linear kinematics ([`report::kinematics::note`]).
fn print_warnings(s: &Scene, r: &RunResult, unconverged: usize) {
    let fu = frequency_unit(&s.spec.units);
    for (i, f) in r.main.freqs.iter().enumerate() {
        if let Some(e) = r.main.failure(i) {
            eprintln!(
                "warning: {:e} {} failed (status failed in results.csv): {e}",
                fu.show(*f),
                fu.text
            );
        }
    }
    let failed = r.main.failed.iter().filter(|e| e.is_some()).count();
    let singular = r.main.singular.iter().filter(|&&c| c).count();
    if singular > 0 {
        eprintln!(
            "warning: {singular} frequencies have a singular dynamic stiffness (an undamped resonance?): no response there (status singular in results.csv, singular_frequencies in run.json)"
        );
    }
    if unconverged > singular + failed {
        eprintln!(
            "warning: {} frequencies did not converge (see run.json)",
            unconverged - singular - failed
        );
    }
    if let Some(note) = report::kinematics::note(&s.spec.units, r) {
        eprintln!("warning: {note}");
    }
}

/// `jointlin run --time-domain`.
fn time_domain_run(s: &Scene, out: &Path, plots: bool, quiet: bool) -> ExitCode {
    use jointlin_harness::time::{scene_run, tables, TimeSettings};
    let settings = match TimeSettings::from_spec(s.spec.time_domain.as_ref()) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(2);
        }
    };
    if model::kind(s) == Kind::Lumped {
        return super::run_lumped_time::main(s, &settings, out, plots, quiet);
    }
    let mut pb = progress_bar(quiet);
    let r = scene_run::run_scene(s, &settings, &|done, total| {
        pb.set_message("time domain");
        pb.set_length(total as u64);
        pb.set_position(done as u64);
    });
    pb.finish_and_clear();
    let r = match r {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    eprintln!(
        "{}: time domain, {} free DOFs, {} contact points, {:.3} s",
        s.file,
        r.problem.sys.dofs.n_free(),
        r.problem.contacts.len(),
        r.seconds
    );
    for x in &r.results {
        eprintln!(
            "  {:.6e}: {} {} steps/period, {} cycles ({}), amplitude {:.6e}, energy/cycle {:.6e}, {:.2} s",
            x.freq,
            x.integrator,
            x.steps_per_cycle,
            x.cycles,
            if x.steady { "periodic" } else { "not periodic" },
            x.last.outputs.first().map_or(0.0, |o| o.amplitude),
            x.last.energy,
            x.seconds
        );
    }
    let mut written = Vec::new();
    if plots {
        match plot_point_loops(s, &r, out) {
            Ok(p) => written.extend(p),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    }
    report_written(
        tables::write(out, &Job::from(s), &r).map(|f| written.into_iter().chain(f).collect()),
    )
}

/// loops_time.svg: the loops of the (at most four) contact points that dissipate most,
/// at the frequency whose loops the run kept (its largest response).
fn plot_point_loops(
    s: &Scene,
    r: &jointlin_harness::time::scene_run::TimeRun,
    out: &Path,
) -> Result<Option<PathBuf>, String> {
    use jointlin_harness::report::{loop_plot, point_loops};
    let Some(x) = r.results.iter().find(|x| !x.loops.is_empty()) else {
        return Ok(None);
    };
    let nodes = jointlin_harness::model::node_ids(s, &r.problem);
    let all: Vec<usize> = (0..r.problem.contacts.len()).collect();
    let loops = point_loops::most_dissipating(&r.problem, &nodes, &x.loops, &all);
    if loops.is_empty() {
        return Ok(None);
    }
    let fu = jointlin_harness::settings::units::frequency_unit(&s.spec.units);
    let title = format!(
        "{}: time domain, the {} points dissipating most, last period at {:.4} {}",
        s.title(),
        loops.len(),
        fu.show(x.freq),
        fu.text
    );
    std::fs::create_dir_all(out).map_err(|e| e.to_string())?;
    let file = out.join("loops_time.svg");
    jointlin_harness::util::atomic::with_temp(&file, |t| {
        loop_plot::draw(t, &title, &s.spec.units, &loops)
    })?;
    Ok(Some(file))
}
