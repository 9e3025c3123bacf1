//! The commands of `jointlin`, one file each: the clap arguments, the plumbing from the
//! input to the study, the run log on stderr and the exit code (0 done, 1 the run
//! failed, 2 the input or the arguments are wrong).
// The doc comments of the clap arguments below are the commands' help texts, written
// for the terminal: `[sweep]`, `[[outputs]]` and `<SCENE>` there are TOML tables and
// placeholders, not links or HTML.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

mod backbone;
mod bench;
mod check;
mod deck;
mod effects;
mod export;
mod loss;
mod man;
mod matrices;
mod mhb;
mod modes;
mod reduce;
mod run;
mod run_lumped;
mod run_lumped_time;
mod tradeoff;
mod validate;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use jointlin_harness::capi;
use jointlin_harness::input::{self, scene::overrides::Override, scene::Reading, scene::Scene};
use jointlin_harness::util::progress::progress_bar;
use jointlin_harness::util::{atomic, provenance};

#[derive(Parser)]
#[command(
    name = "jointlin",
    version,
    about = "Frequency-domain joint contact studies: scenes → static preload → steady-state sweeps with linearized contact (k*, d*) through the jointlin C API"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Run a scene or an Abaqus-format deck (.inp; docs/own-model.md, "Bring your own model"):
    /// static preload step, steady-state sweep, reports.
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
    /// Every column name carries the scene's [units] (below for N, mm, s; another time
    /// unit gives frequency_per_<time>):
    ///   results.csv   frequency_Hz, then per named output <name>_amp_mm and
    ///                 <name>_phase_deg, then dissipated_power_N_mm_per_s (power lost in
    ///                 the joints) and status (converged, not_converged, or singular: no response
    ///                 there, empty fields; also singular_frequencies in run.json);
    ///                 harmonic balance: first harmonic
    ///   results_down.csv  the same columns for the descending sweep (direction = "up_down";
    ///                 results.csv then holds the ascending one)
    ///   harmonics.csv harmonic balance only: frequency_Hz, then per output
    ///                 <name>_h0_mean_mm (mean deviation from the static state) and per
    ///                 h = 1..H <name>_h<h>_amp_mm, <name>_h<h>_phase_deg: over a period
    ///                 u(t) = mean + Σ amp_h cos(h ω t + phase_h)
    ///   results_without_contact_damping.csv  the same with d* = 0 (fast mode; written
    ///                 with the plots when the scene has contact damping)
    ///   points.csv    per contact point and frequency: position, pressure, amplitude,
    ///                 k*, d* (per area), energy per cycle, A/δ*, the node (a deck's slave
    ///                 node id) and the frame n, t1, t2 (effects.point_energy_output);
    ///                 harmonic balance: first-harmonic amplitude, k* + iωd* = F̂₁/δ̂₁ of
    ///                 the closed loop, its energy per cycle
    ///   loops.csv/.svg harmonic balance only: every closed point's loop over one period
    ///                 at the largest converged response (u1, u2, the overclosure where
    ///                 normal_load_variation, f1, f2, normal force; docs/outputs.md)
    ///   stick_slip.csv/.svg  points per regime over frequency (effects.stick_slip_map)
    ///   run.json      written last: provenance (schema version, versions, command
    ///                 line, time, SHA-256 of every input file; docs/outputs.md), scene
    ///                 echo, effects with costs, passes, iterations, timings, C-API calls
    ///   frf.svg       FRF of the outputs with and without contact damping (and the
    ///                 sweep down for "up_down"); frequencies that did not converge
    ///                 marked with a red cross
    ///   passes.svg    frequencies per pass (thesis mode: Fig. 4.33; not for one pass)
    ///
    /// Progress on stderr: a bar on a terminal; in a batch job (stderr a file or pipe)
    /// a line per stage and one at least every JOINTLIN_PROGRESS_SECONDS (default 10)
    /// with the elapsed time and the time left; none with --quiet.
    #[command(verbatim_doc_comment)]
    Run(run::Args),
    /// Frequency domain vs the time-domain reference: block stick and slip, the Duffing
    /// sweep up and down, coarse three beams. Writes validation.csv and validation.md.
    Validate(validate::Args),
    /// One scene at a ladder of fidelities (linear stick, Simpson point counts, iteration
    /// tolerances, harmonic balance with H = 1, 3, 7, 15, time-domain steps and settling
    /// lengths): error against the most
    /// accurate time-domain run vs wall time. Writes tradeoff.csv, tradeoff.md and the
    /// Pareto plot tradeoff.svg; prints the frequency- vs time-domain speed ratio.
    Tradeoff(tradeoff::Args),
    /// The contact point models beyond the thesis on one harmonic-balance scene: its sweep
    /// with the thesis's model, with `coupled_slip`, with `normal_load_variation` and with
    /// both (docs/contact3d.md): peak, power, three-direction steps and wall time of each.
    /// Writes effects.csv, effects.md and the FRFs effects.svg.
    Effects(effects::Args),
    /// Joint power loss against the amplitude of an output at resonance, one curve per
    /// screw torque (the scene's [loss_study] table; thesis Fig. 5.41–5.45): per torque
    /// the static step, the resonance (the scene's sweep, then a golden-section search),
    /// then the excitation scaled until the output reaches each amplitude. Writes
    /// loss.csv, loss.md (with the comparison against the reference points), loss.svg,
    /// and at the scene's own torque and the largest amplitude the contact maps
    /// contact_ratio.svg, contact_energy.svg and contact_<interface>.vtu (ParaView).
    #[command(verbatim_doc_comment)]
    Loss(loss::Args),
    /// Validate a scene or an Abaqus-format deck (.inp) and print a summary (nothing is
    /// run or written): the model's free DOFs and contact points; with --modes the stuck
    /// modes below the sweep's top, with --forecast the time a run will take (from one
    /// factorization and solve timed here).
    Check(check::Args),
    /// Write a scene as an Abaqus/Standard job: FILE (the input deck), sweep.frq and
    /// jointlin.cfg beside it (docs/abaqus.md, "Using jointlin from Abaqus").
    ///
    /// The deck is the scene's model node for node: *NODE, *ELEMENT C3D8I per box,
    /// *MATERIAL with *DAMPING (Rayleigh), *SOLID SECTION, clamps as *BOUNDARY, ties as
    /// *TIE, each interface as *SURFACE INTERACTION, USER (the shim's 12 properties,
    /// DEPVAR=57) with its *CONTACT PAIR, step 1 *STATIC with the preload, step 2
    /// *STEADY STATE DYNAMICS, DIRECT with *INCLUDE, INPUT=sweep.frq (one frequency per
    /// line) and the harmonic loads, *NODE PRINT/*NODE OUTPUT of U for every output
    /// (node set named after it), and the `** jointlin units:` comment. jointlin.cfg is
    /// the UEXTERNALDB configuration: the scene's [iteration] and the absolute tolerance
    /// of --mode thesis. `jointlin run FILE`
    /// gives the scene's results (with --mode thesis for a thesis-mode scene).
    ///
    /// What a deck cannot express is an error naming the scene key (exit 2, nothing
    /// written): lumped masses, springs, joints, an initial gap, area_samples, a
    /// downward sweep, harmonic balance, physics switched off in [effects]. A load's
    /// phase is exported (real and imaginary parts of *CLOAD).
    #[command(verbatim_doc_comment)]
    Export(export::Args),
    /// Modes of the scene's (or deck's) model with every closed joint stuck (k_T0) after
    /// the static step: where to put the sweep.
    ///
    /// By default every mode below 1.5 × the sweep's highest frequency (at least 6, at
    /// most 200; --count N for exactly N; a deck's *FREQUENCY step gives N). Prints a Markdown table in the scene's units
    /// (frequency in Hz when [units] time = "s", else 1/time): per mode its label, the
    /// dominant direction (largest kinetic-energy share), the kinetic-energy shares of
    /// the cross-sections' motion across the body's axis (its longest extent):
    /// longitudinal, bending, torsion and section (the sections deform: plate modes),
    /// and the effective masses per direction. Labels: longitudinal_x, bending_xz (axis
    /// x, moving along z), torsion_x, section, translation_z (lumped masses).
    ///
    /// A lumped scene (mass bodies, [[matrices]], springs, joints) lists its frequencies
    /// with every joint stuck (k_T0) and writes modes.csv (mode, frequency) only.
    ///
    /// Files written to DIR with --out DIR:
    ///   modes.csv   mode, frequency_Hz (or frequency_per_<time>), label, dominant,
    ///               share_longitudinal, share_bending, share_torsion, share_section,
    ///               effective_mass_<x|y|z>_<mass>, effective_inertia_<x|y|z>_<mass>_<length>2
    ///               (about the mass centre), backward_error of K φ = λ M φ
    ///               (‖Kφ − λMφ‖₁ / (‖K‖₁ + |λ|‖M‖₁)‖φ‖₁)
    ///   modes.vtu   the mesh with a point vector per mode, mode_<i>_<f>_<Hz|per_time>,
    ///               scaled to a largest nodal displacement of 1 (ParaView: Warp By Vector)
    #[command(verbatim_doc_comment)]
    Modes(modes::Args),
    /// Cost of the nonlinear sweep relative to the linear sweep (same model and
    /// frequencies) for fast and thesis modes at about 1k, 10k and 100k DOF, with peak
    /// memory (getrusage maxrss). Prints a Markdown table.
    Bench(bench::Args),
    /// Multi-harmonic balance (AFT through jointlin_point_step): cost vs H of a
    /// frequency sweep of the 3-DOF Jenkins chain, or with --scene of FE scenes (time per
    /// frequency split into mesh and contact parts), beside the first-order
    /// linearization. Prints a Markdown table per system.
    Mhb(mhb::Args),
    /// Backbone of a scene's mode: natural frequency and damping ratio against the
    /// modal amplitude, of a lumped scene directly and of an FE scene or deck reduced
    /// onto its contact directions (docs/backbone-fe.md); first order (complex
    /// eigenvalues with every joint's k*, d* through jointlin_linearize consistent with
    /// the mode's own amplitudes) or with --harmonics H the extended periodic motion
    /// concept (AFT through jointlin_point_step). Writes backbone.csv, backbone.svg and
    /// run.json.
    Backbone(backbone::Args),
    /// Reduce an FE scene or deck (Craig–Bampton, docs/reduce.md): after the static
    /// preload, onto the closed contact points' two tangential relative displacements,
    /// the outputs and the load, plus the interior modes of the structure with every
    /// joint stuck. Writes DIR/K.mtx, M.mtx (D.mtx with material damping), dofs.csv and
    /// scene.toml: a `[[matrices]]` model with one `[[joints]]` entry per contact
    /// direction (the point's law, its normal force from the preload, k_T0 times its
    /// area), the load and the outputs, and the full scene's units, sweep, iteration and
    /// effects, which `run`, `backbone` and `modes` take as any lumped scene;
    /// run.json compares its stuck frequencies with the full model's.
    Reduce(reduce::Args),
    /// Models given by their matrices (`[[matrices]]` of a scene): converters of FE
    /// codes' matrix output.
    #[command(subcommand)]
    Matrices(matrices::Args),
    /// Abaqus-format decks from other tools: converters of mesh generators' exports.
    #[command(subcommand)]
    Deck(deck::Args),
    /// Write the man pages of the program and of every command (jointlin.1,
    /// jointlin-run.1, …) into DIR, generated from this help; `make install` puts them
    /// in PREFIX/share/man/man1.
    Man(man::Args),
}

/// Runs `jointlin` with the command line `args` (the program's name first), as the
/// program does: clap's help, version and errors printed, the exit code returned. The
/// `jointlin` program and the Python package's child process both start here.
pub fn run_args<I, T>(args: I) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let code = match Cli::try_parse_from(args) {
        Ok(cli) => dispatch(cli.command),
        Err(e) => {
            // Help and version go to stdout, errors to stderr, as `Cli::parse` prints them.
            let _ = e.print();
            return u8::try_from(e.exit_code()).unwrap_or(2);
        }
    };
    // ExitCode keeps its value private; the commands only return 0, 1 and 2.
    (0u8..=255)
        .find(|&v| ExitCode::from(v) == code)
        .unwrap_or(1)
}

/// Runs the command.
pub fn dispatch(command: Command) -> ExitCode {
    match command {
        Command::Run(a) => run::main(a),
        Command::Validate(a) => validate::main(a),
        Command::Tradeoff(a) => tradeoff::main(a),
        Command::Effects(a) => effects::main(a),
        Command::Loss(a) => loss::main(a),
        Command::Check(a) => check::main(a),
        Command::Export(a) => export::main(a),
        Command::Modes(a) => modes::main(a),
        Command::Bench(a) => bench::main(a),
        Command::Mhb(a) => mhb::main(a),
        Command::Backbone(a) => backbone::main(a),
        Command::Reduce(a) => reduce::main(a),
        Command::Matrices(a) => matrices::main(a),
        Command::Deck(a) => deck::main(a),
        Command::Man(a) => man::main(a),
    }
}

/// Reads an input through the one input path ([`input::load`]) as a scene (a deck as the
/// scene of its run); a bad one is printed (a scene's error names file:line:column and
/// key, a deck's file:line and keyword) and becomes exit code 2.
fn load_scene(path: &Path) -> Result<Scene, ExitCode> {
    load_scene_with(path, &[])
}

/// `--set KEY=VALUE` (repeatable): a scene value changed before the scene is read.
#[derive(clap::Args)]
pub struct SceneOverrides {
    /// Change a value of the scene before it is read: KEY a dotted path
    /// (`iteration.mode`, `interfaces.*.rule` for every interface, `interfaces.0.mu`),
    /// VALUE a TOML value or a bare word; `KEY=` removes the key; a table the scene
    /// leaves out (a deck's scene without [iteration]) is created. Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<Override>,
}

/// The build's notes and warnings, one `note:` or `warning:` line each on stderr.
fn print_findings(p: &jointlin_harness::model::Problem) {
    for n in &p.notes {
        eprintln!("note: {n}");
    }
    for w in &p.warnings {
        eprintln!("warning: {w}");
    }
}

/// [`load_scene`] with overrides.
fn load_scene_with(path: &Path, set: &[Override]) -> Result<Scene, ExitCode> {
    load_scene_for(path, set, Reading::Forced)
}

/// [`load_scene_with`] for a command that reads the scene as `reading`.
fn load_scene_for(path: &Path, set: &[Override], reading: Reading) -> Result<Scene, ExitCode> {
    match input::load_for(path, set, reading) {
        Ok(i) => Ok(i.into_scene()),
        Err(e) => {
            eprintln!("error: {e}");
            Err(ExitCode::from(2))
        }
    }
}

/// A study command (`command`, as run.json names it): loads the scene, runs `study` on
/// it, prints its Markdown and writes its files into `out`, then run.json
/// ([`study_written`]); exit code 2 for a bad scene, 1 for a failed study or write.
fn study_main<T, E: std::fmt::Display>(
    command: &str,
    scene: &Path,
    set: &[Override],
    out: &Path,
    study: impl FnOnce(&Scene) -> Result<T, E>,
    markdown: impl FnOnce(&T) -> String,
    write: impl FnOnce(&Path, &T) -> Result<Vec<PathBuf>, String>,
) -> ExitCode {
    let s = match load_scene_with(scene, set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if let Err(code) = begin_outputs(out) {
        return code;
    }
    let started = std::time::Instant::now();
    let t = match study(&s) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    print!("{}", markdown(&t));
    study_written(command, &s, out, started, write(out, &t))
}

/// Prepares `out` for a command's files ([`atomic::begin`]: an earlier run.json and
/// leftover partial files removed, the interrupt notice installed); exit 1 if it cannot.
fn begin_outputs(out: &Path) -> Result<(), ExitCode> {
    atomic::begin(out).map_err(|e| {
        eprintln!("error: {}: {e}", out.display());
        ExitCode::from(1)
    })
}

/// After a study wrote `written` into `out`: run.json last (the provenance head,
/// the scene echo, the files written and the study's wall time in seconds), then the
/// list of files on stderr.
fn study_written(
    command: &str,
    scene: &Scene,
    out: &Path,
    started: std::time::Instant,
    written: Result<Vec<PathBuf>, String>,
) -> ExitCode {
    let written = written.and_then(|mut files| {
        let names: Vec<String> = files
            .iter()
            .map(|f| {
                f.file_name()
                    .unwrap_or_default()
                    .to_string_lossy()
                    .into_owned()
            })
            .collect();
        let head = provenance::head(command, &capi::abi_version(), &scene.sources);
        let body = serde_json::json!({
            "scene": {"file": scene.file, "spec": scene.spec, "text": scene.text},
            "files": names,
            "seconds": started.elapsed().as_secs_f64(),
        });
        let text = serde_json::to_string_pretty(&provenance::with_head(head, body))
            .map_err(|e| e.to_string())?;
        files.push(atomic::write_marker(out, &text)?);
        Ok(files)
    });
    report_written(written)
}

/// Runs `work` under a progress bar of `steps` steps (each message it reports is one
/// step); an error is printed and becomes exit code 1.
fn with_progress<T, E: std::fmt::Display>(
    quiet: bool,
    steps: usize,
    work: impl FnOnce(&(dyn Fn(&str) + Sync)) -> Result<T, E>,
) -> Result<T, ExitCode> {
    let mut pb = progress_bar(quiet);
    pb.set_length(steps as u64);
    let r = work(&|l| {
        pb.set_message(l);
        pb.inc(1);
    });
    pb.finish_and_clear();
    r.map_err(|e| {
        eprintln!("error: {e}");
        ExitCode::from(1)
    })
}

/// Lists the files a report command wrote, or its write error; the exit code follows.
fn report_written<E: std::fmt::Display>(written: Result<Vec<PathBuf>, E>) -> ExitCode {
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

/// Restores the default action of SIGPIPE (Rust ignores it, so `println!` to a closed
/// pipe panics): `jointlin modes X | head -1` then ends quietly like other Unix tools.
#[cfg(unix)]
pub fn default_sigpipe() {
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
