//! Errors and warnings of the deck reader: every one says `file:line: KEYWORD: message`.

use thiserror::Error;

/// What went wrong, for callers that branch on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DeckErrorKind {
    /// The file could not be read.
    Io,
    /// A line the format does not allow (bad number, missing parameter, text not UTF-8).
    Syntax,
    /// A keyword that is neither supported nor ignored.
    UnknownKeyword,
    /// A keyword or option the format has but this reader does not implement.
    Unsupported,
    /// A node, element, set, surface, material, interaction or part defined twice.
    Duplicate,
    /// A reference to a node, element, set, surface, material or interaction that does
    /// not exist.
    Undefined,
    /// A value out of its range (negative density, ν ≥ 0.5, face label the element does
    /// not have, inverted element, …).
    BadValue,
}

/// A reader error at a deck line.
#[derive(Debug, Clone, Error, PartialEq)]
#[error("{file}:{line}: {keyword}: {message}")]
pub struct DeckError {
    pub kind: DeckErrorKind,
    pub file: String,
    /// 1-based line number (0 when the whole file is meant).
    pub line: usize,
    /// The keyword of the card (e.g. `*ELEMENT`), upper case.
    pub keyword: String,
    pub message: String,
}

/// Where a card came from: file and 1-based line of its keyword line.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Origin {
    pub file: String,
    pub line: usize,
}

impl Origin {
    /// An error of kind `kind` at this origin.
    pub fn error(
        &self,
        kind: DeckErrorKind,
        keyword: &str,
        message: impl Into<String>,
    ) -> DeckError {
        DeckError {
            kind,
            file: self.file.clone(),
            line: self.line,
            keyword: keyword.to_string(),
            message: message.into(),
        }
    }

    /// A warning at this origin.
    pub fn warning(&self, keyword: &str, message: impl Into<String>) -> DeckWarning {
        DeckWarning {
            file: self.file.clone(),
            line: self.line,
            keyword: keyword.to_string(),
            message: message.into(),
            note: false,
        }
    }

    /// A note at this origin: a card a run has no use for and loses nothing by (an
    /// output request for Abaqus's own files).
    pub fn note(&self, keyword: &str, message: impl Into<String>) -> DeckWarning {
        DeckWarning {
            note: true,
            ..self.warning(keyword, message)
        }
    }
}

/// Something the reader skipped on purpose (an ignored output keyword, …).
#[derive(Debug, Clone, PartialEq)]
pub struct DeckWarning {
    pub file: String,
    pub line: usize,
    pub keyword: String,
    pub message: String,
    /// A note (nothing of the analysis is lost), not a warning.
    pub note: bool,
}

impl std::fmt::Display for DeckWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}:{}: {}: {}",
            self.file, self.line, self.keyword, self.message
        )
    }
}
