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
pub mod reduced;
mod steps;

use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::input::scene::Scene;
use crate::model::{build, BuildError};
use crate::util::atomic::partial_path;

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

/// Writes `job`: the deck at `deck`, [`FREQUENCY_FILE`] and [`CONFIG_FILE`] beside it,
/// all three or none (each written to a temporary name first, renamed when all are
/// written). Refused, nothing written: a file of the job that is one of `inputs` (the
/// scene and the files it reads), and a directory that holds another job's
/// [`FREQUENCY_FILE`] or [`CONFIG_FILE`] (two jobs would share them: one directory per
/// job). Returns the files written.
pub fn write(job: &Job, deck: &Path, inputs: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    check_target(deck, inputs)?;
    let dir = deck.parent().unwrap_or(Path::new(""));
    let files = [
        (deck.to_path_buf(), &job.deck),
        (dir.join(FREQUENCY_FILE), &job.frequencies),
        (dir.join(CONFIG_FILE), &job.config),
    ];
    if !dir.as_os_str().is_empty() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let temps: Vec<PathBuf> = files.iter().map(|(p, _)| partial_path(p)).collect();
    let clean = |temps: &[PathBuf]| {
        for t in temps {
            let _ = std::fs::remove_file(t);
        }
    };
    for ((path, text), tmp) in files.iter().zip(&temps) {
        if let Err(e) = std::fs::write(tmp, text) {
            clean(&temps);
            return Err(format!("{}: {e}", path.display()));
        }
    }
    for ((path, _), tmp) in files.iter().zip(&temps) {
        if let Err(e) = std::fs::rename(tmp, path) {
            clean(&temps);
            return Err(format!("{}: {e}", path.display()));
        }
    }
    Ok(files.into_iter().map(|(p, _)| p).collect())
}

/// Refuses a job at `deck` whose files would overwrite one of `inputs` (the scene and
/// the files it reads), an existing file that is not this job's deck (a mesh the scene's
/// deck includes, any other file), or another job's files in the same directory.
pub fn check_target(deck: &Path, inputs: &[PathBuf]) -> Result<(), String> {
    let dir = deck.parent().unwrap_or(Path::new(""));
    let name = deck
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if name == FREQUENCY_FILE || name == CONFIG_FILE {
        return Err(format!(
            "{}: the deck would be the job's own {name}; name it JOB.inp",
            deck.display()
        ));
    }
    for path in [
        deck.to_path_buf(),
        dir.join(FREQUENCY_FILE),
        dir.join(CONFIG_FILE),
    ] {
        if let Some(input) = inputs.iter().find(|i| same_file(&path, i)) {
            return Err(format!(
                "{}: is {}, which this export reads; write the job elsewhere",
                path.display(),
                input.display()
            ));
        }
    }
    let ours = std::fs::read_to_string(dir.join(CONFIG_FILE))
        .is_ok_and(|c| job_of(&c).as_deref() == Some(name.as_str()));
    if deck.exists() && !ours {
        return Err(format!(
            "{}: exists and is not a deck export wrote for this job (no {CONFIG_FILE} beside it names it); write the job elsewhere",
            deck.display()
        ));
    }
    if let Some(other) = other_job(dir, &name) {
        return Err(format!(
            "{}: holds the job {other} (its {FREQUENCY_FILE} and {CONFIG_FILE}); {name} would replace them: export each job into a directory of its own",
            if dir.as_os_str().is_empty() { Path::new(".") } else { dir }.display()
        ));
    }
    Ok(())
}

/// The deck a [`CONFIG_FILE`] written by export names in its first line.
fn job_of(config: &str) -> Option<String> {
    let first = config.lines().next()?;
    let (_, rest) = first.split_once("of the Abaqus job ")?;
    let (job, _) = rest.split_once(", written by")?;
    Some(job.to_string())
}

/// Whether `a` and `b` name one existing file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// The deck name of another job whose files lie in `dir` (a [`CONFIG_FILE`] written
/// for a deck other than `deck_name`, or a [`FREQUENCY_FILE`] without one), if any.
fn other_job(dir: &Path, deck_name: &str) -> Option<String> {
    let config = std::fs::read_to_string(dir.join(CONFIG_FILE)).ok();
    let frequencies = dir.join(FREQUENCY_FILE).exists();
    let named = config.as_deref().and_then(job_of);
    match (config, named) {
        (Some(_), Some(job)) if job == deck_name => None,
        (Some(_), Some(job)) => Some(job),
        (Some(_), None) => Some(format!(
            "of an unknown deck ({CONFIG_FILE} not written by export)"
        )),
        (None, _) if frequencies => Some(format!(
            "of an unknown deck ({FREQUENCY_FILE} without {CONFIG_FILE})"
        )),
        (None, _) => None,
    }
}

/// A float in shortest round-trip form (read back bit for bit), e.g. `1174.0`, `1e-6`.
fn num(v: f64) -> String {
    format!("{v:?}")
}
