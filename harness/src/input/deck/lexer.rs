//! Cards of an Abaqus-format deck: a keyword line (`*NAME, PARAM=VALUE, …`, continued
//! on the next line when it ends with a comma) and its data lines. `**` lines are
//! comments; keywords and parameter names are case-insensitive (stored upper case);
//! `*INCLUDE, INPUT=file` is replaced by the lines of that file (relative to the
//! including file): its keyword lines start cards, and data lines before its first
//! keyword line go on the card the `*INCLUDE` stands in (an included list of frequencies
//! or nodes, as Abaqus reads it).

use std::path::{Path, PathBuf};

use super::error::{DeckError, DeckErrorKind, Origin};

/// Deepest `*INCLUDE` nesting accepted (a file including itself is an error, not a hang).
const MAX_INCLUDE_DEPTH: usize = 16;

/// One data line: its 1-based line number and its comma-separated fields, trimmed
/// (a trailing comma gives no empty last field).
#[derive(Debug, Clone, PartialEq)]
pub struct DataLine {
    pub line: usize,
    pub fields: Vec<String>,
}

/// A keyword line and the data lines that follow it.
#[derive(Debug, Clone, PartialEq)]
pub struct Card {
    /// Upper-case keyword with single spaces, e.g. `SOLID SECTION`.
    pub keyword: String,
    /// (upper-case name, value as written) of each parameter; a flag has value "".
    pub params: Vec<(String, String)>,
    pub origin: Origin,
    pub data: Vec<DataLine>,
}

impl Card {
    /// `*KEYWORD` for messages.
    pub fn name(&self) -> String {
        format!("*{}", self.keyword)
    }

    /// The value of parameter `name` (upper case), if given.
    pub fn param(&self, name: &str) -> Option<&str> {
        self.params
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// True if parameter `name` is present (with or without value).
    pub fn flag(&self, name: &str) -> bool {
        self.params.iter().any(|(k, _)| k == name)
    }

    /// The value of a required parameter.
    pub fn required(&self, name: &str) -> Result<&str, DeckError> {
        match self.param(name) {
            Some(v) if !v.is_empty() => Ok(v),
            _ => Err(self.error(
                DeckErrorKind::Syntax,
                format!("parameter {name}= is required"),
            )),
        }
    }

    /// An error at the keyword line.
    pub fn error(&self, kind: DeckErrorKind, message: impl Into<String>) -> DeckError {
        self.origin.error(kind, &self.name(), message)
    }

    /// An error at data line `line`.
    pub fn error_at(
        &self,
        line: usize,
        kind: DeckErrorKind,
        message: impl Into<String>,
    ) -> DeckError {
        Origin {
            file: self.origin.file.clone(),
            line,
        }
        .error(kind, &self.name(), message)
    }
}

/// Reads the cards of the deck file `path`, following `*INCLUDE`s.
pub fn read_file(path: &Path) -> Result<Vec<Card>, DeckError> {
    let mut cards = Vec::new();
    let origin = Origin {
        file: path.display().to_string(),
        line: 0,
    };
    let mut current = None;
    lex_file(path, &origin, 0, &mut cards, &mut current)?;
    cards.extend(current);
    Ok(cards)
}

/// Reads the cards of deck text `text` named `name` in messages; `*INCLUDE` paths are
/// relative to `dir`.
pub fn read_str(text: &str, name: &str, dir: &Path) -> Result<Vec<Card>, DeckError> {
    let mut cards = Vec::new();
    let mut current = None;
    lex_text(text, name, dir, 0, &mut cards, &mut current)?;
    cards.extend(current);
    Ok(cards)
}

fn lex_file(
    path: &Path,
    from: &Origin,
    depth: usize,
    cards: &mut Vec<Card>,
    current: &mut Option<Card>,
) -> Result<(), DeckError> {
    let bytes = std::fs::read(path).map_err(|e| {
        from.error(
            DeckErrorKind::Io,
            "*INCLUDE",
            format!("cannot read {}: {e}", path.display()),
        )
    })?;
    let name = path.display().to_string();
    let text = String::from_utf8(bytes).map_err(|e| {
        Origin {
            file: name.clone(),
            line: 0,
        }
        .error(
            DeckErrorKind::Syntax,
            "",
            format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
        )
    })?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    lex_text(&text, &name, &dir, depth, cards, current)
}

fn lex_text(
    text: &str,
    name: &str,
    dir: &Path,
    depth: usize,
    cards: &mut Vec<Card>,
    current: &mut Option<Card>,
) -> Result<(), DeckError> {
    let mut lines = text.lines().enumerate().peekable();
    while let Some((i, raw)) = lines.next() {
        let line = raw.trim();
        let origin = Origin {
            file: name.to_string(),
            line: i + 1,
        };
        if line.starts_with("**") || line.is_empty() && current.is_none() {
            continue;
        }
        if let Some(rest) = line.strip_prefix('*') {
            // Continuation: a keyword line ending with a comma goes on on the next line.
            let mut head = rest.to_string();
            while head.trim_end().ends_with(',') {
                match lines.peek() {
                    Some((_, next)) if !next.trim().starts_with('*') => {
                        head.push_str(next.trim());
                        lines.next();
                    }
                    _ => break,
                }
            }
            let card = keyword_card(&head, origin)?;
            if card.keyword == "INCLUDE" {
                if depth >= MAX_INCLUDE_DEPTH {
                    return Err(card.error(
                        DeckErrorKind::BadValue,
                        format!("more than {MAX_INCLUDE_DEPTH} nested includes (a file including itself?)"),
                    ));
                }
                let input = card.required("INPUT")?;
                let path: PathBuf = dir.join(input.trim_matches('"'));
                lex_file(&path, &card.origin, depth + 1, cards, current)?;
            } else {
                cards.extend(current.take());
                *current = Some(card);
            }
            continue;
        }
        match current.as_mut() {
            Some(card) => {
                let mut fields: Vec<String> =
                    line.split(',').map(|f| f.trim().to_string()).collect();
                if fields.len() > 1 && fields.last().is_some_and(|f| f.is_empty()) {
                    fields.pop();
                }
                card.data.push(DataLine {
                    line: i + 1,
                    fields,
                });
            }
            None => {
                return Err(origin.error(
                    DeckErrorKind::Syntax,
                    "",
                    format!("data line before the first keyword: {:?}", truncate(line)),
                ))
            }
        }
    }
    Ok(())
}

/// Splits `NAME, P1=V1, FLAG` into the upper-case keyword and parameters.
fn keyword_card(head: &str, origin: Origin) -> Result<Card, DeckError> {
    let mut parts = head.split(',');
    let keyword = parts
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_ascii_uppercase();
    if keyword.is_empty() {
        return Err(origin.error(DeckErrorKind::Syntax, "*", "empty keyword"));
    }
    let mut params = Vec::new();
    for p in parts {
        let p = p.trim();
        if p.is_empty() {
            continue;
        }
        let (k, v) = match p.split_once('=') {
            Some((k, v)) => (k.trim(), v.trim()),
            None => (p, ""),
        };
        let k = k
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
            .to_ascii_uppercase();
        params.push((k, v.to_string()));
    }
    Ok(Card {
        keyword,
        params,
        origin,
        data: Vec::new(),
    })
}

/// At most 40 characters of `s`, for messages.
pub fn truncate(s: &str) -> String {
    s.chars().take(40).collect()
}

/// A number as Abaqus writes it: `1`, `1.`, `.5`, `1.E4`, `2.1d5`, `-3e-2`; finite only.
pub fn parse_number(s: &str) -> Option<f64> {
    let t = s.trim();
    if t.is_empty()
        || !t.bytes().all(|b| {
            b.is_ascii_digit() || matches!(b, b'.' | b'+' | b'-' | b'e' | b'E' | b'd' | b'D')
        })
    {
        return None;
    }
    let v: f64 = t.replace(['d', 'D'], "e").parse().ok()?;
    v.is_finite().then_some(v)
}

/// A positive integer id (node, element, DOF); `1.` is not an id.
pub fn parse_id(s: &str) -> Option<u64> {
    let t = s.trim();
    if t.is_empty() || !t.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    t.parse().ok().filter(|&v| v > 0)
}
