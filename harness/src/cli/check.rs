//! `jointlin check SCENE|DECK.inp`: validates a scene and builds its model (so that
//! every error a run meets before its first solve is found here), or reads an Abaqus-format deck and
//! pairs its contact surfaces, and prints a summary.

use std::path::PathBuf;
use std::process::ExitCode;

use super::{load_scene_with, print_findings, SceneOverrides};
use jointlin_harness::input::scene::Scene;
use jointlin_harness::input::{deck, format_of, Format};
use jointlin_harness::model::{self, BuildError, Built, Problem};
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::solve::cost;
use jointlin_harness::solve::modal_stuck::{stuck_modes, ModeCount};
use jointlin_harness::util::number::{counted, sig, sig_n};

// The command's help is the doc comment of `Command::Check`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML, see scenes/) or Abaqus-format deck (.inp).
    #[arg(required_unless_present = "keywords")]
    scene: Option<PathBuf>,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Print the deck keywords the reader implements, each with its parameters, as
    /// the Markdown table of docs/own-model.md, and exit.
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
    // between non-conforming meshes), with the scene's location; a lumped scene's
    // system is built instead (its [[matrices]] files read), with no FE findings.
    let mut built = None;
    let mut parts = model_parts(&s);
    match model::model(&s) {
        Ok(Built::Lumped(l)) => parts = format!("{parts} ({} DOFs)", l.dofs.len()),
        Ok(Built::Fe(p)) => built = Some(p),
        // The lumped system reads the [[matrices]] files: their errors name file:line.
        Err(BuildError::Lumped(e)) => {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(2);
        }
        // A deck (a scene's `model`) names its own file:line.
        Err(BuildError::Deck(e)) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
        Err(e) => {
            eprintln!("error: {}", model::locate(&s, &e));
            return ExitCode::from(2);
        }
    }
    let fu = frequency_unit(&s.spec.units);
    println!(
        "{}: ok — {parts}, {} ({} to {} {}), mode {}",
        s.file,
        counted(s.frequencies().len(), "frequency", "frequencies"),
        fu.show(s.frequencies().first().copied().unwrap_or(0.0)),
        fu.show(s.frequencies().last().copied().unwrap_or(0.0)),
        fu.text,
        s.spec.iteration.mode.name()
    );
    if let Some(p) = built {
        println!(
            "model: {} free DOFs, {}",
            p.sys.dofs.n_free(),
            counted(p.contacts.len(), "contact point", "contact points")
        );
        print_findings(&p);
        extras(&a, &s, &p);
    }
    ExitCode::SUCCESS
}

/// What the scene's model is made of, counted: the deck of `model` (nodes, elements,
/// contact pairs, ties), or the bodies, matrices, springs, joints and interfaces the
/// scene lists (those it has).
fn model_parts(s: &Scene) -> String {
    let count = |n: usize, word: &str| counted(n, word, &format!("{word}s"));
    if let Some(job) = &s.deck {
        let d = &job.deck;
        return format!(
            "deck {}: {}, {}, {}, {}",
            job.file,
            count(d.nodes.len(), "node"),
            count(d.elements.len(), "element"),
            count(d.contact_pairs.len(), "contact pair"),
            count(d.ties.len(), "tie")
        );
    }
    let sp = &s.spec;
    let listed: Vec<String> = [
        (sp.bodies.len(), "body"),
        (sp.matrices.len(), "matrix model"),
        (sp.springs.len(), "spring"),
        (sp.joints.len(), "joint"),
        (sp.interfaces.len(), "interface"),
        (sp.ties.len(), "tie"),
    ]
    .into_iter()
    .filter(|&(n, _)| n > 0)
    .map(|(n, w)| {
        if w == "body" && n != 1 {
            format!("{n} bodies")
        } else {
            count(n, w)
        }
    })
    .collect();
    if listed.is_empty() {
        "no model parts".into()
    } else {
        listed.join(", ")
    }
}

/// `jointlin check DECK.inp`: reads the deck, pairs its contact surfaces, prints the
/// summary and the reader's warnings; exit 2 with `file:line: *KEYWORD: message`.
fn check_deck(path: &std::path::Path, a: &Args) -> ExitCode {
    // Everything a run reads first (the deck, its units comment, jointlin.cfg beside
    // it), so nothing is called ok that the run then refuses.
    let s = match load_scene_with(path, &a.overrides.set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let Some(job) = s.deck.as_ref() else {
        eprintln!("error: {}: not read as a deck", path.display());
        return ExitCode::from(2);
    };
    let frequency = frequency_unit(&s.spec.units).text;
    match deck::summary::summary(&job.deck, &job.file, &frequency) {
        Ok(summary) => print!("{summary}"),
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    }
    run_checks(&s, a)
}

/// What `jointlin run` meets before its first solve on a deck after reading it: the
/// model build (ties, contact pairs, loads, outputs); exit 2 with the deck's file:line.
/// The reader's and the build's warnings are printed.
fn run_checks(s: &Scene, a: &Args) -> ExitCode {
    match model::build(s) {
        Ok(p) => {
            print_findings(&p);
            println!(
                "run checks: ok — {} free DOFs, {}, {}",
                p.sys.dofs.n_free(),
                counted(p.contacts.len(), "contact point", "contact points"),
                counted(s.frequencies().len(), "frequency", "frequencies")
            );
            extras(a, s, &p);
            ExitCode::SUCCESS
        }
        Err(BuildError::Deck(e)) => {
            for w in s.deck.iter().flat_map(|j| &j.warnings) {
                eprintln!("{}: {w}", if w.note { "note" } else { "warning" });
            }
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("error: {}: building the model: {e}", s.file);
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
                "time forecast: one factorization of the dynamic stiffness {} s, one solve {} s (measured here at {} {unit}); {} frequencies in mode {}: {}–{} factorizations, {}–{} solves, about {}–{} s with the plots' reference sweep (--no-plots halves it), plus the static step",
                sig_n(m.factorization, 2),
                sig_n(m.solve, 2),
                sig(fu.show(f0)),
                freqs.len(),
                it.mode.name(),
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
