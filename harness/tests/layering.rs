//! The layering check: the harness's top-level modules (its rooms) import each other
//! without circles. Reads every `crate::ROOM` path in harness/src (comments and test code
//! left out: a test may compare a room with a higher one, e.g. a solver with its
//! time-domain reference), builds the graph between rooms and fails on any circle,
//! listing the imports that close it. The binary's files (main.rs, cli/) sit above every
//! room and reach them as `jointlin_harness::`, so they are not part of the graph.
//!
//! Run: `cargo test --release -p jointlin-harness --test layering`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// An import of one room by another: where it is and the line's text.
#[derive(Debug, Clone)]
struct Import {
    file: String,
    line: usize,
    text: String,
}

/// Room → imported room → the imports.
type Graph = BTreeMap<String, BTreeMap<String, Vec<Import>>>;

/// The room of a file (path relative to src/, `/`-separated), `None` for the crate
/// roots and the binary's files.
fn room(file: &str) -> Option<String> {
    let first = file.split('/').next()?;
    let name = first.strip_suffix(".rs").unwrap_or(first);
    (!matches!(name, "lib" | "main" | "cli")).then(|| name.to_string())
}

/// A file that holds only test code: `tests.rs`, `*_tests.rs`, or any file under a
/// `tests/` directory (a `#[cfg(test)] mod tests;` split into files).
fn is_test_file(file: &str) -> bool {
    let name = file.rsplit('/').next().unwrap_or(file);
    name == "tests.rs" || name.ends_with("_tests.rs") || file.split('/').any(|d| d == "tests")
}

/// The lines of `text` outside `#[cfg(test)]` items and `//` comments, numbered from 1.
fn code_lines(text: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut skip_depth: Option<i64> = None; // brace depth inside a skipped test item
    let mut cfg_test = false;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(d) = skip_depth.as_mut() {
            *d += t.matches('{').count() as i64 - t.matches('}').count() as i64;
            if *d <= 0 {
                skip_depth = None;
            }
            continue;
        }
        if t == "#[cfg(test)]" {
            cfg_test = true;
            continue;
        }
        if cfg_test && !t.starts_with("#[") && !t.is_empty() {
            cfg_test = false;
            let d = t.matches('{').count() as i64 - t.matches('}').count() as i64;
            if d > 0 {
                skip_depth = Some(d);
            }
            continue; // the test item's first line (e.g. `mod tests {` or `use …;`)
        }
        if t.starts_with("//") {
            continue;
        }
        out.push((i + 1, line));
    }
    out
}

/// The graph between the rooms of `files` (path relative to src/, text).
fn graph(files: &[(String, String)]) -> Graph {
    let rooms: BTreeSet<String> = files.iter().filter_map(|(f, _)| room(f)).collect();
    let mut g = Graph::new();
    for (file, text) in files {
        let Some(from) = room(file) else { continue };
        if is_test_file(file) {
            continue;
        }
        for (n, line) in code_lines(text) {
            for (at, _) in line.match_indices("crate::") {
                let rest = &line[at + "crate::".len()..];
                let to: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                // Not `jointlin_harness::crate`-like prefixes: `crate` must start a path.
                let before = line[..at].chars().next_back();
                if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
                    continue;
                }
                if to != from && rooms.contains(&to) {
                    g.entry(from.clone())
                        .or_default()
                        .entry(to)
                        .or_default()
                        .push(Import {
                            file: file.clone(),
                            line: n,
                            text: line.trim().to_string(),
                        });
                }
            }
        }
    }
    g
}

/// The circles of `g`: each strongly connected set of two or more rooms, as a message
/// listing the imports between its rooms. Empty when the rooms are layered.
fn circles(g: &Graph) -> Vec<String> {
    let nodes: BTreeSet<&String> = g.keys().chain(g.values().flat_map(|m| m.keys())).collect();
    let reach = |from: &String| -> BTreeSet<String> {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for m in g.get(&n).into_iter().flat_map(|e| e.keys()) {
                if seen.insert(m.clone()) {
                    stack.push(m.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&String, BTreeSet<String>> =
        nodes.iter().map(|&n| (n, reach(n))).collect();
    let mut done = BTreeSet::new();
    let mut out = Vec::new();
    for &n in &nodes {
        if done.contains(n) || !reachable[n].contains(n) {
            continue;
        }
        // The rooms that reach n and that n reaches: n's circle.
        let set: BTreeSet<&String> = nodes
            .iter()
            .copied()
            .filter(|m| reachable[n].contains(*m) && reachable[m].contains(n))
            .collect();
        let mut msg = format!(
            "circle between {}:",
            set.iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        );
        for a in &set {
            for (b, imports) in g.get(*a).into_iter().flatten() {
                if set.contains(b) {
                    for i in imports {
                        msg += &format!("\n  {a} -> {b}: {}:{}: {}", i.file, i.line, i.text);
                    }
                }
            }
        }
        done.extend(set.iter().map(|s| (*s).clone()));
        out.push(msg);
    }
    out
}

/// Every .rs file under `dir`, path relative to `root` with `/` separators.
fn read_tree(root: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("readable source directory")
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            read_tree(root, &p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            let rel = p.strip_prefix(root).expect("under root");
            let rel = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            out.push((
                rel,
                std::fs::read_to_string(&p).expect("readable source file"),
            ));
        }
    }
}

fn files(list: &[(&str, &str)]) -> Vec<(String, String)> {
    list.iter()
        .map(|(f, t)| (f.to_string(), t.to_string()))
        .collect()
}

#[test]
fn the_harness_rooms_have_no_circles() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut tree = Vec::new();
    read_tree(&src, &src, &mut tree);
    let g = graph(&tree);
    // The check sees the rooms (guards against reading nothing).
    assert!(g.contains_key("capi") && g.contains_key("solve"), "{g:?}");
    let c = circles(&g);
    assert!(
        c.is_empty(),
        "the rooms import each other in circles:\n{}",
        c.join("\n")
    );
}

#[test]
fn a_planted_circle_fails_and_names_its_imports() {
    let tree = files(&[
        ("lib.rs", "pub mod low;\npub mod mid;\npub mod top;\n"),
        ("low.rs", "use std::fmt;\n// use crate::top::Comment;\n"),
        (
            "mid/mod.rs",
            "use crate::low::A;\nfn f() { crate::top::g(); }\n",
        ),
        ("top.rs", "use crate::mid::B;\nuse crate::low::C;\n"),
    ]);
    let c = circles(&graph(&tree));
    assert_eq!(c.len(), 1, "{c:?}");
    assert!(c[0].starts_with("circle between mid, top:"), "{}", c[0]);
    assert!(
        c[0].contains("mid -> top: mid/mod.rs:2: fn f() { crate::top::g(); }"),
        "{}",
        c[0]
    );
    assert!(
        c[0].contains("top -> mid: top.rs:1: use crate::mid::B;"),
        "{}",
        c[0]
    );
    assert!(!c[0].contains("low"), "{}", c[0]);
}

#[test]
fn comments_and_test_code_are_not_imports() {
    let tree = files(&[
        ("a.rs", "use crate::b::X;\n"),
        (
            "b/mod.rs",
            "//! see [`crate::a`]\n#[cfg(test)]\nmod tests {\n    use crate::a::Y;\n}\n",
        ),
        ("b/tests.rs", "use crate::a::Z;\n"),
        ("b/tests/mod.rs", "use crate::a::V;\n"),
        ("b/tests/case.rs", "use crate::a::U;\n"),
        (
            "b/more.rs",
            "#[cfg(test)]\nuse crate::a::W;\npub fn f() {}\n",
        ),
    ]);
    assert!(circles(&graph(&tree)).is_empty());
    // The same import outside test code closes the circle.
    let tree = files(&[
        ("a.rs", "use crate::b::X;\n"),
        ("b/mod.rs", "use crate::a::Y;\n"),
    ]);
    assert_eq!(circles(&graph(&tree)).len(), 1);
}
