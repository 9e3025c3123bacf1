//! Scene errors that name the file, the line and column, and the key (dotted path,
//! array entries by index: `bodies[1].size`).
//!
//! Parse errors come from `toml` with a byte span; the key is found by walking the
//! document (`toml_edit`, which keeps spans) to the innermost key whose value holds the
//! span. Validation errors come with a key path; the line is found the other way round.

use std::fmt;
use std::ops::Range;

use toml_edit::{ImDocument, Item, Table, Value};

/// One step of a key path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Seg {
    Key(String),
    Index(usize),
}

/// A failed check: where and why.
pub type Problem = (KeyPath, String);

/// A key path, e.g. `bodies[1].size`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct KeyPath(pub Vec<Seg>);

impl KeyPath {
    pub fn root() -> Self {
        KeyPath(Vec::new())
    }

    /// This path with a key appended.
    pub fn key(&self, k: &str) -> Self {
        let mut p = self.clone();
        p.0.push(Seg::Key(k.to_string()));
        p
    }

    /// This path with an array index appended.
    pub fn index(&self, i: usize) -> Self {
        let mut p = self.clone();
        p.0.push(Seg::Index(i));
        p
    }
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return write!(f, "(top level)");
        }
        for (i, s) in self.0.iter().enumerate() {
            match s {
                Seg::Key(k) if i == 0 => write!(f, "{k}")?,
                Seg::Key(k) => write!(f, ".{k}")?,
                Seg::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// A bad scene: where and why. Display: `file:line:column: key `path`: message`.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    pub file: String,
    /// 1-based line, 0 if unknown (I/O errors).
    pub line: usize,
    /// 1-based column (characters), 0 if unknown.
    pub column: usize,
    pub key: String,
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: ", self.file)?;
        } else {
            write!(f, "{}:{}:{}: ", self.file, self.line, self.column)?;
        }
        if !self.key.is_empty() {
            write!(f, "key `{}`: ", self.key)?;
        }
        write!(f, "{}", self.message)
    }
}

impl std::error::Error for SceneError {}

/// 1-based (line, column) of a byte offset.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

enum Node<'a> {
    Item(&'a Item),
    Value(&'a Value),
    Table(&'a Table),
}

impl<'a> Node<'a> {
    fn span(&self) -> Option<Range<usize>> {
        match self {
            Node::Item(i) => i.span(),
            Node::Value(v) => v.span(),
            Node::Table(t) => t.span(),
        }
    }

    /// Child by key: (key span, child).
    fn get(&self, k: &str) -> Option<(Option<Range<usize>>, Node<'a>)> {
        match self {
            Node::Table(t) => {
                let key_span = t.key(k).and_then(|k| k.span());
                t.get(k).map(|i| (key_span, Node::Item(i)))
            }
            Node::Item(Item::Table(t)) => Node::Table(t).get(k),
            Node::Item(Item::Value(v)) => Node::Value(v).get(k),
            Node::Value(Value::InlineTable(t)) => {
                let key_span = t.key(k).and_then(|k| k.span());
                t.get(k).map(|v| (key_span, Node::Value(v)))
            }
            _ => None,
        }
    }

    fn at(&self, i: usize) -> Option<Node<'a>> {
        match self {
            Node::Item(Item::ArrayOfTables(a)) => a.get(i).map(Node::Table),
            Node::Item(Item::Value(v)) => Node::Value(v).at(i),
            Node::Value(Value::Array(a)) => a.get(i).map(Node::Value),
            _ => None,
        }
    }

    /// Children with their path segments and key spans.
    fn children(&self) -> Vec<(Seg, Option<Range<usize>>, Node<'a>)> {
        match self {
            Node::Table(t) => t
                .iter()
                .filter_map(|(k, _)| {
                    let (ks, n) = self.get(k)?;
                    Some((Seg::Key(k.to_string()), ks, n))
                })
                .collect(),
            Node::Item(Item::Table(t)) => Node::Table(t).children(),
            Node::Item(Item::ArrayOfTables(a)) => a
                .iter()
                .enumerate()
                .map(|(i, t)| (Seg::Index(i), t.span(), Node::Table(t)))
                .collect(),
            Node::Item(Item::Value(v)) => Node::Value(v).children(),
            Node::Value(Value::InlineTable(t)) => t
                .iter()
                .filter_map(|(k, _)| {
                    let (ks, n) = self.get(k)?;
                    Some((Seg::Key(k.to_string()), ks, n))
                })
                .collect(),
            Node::Value(Value::Array(a)) => a
                .iter()
                .enumerate()
                .map(|(i, v)| (Seg::Index(i), v.span(), Node::Value(v)))
                .collect(),
            _ => Vec::new(),
        }
    }
}

/// Byte offset to report for a key path: the key itself if present, else the deepest
/// existing ancestor (a missing key is reported at its table).
pub fn offset_of(doc: &ImDocument<&str>, path: &KeyPath) -> usize {
    let mut node = Node::Table(doc.as_table());
    let mut best = 0;
    for seg in &path.0 {
        let next = match seg {
            Seg::Key(k) => node.get(k).map(|(ks, n)| {
                if let Some(s) = ks.or_else(|| n.span()) {
                    best = s.start;
                }
                n
            }),
            Seg::Index(i) => node.at(*i).inspect(|n| {
                if let Some(s) = n.span() {
                    best = s.start;
                }
            }),
        };
        match next {
            Some(n) => node = n,
            None => break,
        }
    }
    best
}

/// The innermost key path whose value's span contains `offset` (implicit tables, which
/// have no span of their own, are searched through).
pub fn path_at(doc: &ImDocument<&str>, offset: usize) -> KeyPath {
    let mut path = KeyPath::root();
    descend(&Node::Table(doc.as_table()), offset, &mut path);
    path
}

fn descend(node: &Node<'_>, offset: usize, path: &mut KeyPath) -> bool {
    let inside = |s: &Option<Range<usize>>| {
        s.as_ref()
            .is_some_and(|r| r.start <= offset && offset < r.end.max(r.start + 1))
    };
    for (seg, key_span, child) in node.children() {
        let span = child.span();
        if inside(&span) || inside(&key_span) {
            path.0.push(seg);
            descend(&child, offset, path);
            return true;
        }
        if span.is_none() {
            path.0.push(seg);
            if descend(&child, offset, path) {
                return true;
            }
            path.0.pop();
        }
    }
    false
}

/// A validation error at `path` of `text` (file `file`).
pub fn at_path(file: &str, text: &str, path: &KeyPath, message: String) -> SceneError {
    let (line, column) = match ImDocument::parse(text) {
        Ok(doc) => line_col(text, offset_of(&doc, path)),
        Err(_) => (0, 0),
    };
    SceneError {
        file: file.to_string(),
        line,
        column,
        key: path.to_string(),
        message,
    }
}

/// A parse or type error from `toml` at a byte span.
pub fn from_toml(file: &str, text: &str, err: &toml::de::Error) -> SceneError {
    let start = err.span().map_or(0, |s| s.start);
    let (line, column) = line_col(text, start);
    let mut key = match ImDocument::parse(text) {
        Ok(doc) => path_at(&doc, start),
        Err(_) => KeyPath::root(),
    };
    let message = err.message().trim().to_string();
    // "missing field `x`": the span is the enclosing table; name the missing key.
    if let Some(rest) = message.strip_prefix("missing field `") {
        if let Some(name) = rest.split('`').next() {
            key = key.key(name);
        }
    }
    SceneError {
        file: file.to_string(),
        line,
        column,
        key: if key.0.is_empty() {
            String::new()
        } else {
            key.to_string()
        },
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = "title = \"t\"\n[sweep]\nf_min = 1.0\n\n[[bodies]]\nname = \"a\"\n\n[[bodies]]\nname = \"b\"\nsize = [1.0, 2.0, 3.0]\n";

    #[test]
    fn paths_and_offsets_round_trip() {
        let doc = ImDocument::parse(DOC).unwrap();
        let p = KeyPath::root().key("bodies").index(1).key("size");
        assert_eq!(p.to_string(), "bodies[1].size");
        let off = offset_of(&doc, &p);
        assert_eq!(line_col(DOC, off), (10, 1));
        assert_eq!(path_at(&doc, off + 8), p.index(0));
        // A missing key is reported at its table.
        let missing = KeyPath::root().key("bodies").index(0).key("size");
        assert_eq!(line_col(DOC, offset_of(&doc, &missing)).0, 5);
        let f = KeyPath::root().key("sweep").key("f_min");
        assert_eq!(line_col(DOC, offset_of(&doc, &f)), (3, 1));
    }
}
