//! Abaqus-format input decks: the reader and its plain data model [`Deck`].
//!
//! Read as Abaqus reads them: keywords and parameters case-insensitive, `**` comments,
//! keyword lines continued after a trailing comma, data lines continued for long
//! element connectivities, `*INCLUDE, INPUT=`, numbers such as `1.`, `1.E4`, `2.1d5`,
//! `GENERATE` ranges, flat decks and `*PART`/`*ASSEMBLY`/`*INSTANCE` decks (instances
//! translated, their names prefixed `INSTANCE.`, their ids offset past the ids before
//! them). Every error is `file:line: *KEYWORD: message` ([`DeckError`]); a keyword in
//! neither [`SUPPORTED_KEYWORDS`] nor [`IGNORED_KEYWORDS`] is an error.

pub mod check;
pub mod config;
pub mod error;
pub mod gmsh;
pub mod job;
pub mod lexer;
pub mod model;
pub mod parse;
pub mod props;
pub mod sets;
pub mod summary;

#[cfg(test)]
mod tests;

use std::path::Path;

pub use error::{DeckError, DeckErrorKind, DeckWarning};
pub use model::*;

/// Keywords the reader understands (upper case, single spaces).
pub const SUPPORTED_KEYWORDS: &[&str] = &[
    "HEADING",
    "NODE",
    "ELEMENT",
    "NSET",
    "ELSET",
    "SURFACE",
    "MATERIAL",
    "ELASTIC",
    "DENSITY",
    "DAMPING",
    "SOLID SECTION",
    "SURFACE INTERACTION",
    "CONTACT PAIR",
    "TIE",
    "BOUNDARY",
    "STEP",
    "STATIC",
    "FREQUENCY",
    "STEADY STATE DYNAMICS",
    "CLOAD",
    "DLOAD",
    "DSLOAD",
    "NODE PRINT",
    "NODE OUTPUT",
    "OUTPUT",
    "END STEP",
    "PART",
    "END PART",
    "ASSEMBLY",
    "END ASSEMBLY",
    "INSTANCE",
    "END INSTANCE",
    "INCLUDE",
];

/// Output and print keywords read and skipped with a warning: they ask for results
/// this code does not write.
pub const IGNORED_KEYWORDS: &[&str] = &[
    "ELEMENT OUTPUT",
    "EL PRINT",
    "EL FILE",
    "NODE FILE",
    "CONTACT OUTPUT",
    "CONTACT PRINT",
    "CONTACT FILE",
    "ENERGY PRINT",
    "ENERGY OUTPUT",
    "SECTION PRINT",
    "PREPRINT",
    "RESTART",
    "MONITOR",
    "FILE FORMAT",
    "OUTPUT REQUEST",
];

/// Reads the deck file `path` (with its `*INCLUDE`s).
pub fn read(path: &Path) -> Result<(Deck, Vec<DeckWarning>), DeckError> {
    parse::build(lexer::read_file(path)?)
}

/// Reads deck text `text`, named `name` in messages; `*INCLUDE` paths are relative to
/// `dir`.
pub fn read_str(text: &str, name: &str, dir: &Path) -> Result<(Deck, Vec<DeckWarning>), DeckError> {
    parse::build(lexer::read_str(text, name, dir)?)
}
