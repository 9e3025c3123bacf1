//! `jointlin check SCENE|DECK.inp`: validates a scene and builds its model (so that
//! every error a run meets before its first solve is found here), or reads an Abaqus-format deck and
//! pairs its contact surfaces, and prints a summary.

use std::path::PathBuf;
use std::process::ExitCode;

use super::{load_scene_with, SceneOverrides};
use jointlin_harness::input::scene::Scene;
use jointlin_harness::input::{deck, format_of, Format};
use jointlin_harness::model::{self, Problem};
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::solve::cost;
use jointlin_harness::solve::modal_stuck::{stuck_modes, ModeCount};
use jointlin_harness::util::number::{sig, sig_n};

// The command's help is the doc comment of `Command::Check`.
#[derive(clap::Args)]
pub struct Args {
    #[arg(required_unless_present = "keywords")]
    scene: Option<PathBuf>,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Print the deck keywords the reader implements, each with its parameters, as
    /// the README's Markdown table, and exit.
    #[arg(long)]
    keywords: bool,
    /// Also compute the stuck modes (joints closed and stuck after the static step)
    /// below the sweep's highest frequency and list them (as `jointlin modes`; seconds
    /// to minutes on a large model).
    #[arg(long)]
    modes: bool,
    /// Also forecast the run's time: one factorization and one solve of the dynamic
    /// stiffness timed here, times the counts the scene's mode needs.
    #[arg(long)]
    forecast: bool,
}

pub fn main(a: Args) -> ExitCode {
    let Some(scene) = a.scene.clone().filter(|_| !a.keywords) else {
        print!("{}", deck::keywords::markdown_table());
        return ExitCode::SUCCESS;
    };
    if format_of(&scene) == Format::AbaqusDeck {
        return check_deck(&scene, &a);
    }
    let s = match load_scene_with(&scene, &a.overrides.set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    // What only the model build finds (contact faces whose nodes do not match, ties
    // between non-conforming meshes), with the scene's location; lumped scenes with
    // [[joints]] are `jointlin backbone`'s and have no FE model.
    let mut built = None;
    if s.spec.is_lumped() {
        // The lumped system reads the [[matrices]] files: their errors name file:line.
        if let Err(e) = model::lumped::build(&s) {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(2);
        }
    } else {
        match model::build(&s) {
            // A deck (a scene's `model`) names its own file:line.
            Err(model::BuildError::Deck(e)) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            Err(e) => {
                eprintln!("error: {}", model::locate(&s, &e));
                return ExitCode::from(2);
            }
            Ok(p) => built = Some(p),
        }
    }
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
    if let Some(p) = built {
        println!(
            "model: {} free DOFs, {} contact points",
            p.sys.dofs.n_free(),
            p.contacts.len()
        );
        for w in &p.warnings {
            eprintln!("warning: {w}");
        }
        extras(&a, &s, &p);
    }
    ExitCode::SUCCESS
}

/// `jointlin check DECK.inp`: reads the deck, pairs its contact surfaces, prints the
/// summary and the reader's warnings; exit 2 with `file:line: *KEYWORD: message`.
fn check_deck(path: &std::path::Path, a: &Args) -> ExitCode {
    let result = deck::read(path).and_then(|(d, warnings)| {
        deck::summary::summary(&d, &path.display().to_string()).map(|s| (s, warnings))
    });
    match result {
        Ok((summary, warnings)) => {
            print!("{summary}");
            let printed: Vec<String> = warnings.iter().map(|w| w.to_string()).collect();
            for w in &printed {
                eprintln!("warning: {w}");
            }
            run_checks(path, a, &printed)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// What `jointlin run` meets before its first solve on a deck: the run-level reading
/// (units comment, property tables, densities, steps a run can honour) and the model
/// build (ties, contact pairs, loads, outputs); exit 2 with the deck's file:line. The
/// build's warnings are printed but for those in `printed` (the reader's, already out).
fn run_checks(path: &std::path::Path, a: &Args, printed: &[String]) -> ExitCode {
    let s = match load_scene_with(path, &a.overrides.set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    match model::build(&s) {
        Ok(p) => {
            println!(
                "run checks: ok — {} free DOFs, {} contact points, {} frequencies",
                p.sys.dofs.n_free(),
                p.contacts.len(),
                s.frequencies().len()
            );
            for w in p.warnings.iter().filter(|w| !printed.contains(w)) {
                eprintln!("warning: {w}");
            }
            extras(a, &s, &p);
            ExitCode::SUCCESS
        }
        Err(model::BuildError::Deck(e)) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("error: {}: building the model: {e}", path.display());
            ExitCode::from(2)
        }
    }
}

/// The time a run of the scene will take, from one factorization and solve timed here
/// ([`cost`]); a model that cannot be factored at the first frequency says so (the run
/// then reports its singular frequencies).
fn print_forecast(s: &Scene, p: &Problem) {
    let freqs = s.frequencies();
    let Some(&f0) = freqs.first() else { return };
    let it = &s.spec.iteration;
    let fu = frequency_unit(&s.spec.units);
    let unit = &fu.text;
    match cost::measure(p, 2.0 * std::f64::consts::PI * f0) {
        Ok(m) => {
            let f = cost::forecast(
                &m,
                freqs.len(),
                it.mode,
                p.contacts.len(),
                it.harmonics.unwrap_or(1),
                it.max_passes,
                true,
            );
            println!(
                "time forecast: one factorization of the dynamic stiffness {} s, one solve {} s (measured here at {} {unit}); {} frequencies in mode {:?}: {}–{} factorizations, {}–{} solves, about {}–{} s with the plots' reference sweep (--no-plots halves it), plus the static step",
                sig_n(m.factorization, 2),
                sig_n(m.solve, 2),
                sig(fu.show(f0)),
                freqs.len(),
                it.mode,
                f.factorizations[0],
                f.factorizations[1],
                f.solves[0],
                f.solves[1],
                sig_n(f.seconds[0], 2),
                sig_n(f.seconds[1], 2),
            );
        }
        Err(e) => println!(
            "time forecast: none (the dynamic stiffness at {} {unit}: {e})",
            sig(fu.show(f0))
        ),
    }
}

/// What --modes and --forecast ask for.
fn extras(a: &Args, s: &Scene, p: &Problem) {
    if a.modes {
        print_modes(s);
    }
    if a.forecast {
        print_forecast(s, p);
    }
}

/// Most stuck modes the summary lists.
const SUMMARY_MODES: usize = 50;

/// The stuck modes (joints closed and stuck after the static step) below the sweep's
/// highest frequency, as `jointlin modes` computes them; a model whose modes cannot be
/// computed says why (the run may still work: it never needs them).
fn print_modes(s: &Scene) {
    let fu = frequency_unit(&s.spec.units);
    let unit = &fu.text;
    let count = ModeCount::Band {
        factor: 1.0,
        min: 1,
        max: SUMMARY_MODES,
    };
    match stuck_modes(s, count) {
        Ok(m) => {
            let top = m.limit.unwrap_or(0.0);
            let below: Vec<String> = m
                .band
                .modes
                .frequencies_hz()
                .into_iter()
                .filter(|&f| f <= top)
                .map(|f| sig_n(fu.show(f), 5))
                .collect();
            let more = if m.band.complete { "" } else { "at least " };
            println!(
                "stuck modes below the sweep's top {} {unit}: {more}{}{}{}",
                sig(fu.show(top)),
                below.len(),
                if below.is_empty() { "" } else { " — " },
                below.join(", ")
            );
        }
        Err(e) => println!("stuck modes: not computed ({e})"),
    }
}
