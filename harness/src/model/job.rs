//! A run's input as the rooms above the readers see it: its settings
//! ([`RunSettings`], which a study may vary) and its model source, built into a
//! [`Problem`] or a lumped system with those settings, and where it came from (file,
//! text and every file read, for run.json).

use std::borrow::Cow;
use std::path::Path;
use std::sync::Arc;

use super::lumped::{self, Lumped};
use super::{BuildError, Problem};
use crate::input::scene::Scene;
use crate::settings::RunSettings;
use crate::util::provenance::SourceFile;

/// One run's settings and model source.
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    pub settings: RunSettings,
    /// The input as read (scene or deck); its own settings are replaced by
    /// [`Job::settings`] wherever the model is built from it.
    pub(super) source: Arc<Scene>,
}

impl From<&Scene> for Job {
    fn from(scene: &Scene) -> Job {
        Job {
            settings: scene.settings(),
            source: Arc::new(scene.clone()),
        }
    }
}

impl From<&Job> for Job {
    fn from(job: &Job) -> Job {
        job.clone()
    }
}

impl Job {
    /// A scene's TOML `text` (no model file, no `[[matrices]]` files) as a job, its
    /// errors named by `file`: the benches' generated scenes.
    pub fn parse(file: &str, text: &str) -> Result<Job, crate::input::scene::SceneError> {
        Ok(Job::from(&Scene::parse(file, text)?))
    }

    /// Reads a scene or deck through the input path (`input::load`) as a job.
    pub fn load(path: &Path) -> Result<Job, crate::input::InputError> {
        Ok(Job::from(&crate::input::load(path)?.into_scene()))
    }

    /// The same input with `settings`.
    pub fn with_settings(&self, settings: RunSettings) -> Job {
        Job {
            settings,
            source: self.source.clone(),
        }
    }

    /// The input with this job's settings in place of its own.
    fn scene(&self) -> Cow<'_, Scene> {
        let own = self.source.settings();
        if own == self.settings {
            return Cow::Borrowed(self.source.as_ref());
        }
        Cow::Owned(self.source.with_settings(&self.settings))
    }

    /// The FE problem (of an FE or masses-only input): [`super::build()`].
    pub fn build(&self) -> Result<Problem, BuildError> {
        super::build(&self.scene())
    }

    /// The lumped system of a lumped input: [`lumped::build`].
    pub fn lumped(&self) -> Result<Lumped, String> {
        lumped::build(&self.scene())
    }

    /// The node numbers of `p`'s nodes as the input names them: [`super::node_ids`].
    pub fn node_ids(&self, p: &Problem) -> Vec<u64> {
        super::node_ids(&self.source, p)
    }

    /// The title, or the input file's name without extension when it has none (plot
    /// titles).
    pub fn title(&self) -> &str {
        if !self.settings.title.trim().is_empty() {
            return &self.settings.title;
        }
        Path::new(self.file())
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or(self.file())
    }

    /// The input's file name as given (messages, run.json).
    pub fn file(&self) -> &str {
        &self.source.file
    }

    /// The directory of the input file (where its relative paths start).
    pub fn dir(&self) -> &Path {
        Path::new(&self.source.file)
            .parent()
            .unwrap_or(Path::new(""))
    }

    /// The input file's text, as read (run.json).
    pub fn text(&self) -> &str {
        &self.source.text
    }

    /// Every file the input was read from (run.json's `inputs`).
    pub fn sources(&self) -> &[SourceFile] {
        &self.source.sources
    }

    /// The input's schema with this job's settings (run.json's `scene.spec`).
    pub fn spec_json(&self) -> serde_json::Value {
        serde_json::to_value(&self.scene().spec).unwrap_or(serde_json::Value::Null)
    }
}
