//! Scenes: TOML files that describe a study (geometry, materials, contact interfaces,
//! preload, excitation, sweep, iteration, outputs and the `[effects]` switches).
//!
//! [`Scene::load`] reads and validates (and refuses a scene whose run would need more
//! memory than the machine has, `validate::size`); any problem is a [`SceneError`]
//! naming the file, line, column and key. The schema with units is in [`schema`].

pub mod error;
pub mod model_file;
pub mod overrides;
pub mod schema;
pub mod validate;

use std::path::Path;
use std::sync::Arc;

use crate::util::provenance::SourceFile;

use super::deck::job::DeckJob;

pub use error::SceneError;
pub use schema::*;

/// What a command reads of a scene: a forced response (its `[sweep]` and
/// `[[excitation]]` required) or the free structure alone (modes, backbones: both may be
/// left out).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reading {
    Forced,
    Free,
}

/// A validated scene and where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// File name as given (for messages).
    pub file: String,
    /// The file's text (echoed into run.json).
    pub text: String,
    pub spec: SceneFile,
    /// The deck of `model = "file.inp"`, or of a deck run (`jointlin run DECK.inp`),
    /// attached by `input::load`; the model is built from it.
    pub deck: Option<Arc<DeckJob>>,
    /// Every file the input was read from, as read (the scene before `--set`, the deck
    /// and its files, the shim configuration beside a deck): run.json's `inputs`.
    pub sources: Vec<SourceFile>,
}

/// An error at a key a `--set` gave, or in a table a `--set` created (absent from the
/// file's text `original`): placed on the command line (`--set KEY=VALUE:`), not at a
/// line of the file that does not hold that value.
fn on_command_line(e: SceneError, set: &[overrides::Override], original: &str) -> SceneError {
    let table = e.key.split(['.', '[']).next().unwrap_or("");
    let created = || {
        !table.is_empty()
            && original
                .parse::<toml::Table>()
                .is_ok_and(|t| !t.contains_key(table))
    };
    let covering = set
        .iter()
        .rev()
        .find(|o| !e.key.is_empty() && o.covers(&e.key));
    let creating = || set.iter().rev().find(|o| o.table() == table && created());
    match covering.or_else(creating) {
        Some(o) => SceneError {
            file: format!("--set {}", o.text()),
            line: 0,
            column: 0,
            ..e
        },
        None => e,
    }
}

impl Scene {
    /// This scene with its contact points as the thesis's model: both `[effects]`
    /// switches of the three-direction point off (`normal_load_variation`,
    /// `coupled_slip`), so each point or joint with `normal` is two independent
    /// tangential directions at its static normal force (the first-order rungs, and the
    /// linearization a backbone with points starts from).
    pub fn thesis_points(&self) -> Scene {
        let mut s = self.clone();
        s.spec.effects.normal_load_variation = false;
        s.spec.effects.coupled_slip = false;
        s
    }

    /// The scene's settings (what a run reads of it besides the model).
    pub fn settings(&self) -> RunSettings {
        let s = &self.spec;
        RunSettings {
            title: s.title.clone(),
            units: s.units.clone(),
            sweep: s.sweep.clone(),
            iteration: s.iteration,
            outputs: s.outputs.clone(),
            effects: s.effects,
            loss_study: s.loss_study.clone(),
            time_domain: s.time_domain,
            field_output: s.field_output.clone(),
        }
    }

    /// This scene with `settings` in place of its own.
    pub fn with_settings(&self, settings: &RunSettings) -> Scene {
        let mut scene = self.clone();
        let (s, r) = (&mut scene.spec, settings);
        s.title = r.title.clone();
        s.units = r.units.clone();
        s.sweep = r.sweep.clone();
        s.iteration = r.iteration;
        s.outputs = r.outputs.clone();
        s.effects = r.effects;
        s.loss_study = r.loss_study.clone();
        s.time_domain = r.time_domain;
        s.field_output = r.field_output.clone();
        scene
    }

    /// The scene's title, or its file's name without extension when it has none (for
    /// plot titles).
    pub fn title(&self) -> &str {
        if !self.spec.title.trim().is_empty() {
            return &self.spec.title;
        }
        Path::new(&self.file)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or(&self.file)
    }

    /// Reads and validates a scene file.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Scene::load_with(path, &[])
    }

    /// [`Scene::load`] with `--set` overrides applied to the text first
    /// ([`overrides`]).
    pub fn load_with(path: &Path, set: &[overrides::Override]) -> Result<Scene, SceneError> {
        Scene::load_for(path, set, Reading::Forced)
    }

    /// [`Scene::load_with`] for a command that reads the scene as `reading`.
    pub fn load_for(
        path: &Path,
        set: &[overrides::Override],
        reading: Reading,
    ) -> Result<Scene, SceneError> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| SceneError {
            file: file.clone(),
            line: 0,
            column: 0,
            key: String::new(),
            message: format!("cannot read: {e}"),
        })?;
        let source = SourceFile::of(&file, text.as_bytes());
        let original = text;
        let text = overrides::apply(&original, set).map_err(|message| SceneError {
            file: file.clone(),
            line: 0,
            column: 0,
            key: String::new(),
            message,
        })?;
        let mut scene = Scene::parse_for(&file, &text, reading)
            .map_err(|e| on_command_line(e, set, &original))?;
        scene.sources.push(source);
        Ok(scene)
    }

    /// Parses and validates scene text; `file` names it in errors.
    pub fn parse(file: &str, text: &str) -> Result<Scene, SceneError> {
        Scene::parse_for(file, text, Reading::Forced)
    }

    /// [`Scene::parse`] for a command that reads the scene as `reading`.
    pub fn parse_for(file: &str, text: &str, reading: Reading) -> Result<Scene, SceneError> {
        let spec: SceneFile = toml::from_str(text).map_err(|e| error::from_toml(file, text, &e))?;
        let size = || validate::size::check(&spec);
        let problems = validate::validate_for(&spec, reading);
        if let Some((path, msg)) = problems.into_iter().next().or_else(size) {
            return Err(error::at_path(file, text, &path, msg));
        }
        Ok(Scene {
            file: file.to_string(),
            text: text.to_string(),
            spec,
            deck: None,
            sources: Vec::new(),
        })
    }

    /// The sweep's frequencies (1/time): [`SweepSpec::frequencies`].
    pub fn frequencies(&self) -> Vec<f64> {
        self.spec.sweep.frequencies()
    }

    /// The range divided at `eigen`: [`SweepSpec::frequencies_between`].
    pub fn frequencies_between(&self, eigen: &[f64]) -> Vec<f64> {
        self.spec.sweep.frequencies_between(eigen)
    }
}

#[cfg(test)]
pub(crate) mod tests;
