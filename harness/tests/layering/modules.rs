//! The file-level import graph of a crate: each file is a module; a path it names
//! (`crate::…`, `super::…`, `self::…`, or a child module's name) is an import of the file
//! of the deepest module on that path. A child naming its own ancestors is not counted
//! (the parent module is its context, as `use super::*` says), so a circle is one between
//! files that neither contains the other.

use std::collections::BTreeMap;

use super::circles::{add, Graph};
use super::source::{code_lines, is_test_file, Import};

/// The module path of a file: `a/b.rs` and `a/b/mod.rs` → [a, b]; the crate roots
/// (`lib.rs`, `main.rs`) → [].
fn module_of(file: &str) -> Vec<String> {
    let mut parts: Vec<String> = file.split('/').map(str::to_string).collect();
    let last = parts.pop().expect("a file name");
    if !matches!(last.as_str(), "mod.rs" | "lib.rs" | "main.rs") {
        parts.push(last.trim_end_matches(".rs").to_string());
    }
    parts
}

/// The paths of a `use` item's tree (`a::{b, c::{d, e}}` → a::b, a::c::d, a::c::e).
fn use_paths(tree: &str) -> Vec<Vec<String>> {
    fn parse(t: &[char], i: &mut usize, prefix: &[String], out: &mut Vec<Vec<String>>) {
        let mut path = prefix.to_vec();
        loop {
            while t.get(*i).is_some_and(|c| c.is_whitespace()) {
                *i += 1;
            }
            match t.get(*i) {
                Some('{') => {
                    *i += 1;
                    loop {
                        parse(t, i, &path, out);
                        match t.get(*i) {
                            Some(',') => *i += 1,
                            _ => break,
                        }
                        while t.get(*i).is_some_and(|c| c.is_whitespace()) {
                            *i += 1;
                        }
                        if t.get(*i) == Some(&'}') {
                            break;
                        }
                    }
                    *i += 1; // the closing brace
                    return;
                }
                Some(c) if c.is_alphanumeric() || *c == '_' => {
                    let begin = *i;
                    while t.get(*i).is_some_and(|c| c.is_alphanumeric() || *c == '_') {
                        *i += 1;
                    }
                    let seg: String = t[begin..*i].iter().collect();
                    if seg != "self" || path.is_empty() {
                        path.push(seg);
                    }
                    if t.get(*i) == Some(&':') && t.get(*i + 1) == Some(&':') {
                        *i += 2;
                        continue;
                    }
                    // `as name` and the rest of the member up to `,`, `}` or the end.
                    while t.get(*i).is_some_and(|c| *c != ',' && *c != '}') {
                        *i += 1;
                    }
                    out.push(path);
                    return;
                }
                _ => {
                    out.push(path); // `*` or the end
                    while t.get(*i).is_some_and(|c| *c != ',' && *c != '}') {
                        *i += 1;
                    }
                    return;
                }
            }
        }
    }
    let t: Vec<char> = tree.chars().collect();
    let mut out = Vec::new();
    parse(&t, &mut 0, &[], &mut out);
    out
}

/// The paths on a line of code: `a::b::c` runs of identifiers.
fn expression_paths(line: &str) -> Vec<Vec<String>> {
    let chars: Vec<char> = line.chars().collect();
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let starts = (chars[i].is_alphabetic() || chars[i] == '_')
            && (i == 0 || !(ident(chars[i - 1]) || chars[i - 1] == ':'));
        if !starts {
            i += 1;
            continue;
        }
        let mut path = Vec::new();
        loop {
            let begin = i;
            while i < chars.len() && ident(chars[i]) {
                i += 1;
            }
            path.push(chars[begin..i].iter().collect::<String>());
            let more = chars.get(i) == Some(&':')
                && chars.get(i + 1) == Some(&':')
                && chars
                    .get(i + 2)
                    .is_some_and(|&c| c.is_alphabetic() || c == '_');
            if !more {
                break;
            }
            i += 2;
        }
        if path.len() > 1 {
            out.push(path);
        }
    }
    out
}

/// The body of a `use` item (`a::{b, c};` → `a::{b, c}`), `None` for other code.
fn use_body(stmt: &str) -> Option<&str> {
    ["pub(crate) use ", "pub(super) use ", "pub use ", "use "]
        .iter()
        .find_map(|p| stmt.strip_prefix(p))
        .map(|b| b.trim_end_matches(';'))
}

/// The code of `text` as statements to read paths from, each with its first line: a
/// `use` item joined over its lines, every other line alone.
fn statements(text: &str) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut open = false;
    for (n, line) in code_lines(text) {
        let t = line.trim();
        if open {
            let last = out.last_mut().expect("an open use item");
            last.1.push(' ');
            last.1.push_str(t);
        } else {
            out.push((n, t.to_string()));
            if use_body(t).is_none() {
                continue;
            }
        }
        open = !t.ends_with(';');
    }
    out
}

/// The module a path names from module `here` (the deepest existing module on it), or
/// `None` for a path outside the crate.
fn target(
    here: &[String],
    path: &[String],
    exists: &dyn Fn(&[String]) -> bool,
) -> Option<Vec<String>> {
    let mut base: Vec<String> = here.to_vec();
    let mut rest = path;
    match path[0].as_str() {
        "crate" => {
            base.clear();
            rest = &path[1..];
        }
        "self" => rest = &path[1..],
        "super" => {
            while rest.first().is_some_and(|s| s == "super") {
                base.pop()?;
                rest = &rest[1..];
            }
        }
        first => {
            let child = [here, &[first.to_string()]].concat();
            if !exists(&child) {
                return None;
            }
        }
    }
    let mut deepest = base;
    for seg in rest {
        let next = [deepest.as_slice(), std::slice::from_ref(seg)].concat();
        if !exists(&next) {
            break;
        }
        deepest = next;
    }
    Some(deepest)
}

/// Every path named by the code of `text`, with the first line of its statement and the
/// statement's text.
pub fn named_paths(text: &str) -> Vec<(usize, String, Vec<String>)> {
    let mut out = Vec::new();
    for (n, stmt) in statements(text) {
        let found = match use_body(&stmt) {
            Some(body) => use_paths(body),
            None => expression_paths(&stmt),
        };
        for path in found.into_iter().filter(|p| p.len() > 1) {
            out.push((n, stmt.clone(), path));
        }
    }
    out
}

/// The file-level graph of a crate's `files` (path relative to its src/, text); test
/// files and test items left out.
pub fn graph(files: &[(String, String)]) -> Graph {
    let by_module: BTreeMap<Vec<String>, &String> = files
        .iter()
        .filter(|(f, _)| f != "main.rs")
        .map(|(f, _)| (module_of(f), f))
        .collect();
    let exists = |m: &[String]| by_module.contains_key(m);
    let mut g = Graph::new();
    for (file, text) in files {
        if is_test_file(file) {
            continue;
        }
        let here = module_of(file);
        for (n, text, path) in named_paths(text) {
            let Some(to) = target(&here, &path, &exists) else {
                continue;
            };
            if !here.starts_with(&to) {
                let file_to = by_module[&to];
                let file = file.clone();
                add(
                    &mut g,
                    &file.clone(),
                    file_to,
                    Import {
                        file,
                        line: n,
                        text,
                    },
                );
            }
        }
    }
    g
}
