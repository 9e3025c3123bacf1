//! The one input path: a file is recognized ([`format_of`]), read by its format's reader
//! ([`load`]) into an [`Input`], and built into the one `model::Problem` (mesh, K, M,
//! contact points, loads, outputs) that the solvers and studies take.
//!
//! Readers, one directory each:
//! - [`scene`]: the project's TOML scenes (`*.toml`), validated with file:line:key errors.
//! - Abaqus input decks (`*.inp`, or a file whose first keyword line starts with `*`):
//!   [`deck`] reads them into a plain `Deck` (nodes, elements, sets, surfaces,
//!   materials, contact pairs, steps) and checks what a run takes from them
//!   ([`deck::job::DeckJob`]); a scene may take its model from one (`model = "x.inp"`).

pub mod deck;
pub mod matrices;
pub mod scene;

use std::path::Path;

use thiserror::Error;

use deck::job::DeckJob;
use deck::DeckError;
use scene::{Scene, SceneError};

/// The formats an input file can be in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// A TOML scene (see scenes/).
    Scene,
    /// An Abaqus input deck (keyword lines start with `*`).
    AbaqusDeck,
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Format::Scene => "TOML scene",
            Format::AbaqusDeck => "Abaqus input deck",
        })
    }
}

/// A read and validated input.
#[derive(Debug, Clone, PartialEq)]
pub enum Input {
    /// A scene (with its deck attached when it says `model = "x.inp"`).
    Scene(Scene),
    /// A deck run: the deck with the scene a run of it takes (default `[effects]` and
    /// `[iteration]`, the latter as the `jointlin.cfg` beside the deck sets it
    /// ([`deck::config`]); the deck's sweep and node outputs).
    Deck(Scene),
}

impl Input {
    /// The scene every study takes.
    pub fn into_scene(self) -> Scene {
        match self {
            Input::Scene(s) | Input::Deck(s) => s,
        }
    }
}

/// Errors of [`load`].
#[derive(Debug, Error)]
pub enum InputError {
    /// A scene that cannot be read or is invalid (file:line:column and key).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A deck that cannot be read or run (`file:line: *KEYWORD: message`).
    #[error(transparent)]
    Deck(#[from] DeckError),
}

/// The format of `path`: by extension (`.toml` a scene; `.inp` an Abaqus deck), else by
/// the first line that is neither blank nor a comment (`#` in TOML, `**` in a deck):
/// one starting with `*` is a deck keyword. A file that cannot be read counts as a
/// scene, so its reader names the error.
pub fn format_of(path: &Path) -> Format {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("toml") => return Format::Scene,
        Some(e) if e.eq_ignore_ascii_case("inp") => return Format::AbaqusDeck,
        _ => {}
    }
    let Ok(text) = std::fs::read_to_string(path) else {
        return Format::Scene;
    };
    format_of_text(&text)
}

/// The format of a file's text, by its first line that is neither blank nor a comment.
pub fn format_of_text(text: &str) -> Format {
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#') && !l.starts_with("**"));
    match first {
        Some(l) if l.starts_with('*') => Format::AbaqusDeck,
        _ => Format::Scene,
    }
}

/// Reads and validates the input file `path` in its format ([`format_of`]).
pub fn load(path: &Path) -> Result<Input, InputError> {
    load_with(path, &[])
}

/// [`load`] with `--set` overrides of a scene's values (a deck has none to set).
pub fn load_with(path: &Path, set: &[scene::overrides::Override]) -> Result<Input, InputError> {
    load_for(path, set, scene::Reading::Forced)
}

/// [`load_with`] for a command that reads the input as `reading` (a deck is read whole).
pub fn load_for(
    path: &Path,
    set: &[scene::overrides::Override],
    reading: scene::Reading,
) -> Result<Input, InputError> {
    match format_of(path) {
        Format::Scene => {
            let mut s = Scene::load_for(path, set, reading)?;
            scene::model_file::attach(&mut s, path)?;
            let dir = path.parent().unwrap_or(Path::new(""));
            s.sources.extend(matrices::sources(&s.spec.matrices, dir));
            Ok(Input::Scene(s))
        }
        Format::AbaqusDeck => {
            if !set.is_empty() {
                return Err(InputError::Scene(SceneError {
                    file: path.display().to_string(),
                    line: 0,
                    column: 0,
                    key: String::new(),
                    message: "--set changes a scene's values; a deck is run as written".into(),
                }));
            }
            let job = DeckJob::load(path)?;
            let text = std::fs::read_to_string(path).unwrap_or_default();
            let mut s = scene::model_file::deck_scene(job, text);
            if let Some(c) = deck::config::ShimConfig::beside(path)? {
                c.apply(&mut s.spec.iteration);
                s.sources.extend(c.source);
            }
            Ok(Input::Deck(s))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_by_extension_and_first_keyword_line() {
        assert_eq!(format_of(Path::new("a/b.toml")), Format::Scene);
        assert_eq!(format_of(Path::new("a/b.INP")), Format::AbaqusDeck);
        assert_eq!(
            format_of_text("** a deck\n\n*Heading\njob\n"),
            Format::AbaqusDeck
        );
        assert_eq!(
            format_of_text("# a scene\n[units]\nlength = \"mm\"\n"),
            Format::Scene
        );
        assert_eq!(format_of_text(""), Format::Scene);
    }

    #[test]
    fn a_bad_deck_is_a_deck_error_and_a_missing_file_the_scene_reader_s() {
        let dir = std::env::temp_dir().join(format!("jointlin-input-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let deck = dir.join("job.dat");
        std::fs::write(
            &deck,
            "*Heading\n*Node\n1, 0., 0., 0.\n*Boundary\n1, 1, 1, 0.5\n",
        )
        .unwrap();
        let e = load(&deck).unwrap_err();
        assert!(matches!(e, InputError::Deck(_)), "{e}");
        assert!(
            e.to_string().ends_with(
                "job.dat:4: *BOUNDARY: prescribed displacement 0.5 on DOFs 1–1: a run holds boundary DOFs at zero only"
            ),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
        let missing = load(Path::new("no/such/scene")).unwrap_err();
        assert!(matches!(missing, InputError::Scene(_)));
        assert!(missing.to_string().contains("cannot read"), "{missing}");
    }
}
