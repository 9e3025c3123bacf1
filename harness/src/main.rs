//! The `jointlin` command: runs scenes through the harness (which reaches the library
//! only through its C API), lists modes, and benchmarks the sweep modes.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};

use jointlin_harness::bench;
use jointlin_harness::report::{self, ReportOptions};
use jointlin_harness::run::{run, Extras};
use jointlin_harness::scene::{validate, Mode, Scene};

#[derive(Parser)]
#[command(
    name = "jointlin",
    version,
    about = "Frequency-domain joint contact studies: scenes → static preload → steady-state sweeps with linearized contact (k*, d*) through the jointlin C API"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum ModeArg {
    Fast,
    Thesis,
    HarmonicBalance,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene: static preload step, steady-state sweep, reports.
    ///
    /// Steps: (1) the static preload step solves K u + f_c(u) = f_pre by Newton with the
    /// library's normal law (UINTER, LINPER = 0); open points stay open. (2) The
    /// steady-state step solves (K + K_c(k*) + iω(D + D_c(d*)) − ω²M) û = f̂ per frequency,
    /// k* and d* per point and tangential direction from the library for the point's
    /// amplitude, iterated to consistency: mode `fast` (default; one factorization per
    /// frequency, condensation onto the contact DOFs) or `thesis` (the UEXTERNALDB
    /// multi-pass scheme of thesis §4.3.2 through the library's store). Or, with
    /// [iteration] mode = "harmonic_balance", harmonics = H (samples = N optional), the
    /// multi-harmonic balance: the library's time-domain point marched over each contact
    /// direction's periodic slip (AFT, N samples per period), the linear part condensed
    /// onto the contact directions per harmonic 0..H, Newton per frequency; the normal
    /// load is held at its static value. The scene's [effects] table switches physics
    /// and outputs on and off; the run log lists the active effects and what each cost.
    /// Grounded springs with a `cubic` term α (the Duffing oscillator) get
    /// k* = k + ¾αA² from the library for their amplitude A and are iterated to
    /// consistency like contact points (modes fast and thesis; not harmonic_balance).
    ///
    /// Sweep direction ([sweep] direction): "up" (default) runs the frequencies
    /// ascending, "down" descending, "up_down" both; each frequency starts from the
    /// previous one's converged state, so a multi-valued response (Duffing) stays on its
    /// branch and jumps where the branch ends (a fold). Every CSV lists the frequencies
    /// ascending whatever the order they were run in.
    ///
    /// Files written to DIR (only after a valid scene and a successful run; a bad scene
    /// names file:line:column and key, and nothing is written):
    ///   results.csv   freq_hz, then per named output <name>_amp and <name>_phase_deg,
    ///                 then dissipated_power (power lost in the joints, force·length/time)
    ///                 and status (converged, not_converged, or singular: no response
    ///                 there, empty fields; also singular_frequencies in run.json);
    ///                 harmonic balance: first harmonic
    ///   results_down.csv  the same columns for the descending sweep (direction = "up_down";
    ///                 results.csv then holds the ascending one)
    ///   harmonics.csv harmonic balance only: freq_hz, then per output and h = 0..H
    ///                 <name>_h<h>_amp (h = 0: mean deviation from the static state)
    ///   results_without_contact_damping.csv  the same with d* = 0 (fast mode; written
    ///                 with the plots when the scene has contact damping)
    ///   points.csv    per contact point and frequency: position, pressure, amplitude,
    ///                 k*, d* (per area), energy per cycle, A/δ* (effects.point_energy_output);
    ///                 harmonic balance: first-harmonic amplitude, k* + iωd* = F̂₁/δ̂₁ of
    ///                 the closed loop, its energy per cycle
    ///   stick_slip.csv/.svg  points per regime over frequency (effects.stick_slip_map)
    ///   run.json      scene echo, effects with costs, passes, iterations, timings, C-API calls
    ///   frf.svg       FRF of the outputs with and without contact damping (and the
    ///                 sweep down for "up_down")
    ///   passes.svg    frequencies per pass (thesis mode: Fig. 4.33)
    #[command(verbatim_doc_comment)]
    Run {
        /// Scene file (TOML, see scenes/).
        scene: PathBuf,
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
        /// hysteresis; RK4 or Newmark, the scene's [time_domain] table): per frequency until
        /// periodic; writes results_time.csv, points_time.csv, run_time.json.
        #[arg(long)]
        time_domain: bool,
    },
    /// Frequency domain vs the time-domain reference: block stick and slip, the Duffing
    /// sweep up and down, coarse three beams. Writes validation.csv and validation.md.
    Validate {
        /// Output directory.
        #[arg(long, default_value = "out/validation")]
        out: PathBuf,
        /// Directory with block-stick.toml, block-slip.toml, three-beams.toml.
        #[arg(long, default_value = "scenes")]
        scenes: PathBuf,
        /// Cases (default all): block-stick, block-slip, duffing, softening-friction, three-beams.
        #[arg(long, value_delimiter = ',')]
        cases: Vec<String>,
    },
    /// One scene at a ladder of fidelities (linear stick, Simpson point counts, iteration
    /// tolerances, harmonic balance with H = 1, 3, 7, 15, time-domain steps and settling
    /// lengths): error against the most
    /// accurate time-domain run vs wall time. Writes tradeoff.csv, tradeoff.md and the
    /// Pareto plot tradeoff.svg; prints the frequency- vs time-domain speed ratio.
    Tradeoff {
        scene: PathBuf,
        /// Output directory.
        #[arg(long, default_value = "out/tradeoff")]
        out: PathBuf,
        /// Frequency (1/time); default the scene's only one, else its response peak.
        #[arg(long)]
        freq: Option<f64>,
    },
    /// Joint power loss against the amplitude of an output at resonance, one curve per
    /// screw torque (the scene's [loss_study] table; thesis Fig. 5.41–5.45): per torque
    /// the static step, the resonance (the scene's sweep, then a golden-section search),
    /// then the excitation scaled until the output reaches each amplitude. Writes
    /// loss.csv, loss.md (with the comparison against the reference points), loss.svg,
    /// and at the scene's own torque and the largest amplitude the contact maps
    /// contact_ratio.svg, contact_energy.svg and contact_<interface>.vtu (ParaView).
    #[command(verbatim_doc_comment)]
    Loss {
        scene: PathBuf,
        /// Output directory (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Instead: find the factor on every interface's k_T0 that matches the first
        /// reference point, print it, and write nothing.
        #[arg(long)]
        calibrate: bool,
        /// Instead: a mesh study at the first reference point's torque (its amplitude
        /// and a quarter of it) with every box's divisions × each factor, area-sampled
        /// and node-based; writes mesh_study.md and mesh_study.csv.
        #[arg(long, value_delimiter = ',', num_args = 1..)]
        mesh_study: Vec<usize>,
        /// With --mesh-study: multiply only these divisions, AXES[:PREFIX,…] (e.g. `z`,
        /// `x:jaw_,blade_in`: x of the boxes whose names start so); repeat for several,
        /// each compared with the scene itself. Default: every axis of every box.
        #[arg(long)]
        refine: Vec<String>,
        /// With --mesh-study: only the area-sampled law (half the time; the node-based
        /// columns are left out).
        #[arg(long)]
        sampled_only: bool,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Validate a scene and print a summary (nothing is run or written).
    Check { scene: PathBuf },
    /// Eigenfrequencies of the scene's model with every closed joint stuck (k_T0) after
    /// the static step: where to put the sweep.
    Modes {
        scene: PathBuf,
        /// Number of modes.
        #[arg(long, default_value_t = 6)]
        count: usize,
    },
    /// Cost of the nonlinear sweep relative to the linear sweep (same model and
    /// frequencies) for fast and thesis modes at about 1k, 10k and 100k DOF, with peak
    /// memory (getrusage maxrss). Prints a Markdown table.
    Bench {
        /// Approximate DOF counts.
        #[arg(long, value_delimiter = ',', default_values_t = vec![1_000usize, 10_000, 100_000])]
        dofs: Vec<usize>,
        /// Frequencies per sweep.
        #[arg(long, default_value_t = 20)]
        freqs: usize,
        /// Skip thesis mode above this DOF count (it costs passes × frequencies
        /// factorizations).
        #[arg(long, default_value_t = 20_000)]
        thesis_max_dofs: usize,
        /// Instead: cost against the number of contact points at about the first DOF
        /// count (1, 2, 4 elements per mm of thickness), fast mode only.
        #[arg(long)]
        contact_scan: bool,
    },
    /// Multi-harmonic balance (AFT through jointlin_point_step): cost vs H of a
    /// frequency sweep of the 3-DOF Jenkins chain, or with --scene of FE scenes (time per
    /// frequency split into mesh and contact parts), beside the first-order
    /// linearization. Prints a Markdown table per system.
    Mhb {
        /// Harmonics to run (the last row is the reference of the deviation column).
        #[arg(long, value_delimiter = ',', default_values_t = vec![1usize, 3, 7, 15])]
        harmonics: Vec<usize>,
        /// Frequencies per sweep (default 200 for the chain, 5 for scenes).
        #[arg(long)]
        freqs: Option<usize>,
        /// FE scenes to run instead of the chain (e.g. scenes/three-beams-coarse.toml,
        /// scenes/three-beams.toml).
        #[arg(long, value_delimiter = ',')]
        scene: Vec<PathBuf>,
        /// Band f_min,f_max (1/time) for scenes; default each scene's first refine band.
        #[arg(long, value_delimiter = ',', num_args = 2)]
        band: Vec<f64>,
        /// Force amplitude on the last mass.
        #[arg(long, default_value_t = 0.05)]
        force: f64,
    },
}

fn progress_bar(quiet: bool) -> ProgressBar {
    if quiet {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(1);
    pb.set_style(
        ProgressStyle::with_template("{msg:40} [{bar:40}] {pos}/{len} {elapsed}")
            .expect("static template")
            .progress_chars("=> "),
    );
    pb
}

/// Restores the default action of SIGPIPE (Rust ignores it, so `println!` to a closed
/// pipe panics): `jointlin modes X | head -1` then ends quietly like other Unix tools.
#[cfg(unix)]
fn default_sigpipe() {
    extern "C" {
        fn signal(signum: i32, handler: usize) -> usize;
    }
    const SIGPIPE: i32 = 13; // Linux, all architectures this builds on
    const SIG_DFL: usize = 0;
    // SAFETY: signal(2) with a valid signal number and SIG_DFL, before any thread starts.
    unsafe {
        signal(SIGPIPE, SIG_DFL);
    }
}

fn main() -> ExitCode {
    #[cfg(unix)]
    default_sigpipe();
    let cli = Cli::parse();
    match cli.command {
        Command::Run {
            scene,
            out,
            mode,
            harmonics,
            samples,
            no_plots,
            quiet,
            time_domain,
        } => {
            let mut s = match Scene::load(&scene) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if let Some(m) = mode {
                s.spec.iteration.mode = match m {
                    ModeArg::Fast => Mode::Fast,
                    ModeArg::Thesis => Mode::Thesis,
                    ModeArg::HarmonicBalance => Mode::HarmonicBalance,
                };
            }
            let it = &mut s.spec.iteration;
            it.harmonics = harmonics.or(it.harmonics);
            it.samples = samples.or(it.samples);
            // The overrides are checked by the scene's own rules.
            if let Some((key, msg)) = validate::validate(&s.spec).into_iter().next() {
                eprintln!(
                    "error: {}: with the command-line overrides, `{key}`: {msg}",
                    s.file
                );
                return ExitCode::from(2);
            }
            // No earlier run's marker survives this one; an interrupt says so.
            if let Err(e) = report::atomic::begin(&out) {
                eprintln!("error: {}: {e}", out.display());
                return ExitCode::from(1);
            }
            if time_domain {
                return time_domain_run(&s, &out, quiet);
            }
            let pb = progress_bar(quiet);
            let r = run(
                &s,
                Extras {
                    reference_without_damping: !no_plots,
                    condense_max: None,
                },
                &|label, done, total| {
                    pb.set_length(total as u64);
                    pb.set_position(done as u64);
                    pb.set_message(label.to_string());
                },
            );
            pb.finish_and_clear();
            let r = match r {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(1);
                }
            };
            eprintln!(
                "{}: {} free DOFs, {} contact points ({} closed), mode {:?}",
                s.file,
                r.problem.sys.dofs.n_free(),
                r.problem.contacts.len(),
                r.stat.closed.iter().filter(|&&c| c).count(),
                s.spec.iteration.mode
            );
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
            let unconverged = std::iter::once(&r.main)
                .chain(&r.down)
                .map(|sweep| sweep.converged.iter().filter(|&&c| !c).count())
                .sum::<usize>();
            eprintln!(
                "timings: build {:.3} s, static {:.3} s, sweep {:.3} s, reference {:.3} s; {} factorizations",
                r.seconds[0], r.seconds[1], r.seconds[2], r.seconds[3], r.main.factorizations
            );
            match report::write_all(&out, &s, &r, ReportOptions { plots: !no_plots }) {
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
            for (i, f) in r.main.freqs.iter().enumerate() {
                if let Some(e) = r.main.failure(i) {
                    eprintln!("warning: {f:e} Hz failed (status failed in results.csv): {e}");
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
            ExitCode::SUCCESS
        }
        Command::Loss {
            scene,
            out,
            calibrate,
            mesh_study,
            refine,
            sampled_only,
            quiet,
        } => loss(
            &scene,
            &out,
            calibrate,
            &mesh_study,
            &refine,
            !sampled_only,
            quiet,
        ),
        Command::Check { scene } => match Scene::load(&scene) {
            Ok(s) => {
                println!(
                    "{}: ok — {} bodies, {} interfaces, {} frequencies ({} to {}), mode {:?}",
                    s.file,
                    s.spec.bodies.len(),
                    s.spec.interfaces.len(),
                    s.frequencies().len(),
                    s.frequencies().first().copied().unwrap_or(0.0),
                    s.frequencies().last().copied().unwrap_or(0.0),
                    s.spec.iteration.mode
                );
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Modes { scene, count } => {
            let s = match Scene::load(&scene) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            match bench::stuck_modes(&s, count) {
                Ok(f) => {
                    for (i, v) in f.iter().enumerate() {
                        // Shortest round-trip form: the value can go into a scene's sweep.
                        println!("mode {}: {v} (1/time)", i + 1);
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    ExitCode::from(1)
                }
            }
        }
        Command::Bench {
            dofs,
            freqs,
            thesis_max_dofs,
            contact_scan,
        } => match if contact_scan {
            bench::contact_table(dofs[0], freqs, &mut std::io::stdout())
        } else {
            bench::table(&dofs, freqs, thesis_max_dofs, &mut std::io::stdout())
        } {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(1)
            }
        },
        Command::Validate { out, scenes, cases } => {
            let cases = match jointlin_harness::validate::Cases::parse(&cases) {
                Ok(c) => c,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            let rep = match jointlin_harness::validate::run(&scenes, cases, &|l| eprintln!("{l}")) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(1);
                }
            };
            print!("{}", jointlin_harness::validate::markdown(&rep));
            report_written(jointlin_harness::validate::write(&out, &rep))
        }
        Command::Mhb {
            harmonics,
            freqs,
            scene,
            band,
            force,
        } => {
            use jointlin_harness::mhb::{bench, fe_bench};
            if scene.is_empty() {
                let freqs = freqs.unwrap_or(200);
                let rows = bench::sweep_table(force, 0.3, 0.8, freqs, &harmonics);
                println!("{}", bench::markdown(&rows, force, 0.3, 0.8, freqs));
                return ExitCode::SUCCESS;
            }
            for path in scene {
                let s = match Scene::load(&path) {
                    Ok(s) => s,
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::from(2);
                    }
                };
                let band = (band.len() == 2).then(|| (band[0], band[1]));
                let log = |l: &str| eprintln!("{}: {l}", path.display());
                match fe_bench::table(&s, band, freqs.unwrap_or(5), &harmonics, &log) {
                    Ok(t) => println!("{}", fe_bench::markdown(&t)),
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::from(1);
                    }
                }
            }
            ExitCode::SUCCESS
        }
        Command::Tradeoff { scene, out, freq } => {
            let s = match Scene::load(&scene) {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            let t = match jointlin_harness::tradeoff::study(&s, freq, &|l| eprintln!("{l}")) {
                Ok(t) => t,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(1);
                }
            };
            print!("{}", jointlin_harness::tradeoff::markdown(&t));
            report_written(jointlin_harness::tradeoff::write(&out, &t))
        }
    }
}

/// `jointlin loss`.
fn loss(
    scene: &std::path::Path,
    out: &std::path::Path,
    calibrate: bool,
    mesh_study: &[usize],
    refine: &[String],
    node_based: bool,
    quiet: bool,
) -> ExitCode {
    use jointlin_harness::loss;
    let s = match Scene::load(scene) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let Some(st) = s.spec.loss_study.clone() else {
        eprintln!("error: {}: no [loss_study] table", s.file);
        return ExitCode::from(2);
    };
    if calibrate {
        return match loss::calibrate_k_t0(&s, &|l| eprintln!("{l}")) {
            Ok((factor, p)) => {
                for i in &s.spec.interfaces {
                    println!(
                        "{}: k_t0_per_area = {:.6e} (× {factor:.5}); P = {p:.4} {}",
                        i.name,
                        i.k_t0_per_area * factor,
                        st.power_unit
                    );
                }
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(1)
            }
        };
    }
    if !mesh_study.is_empty() {
        return loss_mesh_study(&s, out, mesh_study, refine, node_based, quiet);
    }
    let t = std::time::Instant::now();
    let r = match with_progress(quiet, st.torques.len(), |p| loss::run_study(&s, p)) {
        Ok(r) => r,
        Err(code) => return code,
    };
    print!("{}", loss::report::markdown(&s, &st, &r));
    eprintln!("{:.1} s", t.elapsed().as_secs_f64());
    report_written(loss::report::write(out, &s, &r))
}

/// Runs `work` under a progress bar of `steps` steps (each message it reports is one
/// step); an error is printed and becomes exit code 1.
fn with_progress<T, E: std::fmt::Display>(
    quiet: bool,
    steps: usize,
    work: impl FnOnce(&(dyn Fn(&str) + Sync)) -> Result<T, E>,
) -> Result<T, ExitCode> {
    let pb = progress_bar(quiet);
    pb.set_length(steps as u64);
    let r = work(&|l| {
        pb.set_message(l.to_string());
        pb.inc(1);
    });
    pb.finish_and_clear();
    r.map_err(|e| {
        eprintln!("error: {e}");
        ExitCode::from(1)
    })
}

/// `jointlin loss --mesh-study`.
fn loss_mesh_study(
    s: &Scene,
    out: &std::path::Path,
    factors: &[usize],
    refine: &[String],
    node_based: bool,
    quiet: bool,
) -> ExitCode {
    use jointlin_harness::loss::mesh;
    if factors.contains(&0) {
        eprintln!("error: --mesh-study factors must be >= 1");
        return ExitCode::from(2);
    }
    let refinements = if refine.is_empty() {
        vec![mesh::Refinement::everything()]
    } else {
        match refine.iter().map(|r| mesh::Refinement::parse(r)).collect() {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: --refine {e}");
                return ExitCode::from(2);
            }
        }
    };
    let t = std::time::Instant::now();
    let steps = mesh::laws(node_based).len() * mesh::plan(factors, refinements.len()).len();
    let rows = match with_progress(quiet, steps, |p| {
        mesh::study(s, factors, &refinements, node_based, p)
    }) {
        Ok(r) => r,
        Err(code) => return code,
    };
    let md = mesh::markdown(s, &rows);
    print!("{md}");
    eprintln!("{:.1} s", t.elapsed().as_secs_f64());
    let write = || -> Result<Vec<std::path::PathBuf>, String> {
        let io = |e: std::io::Error| format!("{}: {e}", out.display());
        std::fs::create_dir_all(out).map_err(io)?;
        let (a, b) = (out.join("mesh_study.md"), out.join("mesh_study.csv"));
        std::fs::write(&a, md).map_err(io)?;
        std::fs::write(&b, mesh::csv(&rows)).map_err(io)?;
        Ok(vec![a, b])
    };
    report_written(write())
}

/// `jointlin run --time-domain`.
fn time_domain_run(s: &Scene, out: &std::path::Path, quiet: bool) -> ExitCode {
    use jointlin_harness::time::{scene_run, TimeSettings};
    let settings = match TimeSettings::from_spec(s.spec.time_domain.as_ref()) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(2);
        }
    };
    let pb = progress_bar(quiet);
    let r = scene_run::run_scene(s, &settings, &|done, total| {
        pb.set_length(total as u64);
        pb.set_position(done as u64);
        pb.set_message("time domain");
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
    report_written(scene_run::write(out, s, &r))
}

/// Lists the files a report command wrote, or its write error; the exit code follows.
fn report_written<E: std::fmt::Display>(written: Result<Vec<std::path::PathBuf>, E>) -> ExitCode {
    match written {
        Ok(files) => {
            for f in files {
                eprintln!("wrote {}", f.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error writing reports: {e}");
            ExitCode::from(1)
        }
    }
}
