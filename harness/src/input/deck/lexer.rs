//! Cards of an Abaqus-format deck: a keyword line (`*NAME, PARAM=VALUE, …`, continued
//! on the next line when it ends with a comma) and its data lines. `**` lines are
//! comments; keywords and parameter names are case-insensitive (stored upper case);
//! `*INCLUDE, INPUT=file` is replaced by the lines of that file (relative to the
//! including file): its keyword lines start cards, and data lines before its first
//! keyword line go on the card the `*INCLUDE` stands in (an included list of frequencies
//! or nodes, as Abaqus reads it).

use std::path::{Path, PathBuf};

use super::error::{DeckError, DeckErrorKind, Origin};
use crate::util::provenance::SourceFile;

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
    /// The file the data lines come from when it is not the keyword line's (`INPUT=`, or
    /// an `*INCLUDE`d file of data lines); `None` also when they come from several.
    pub data_file: Option<String>,
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
            file: self
                .data_file
                .clone()
                .unwrap_or_else(|| self.origin.file.clone()),
            line,
        }
        .error(kind, &self.name(), message)
    }
}

/// Most bytes read for one deck, all its `*INCLUDE`s and `INPUT=` files together
/// (1 GiB: a million-node model's deck is some 100 MB; a device such as /dev/zero or a
/// file included over and over stops here instead of filling the memory).
pub const MAX_DECK_BYTES: u64 = 1 << 30;

/// Most files opened for one deck (`*INCLUDE`s and `INPUT=` files): files that include
/// each other several times over stop here instead of being read for hours.
pub const MAX_DECK_FILES: usize = 10_000;

/// What the reader has read so far, against [`MAX_DECK_BYTES`] and [`MAX_DECK_FILES`].
#[derive(Default)]
struct Lexer {
    cards: Vec<Card>,
    current: Option<Card>,
    bytes: u64,
    files: usize,
    /// Every file read, in reading order, with its digest (run.json's `inputs`).
    sources: Vec<SourceFile>,
}

/// Reads the cards of the deck file `path`, following `*INCLUDE`s; also every file
/// read (the deck first).
pub fn read_file(path: &Path) -> Result<(Vec<Card>, Vec<SourceFile>), DeckError> {
    let origin = Origin {
        file: path.display().to_string(),
        line: 0,
    };
    let mut lx = Lexer::default();
    let text = lx.read(path, &origin, "")?;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    lx.lex(&text, &origin.file, &dir, 0)?;
    let sources = std::mem::take(&mut lx.sources);
    Ok((lx.finish(), sources))
}

/// Reads the cards of deck text `text` named `name` in messages; `*INCLUDE` paths are
/// relative to `dir`.
pub fn read_str(text: &str, name: &str, dir: &Path) -> Result<Vec<Card>, DeckError> {
    let mut lx = Lexer {
        bytes: text.len() as u64,
        ..Lexer::default()
    };
    lx.lex(text, name, dir, 0)?;
    Ok(lx.finish())
}

impl Lexer {
    fn finish(mut self) -> Vec<Card> {
        self.cards.extend(self.current.take());
        self.cards
    }

    /// The text of `path`, read for the card at `from` (`keyword`, "" for the deck
    /// itself), within the deck's byte and file budget.
    fn read(&mut self, path: &Path, from: &Origin, keyword: &str) -> Result<String, DeckError> {
        use std::io::Read as _;
        self.files += 1;
        if self.files > MAX_DECK_FILES {
            return Err(from.error(
                DeckErrorKind::BadValue,
                keyword,
                format!("more than {MAX_DECK_FILES} files read for one deck (files including each other over and over?)"),
            ));
        }
        let io = |e: std::io::Error| {
            from.error(
                DeckErrorKind::Io,
                keyword,
                format!("cannot read {}: {e}", path.display()),
            )
        };
        let left = MAX_DECK_BYTES.saturating_sub(self.bytes);
        let mut bytes = Vec::new();
        std::fs::File::open(path)
            .map_err(io)?
            .take(left + 1)
            .read_to_end(&mut bytes)
            .map_err(io)?;
        self.bytes += bytes.len() as u64;
        self.sources
            .push(SourceFile::of(&path.display().to_string(), &bytes));
        if self.bytes > MAX_DECK_BYTES {
            return Err(from.error(
                DeckErrorKind::BadValue,
                keyword,
                format!(
                    "{}: the deck and its files exceed {} MiB",
                    path.display(),
                    MAX_DECK_BYTES >> 20
                ),
            ));
        }
        String::from_utf8(bytes).map_err(|e| {
            Origin {
                file: path.display().to_string(),
                line: 0,
            }
            .error(
                DeckErrorKind::Syntax,
                "",
                format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
            )
        })
    }

    fn lex(&mut self, text: &str, name: &str, dir: &Path, depth: usize) -> Result<(), DeckError> {
        let mut lines = text.lines().enumerate().peekable();
        while let Some((i, raw)) = lines.next() {
            let line = raw.trim();
            let origin = Origin {
                file: name.to_string(),
                line: i + 1,
            };
            if line.starts_with("**") || line.is_empty() && self.current.is_none() {
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
                    self.include(card, dir, depth)?;
                } else {
                    self.cards.extend(self.current.take());
                    let input = card.param("INPUT").map(str::to_string);
                    self.current = Some(card);
                    if let Some(input) = input {
                        self.input_data(&input, dir)?;
                    }
                }
                continue;
            }
            let Some(card) = self.current.as_mut() else {
                return Err(origin.error(
                    DeckErrorKind::Syntax,
                    "",
                    format!("data line before the first keyword: {:?}", truncate(line)),
                ));
            };
            if card.param("INPUT").is_some() && card.keyword != "INCLUDE" && !line.is_empty() {
                return Err(origin.error(
                    DeckErrorKind::Syntax,
                    &card.name(),
                    "a data line after a keyword whose data lines come from its INPUT= file",
                ));
            }
            // Data lines from an included file (a frequency list after the keyword
            // line): their errors name that file, unless the card mixes files.
            let from = (name != card.origin.file).then(|| name.to_string());
            let blank = |l: &DataLine| l.fields.iter().all(|f| f.is_empty());
            if !line.is_empty() {
                if card.data.iter().all(blank) {
                    card.data_file = from;
                } else if card.data_file != from {
                    card.data_file = None;
                }
            }
            card.data.push(data_line(i + 1, line));
        }
        Ok(())
    }

    /// `*INCLUDE, INPUT=file`: the file's lines in place of the card.
    fn include(&mut self, card: Card, dir: &Path, depth: usize) -> Result<(), DeckError> {
        if let Some((p, _)) = card.params.iter().find(|(p, _)| p != "INPUT") {
            return Err(card.origin.error(
                DeckErrorKind::Unsupported,
                &format!("*INCLUDE, {p}="),
                "parameter not supported (this reader implements INPUT)",
            ));
        }
        if depth >= MAX_INCLUDE_DEPTH {
            return Err(card.error(
                DeckErrorKind::BadValue,
                format!("more than {MAX_INCLUDE_DEPTH} nested includes (a file including itself?)"),
            ));
        }
        let path: PathBuf = dir.join(card.required("INPUT")?.trim_matches('"'));
        let text = self.read(&path, &card.origin, "*INCLUDE")?;
        let inner = path.parent().map(Path::to_path_buf).unwrap_or_default();
        self.lex(&text, &path.display().to_string(), &inner, depth + 1)
    }

    /// `*KEYWORD, INPUT=file` (other than `*INCLUDE`): the file's lines are the open
    /// card's data lines (comments skipped; a keyword line there is an error).
    fn input_data(&mut self, input: &str, dir: &Path) -> Result<(), DeckError> {
        let card = self.current.as_ref().expect("input_data follows a card");
        let from = card.origin.clone();
        let keyword = card.name();
        let path = dir.join(input.trim_matches('"'));
        let text = self.read(&path, &from, &keyword)?;
        let file = path.display().to_string();
        let card = self.current.as_mut().expect("input_data follows a card");
        for (i, raw) in text.lines().enumerate() {
            let line = raw.trim();
            if line.is_empty() || line.starts_with("**") {
                continue;
            }
            if line.starts_with('*') {
                return Err(Origin {
                    file: file.clone(),
                    line: i + 1,
                }
                .error(
                    DeckErrorKind::Syntax,
                    &keyword,
                    "a keyword line in a file of data lines (INPUT=)",
                ));
            }
            card.data.push(data_line(i + 1, line));
        }
        card.data_file = Some(file);
        Ok(())
    }
}

/// A data line's trimmed fields (a trailing comma gives no empty last field).
fn data_line(line: usize, text: &str) -> DataLine {
    let mut fields: Vec<String> = text.split(',').map(|f| f.trim().to_string()).collect();
    if fields.len() > 1 && fields.last().is_some_and(|f| f.is_empty()) {
        fields.pop();
    }
    DataLine { line, fields }
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
        data_file: None,
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
