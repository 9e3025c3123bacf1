//! Abaqus-format input decks: the reader and its plain data model [`Deck`].
//!
//! Read as Abaqus reads them: keywords and parameters case-insensitive, `**` comments,
//! keyword lines continued after a trailing comma, data lines continued for long
//! element connectivities, `*INCLUDE, INPUT=`, numbers such as `1.`, `1.E4`, `2.1d5`,
//! `GENERATE` ranges, flat decks and `*PART`/`*ASSEMBLY`/`*INSTANCE` decks (instances
//! translated, their names prefixed `INSTANCE.`, their ids offset past the ids before
//! them). Every error is `file:line: *KEYWORD: message` ([`DeckError`]); a keyword in
//! neither [`keywords::KEYWORDS`] nor [`IGNORED_KEYWORDS`] is an error, and so is a
//! parameter or a data field that [`keywords::KEYWORDS`] does not list for its keyword.

pub mod check;
pub mod config;
pub mod error;
pub mod gmsh;
pub mod job;
pub mod keywords;
pub mod lexer;
pub mod model;
pub mod parse;
pub mod props;
pub mod sets;
pub mod size;
pub mod summary;

#[cfg(test)]
mod tests;

use std::path::Path;

pub use error::{DeckError, DeckErrorKind, DeckWarning};
pub use model::*;

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
    let (cards, sources) = lexer::read_file(path)?;
    let (mut deck, warnings) = parse::build(cards)?;
    deck.sources = sources;
    Ok((deck, warnings))
}

/// Reads deck text `text`, named `name` in messages; `*INCLUDE` paths are relative to
/// `dir`.
pub fn read_str(text: &str, name: &str, dir: &Path) -> Result<(Deck, Vec<DeckWarning>), DeckError> {
    parse::build(lexer::read_str(text, name, dir)?)
}
