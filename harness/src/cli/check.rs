//! `jointlin check SCENE|DECK.inp`: validates a scene and builds its model (so that
//! every error a run meets before its first solve is found here), or reads an Abaqus-format deck and
//! pairs its contact surfaces, and prints a summary.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use super::load_scene;
use jointlin_harness::input::{deck, format_of, Format};
use jointlin_harness::model;

// The command's help is the doc comment of `Command::Check`.
#[derive(clap::Args)]
pub struct Args {
    scene: PathBuf,
}

pub fn main(a: Args) -> ExitCode {
    if format_of(&a.scene) == Format::AbaqusDeck {
        return check_deck(&a.scene);
    }
    let s = match load_scene(&a.scene) {
        Ok(s) => s,
        Err(code) => return code,
    };
    // What only the model build finds (contact faces whose nodes do not match, ties
    // between non-conforming meshes), with the scene's location; lumped scenes with
    // [[joints]] are `jointlin backbone`'s and have no FE model.
    let lumped = !s.spec.joints.is_empty() || s.spec.springs.iter().any(|sp| sp.between.is_some());
    if !lumped {
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
            Ok(_) => {}
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
    ExitCode::SUCCESS
}

/// `jointlin check DECK.inp`: reads the deck, pairs its contact surfaces, prints the
/// summary and the reader's warnings; exit 2 with `file:line: *KEYWORD: message`.
fn check_deck(path: &Path) -> ExitCode {
    let result = deck::read(path).and_then(|(d, warnings)| {
        deck::summary::summary(&d, &path.display().to_string()).map(|s| (s, warnings))
    });
    match result {
        Ok((summary, warnings)) => {
            print!("{summary}");
            for w in warnings {
                eprintln!("warning: {w}");
            }
            run_checks(path)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// What `jointlin run` meets before its first solve on a deck: the run-level reading
/// (units comment, property tables, densities, steps a run can honour) and the model
/// build (ties, contact pairs, loads, outputs); exit 2 with the deck's file:line.
fn run_checks(path: &Path) -> ExitCode {
    let s = match load_scene(path) {
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
