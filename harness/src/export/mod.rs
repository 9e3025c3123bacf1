//! Scene → Abaqus/Standard job (`jointlin export SCENE --inp FILE`): the input deck, the
//! frequency list its steady-state step includes, and the UEXTERNALDB configuration
//! file, all written beside each other (the job directory).
//!
//! The deck is the scene's own model, node for node: nodes and C3D8I elements exactly as
//! the harness meshes the boxes (node id = index + 1, coordinates in shortest
//! round-trip form), one element set and `*SOLID SECTION` per box, the materials with
//! their Rayleigh `*DAMPING`, clamps as `*BOUNDARY`, each tie as a `*TIE` between the
//! two boxes' touching element faces (coincident nodes: the deck reader merges them as
//! the scene does), each interface as a `*CONTACT PAIR` (slave: the lower body's z-max
//! faces that carry contact, master: the upper body's z-min faces) with a
//! `*SURFACE INTERACTION, USER` holding the shim's property table, a `*STATIC` preload
//! step and a `*STEADY STATE DYNAMICS, DIRECT` step with one frequency per data line
//! (`sweep.frq`) and the harmonic loads, node output for every `[[outputs]]`, and the
//! `** jointlin units:` comment. What a deck cannot say is a named error
//! ([`ExportError`], [`check`]): nothing is written then.

mod check;
mod config;
mod mesh;
mod names;
mod steps;

use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::input::scene::Scene;
use crate::model::{build, BuildError};
use crate::util::atomic::write_text;

pub use crate::input::deck::config::CONFIG_FILE;

/// The frequency list the deck's steady-state step includes (`*INCLUDE, INPUT=`), one
/// frequency per line: increment k of the sweep is line k, so a re-run pass of the
/// UEXTERNALDB iteration lists just its increments' lines.
pub const FREQUENCY_FILE: &str = "sweep.frq";

/// Why a scene cannot be exported.
#[derive(Debug, Error)]
pub enum ExportError {
    /// Something in the scene that the deck cannot express: the scene key and why.
    #[error("{file}: `{key}`: {message}")]
    Unsupported {
        file: String,
        key: String,
        message: String,
    },
    /// The scene's model cannot be built.
    #[error("{0}")]
    Build(#[from] BuildError),
    /// The static step or the stuck response (for the configuration's `atol`) failed.
    #[error("{0}")]
    Solve(String),
}

/// The files of an exported job (text).
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    /// The input deck.
    pub deck: String,
    /// [`FREQUENCY_FILE`].
    pub frequencies: String,
    /// [`CONFIG_FILE`].
    pub config: String,
    /// Scene tables a deck does not carry (study settings), for the command's log.
    pub left_out: Vec<String>,
}

/// The job of `scene`; `deck_name` is the deck's file name (for the configuration's
/// comments).
pub fn export(scene: &Scene, deck_name: &str) -> Result<Job, ExportError> {
    let left_out = check::check(scene)?;
    let problem = build(scene)?;
    let names = names::Names::new(scene)?;
    let mut deck = String::new();
    mesh::write(&mut deck, scene, &problem, &names)?;
    steps::surfaces(&mut deck, scene, &problem, &names);
    steps::write(&mut deck, scene, &problem, &names);
    Ok(Job {
        deck,
        frequencies: steps::frequency_lines(scene),
        config: config::text(scene, deck_name, config::atol(scene, &problem)?),
        left_out,
    })
}

/// Writes `job` to `deck` and beside it (each file atomically); returns the paths.
pub fn write(job: &Job, deck: &Path) -> Result<Vec<PathBuf>, String> {
    let dir = deck.parent().unwrap_or(Path::new(""));
    if !dir.as_os_str().is_empty() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let files = [
        (deck.to_path_buf(), &job.deck),
        (dir.join(FREQUENCY_FILE), &job.frequencies),
        (dir.join(CONFIG_FILE), &job.config),
    ];
    for (path, text) in &files {
        write_text(path, text)?;
    }
    Ok(files.into_iter().map(|(p, _)| p).collect())
}

/// A float in shortest round-trip form (read back bit for bit), e.g. `1174.0`, `1e-6`.
fn num(v: f64) -> String {
    format!("{v:?}")
}
