//! The rooms of the harness (its top-level modules) and the table of docs/architecture.md
//! that says, from the bottom up, what each room may import.

use std::collections::{BTreeMap, BTreeSet};

use super::circles::{add, Graph};
use super::modules::named_paths;
use super::source::{code_lines, is_test_file, Import};

/// The room of a file (path relative to src/, `/`-separated), `None` for the crate
/// roots and the binary's files.
pub fn room(file: &str) -> Option<String> {
    let first = file.split('/').next()?;
    let name = first.strip_suffix(".rs").unwrap_or(first);
    (!matches!(name, "lib" | "main" | "cli")).then(|| name.to_string())
}

/// The graph between the rooms of `files` (path relative to src/, text); test code left
/// out (a unit test may compare a room with a higher one).
pub fn graph(files: &[(String, String)]) -> Graph {
    let rooms: BTreeSet<String> = files.iter().filter_map(|(f, _)| room(f)).collect();
    let mut g = Graph::new();
    for (file, text) in files {
        let Some(from) = room(file) else { continue };
        if is_test_file(file) {
            continue;
        }
        for (n, text, path) in named_paths(text) {
            let to = &path[1];
            if path[0] == "crate" && *to != from && rooms.contains(to) {
                let file = file.clone();
                add(
                    &mut g,
                    &from,
                    to,
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

/// The table of rooms: each room, bottom first, with the rooms it may import.
pub type Table = Vec<(String, BTreeSet<String>)>;

/// The table under "## The rooms" of docs/architecture.md: rows `| `room/`, … | what |
/// imports |`, the imports comma-separated room names or `—`.
pub fn table(doc: &str) -> Table {
    let section = doc
        .split("\n## ")
        .find(|s| s.starts_with("The rooms"))
        .expect("docs/architecture.md has a section \"The rooms\"");
    let mut out = Table::new();
    for line in section.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = line.split(" | ").collect();
        let imports = cells.last().expect("a row").trim_end_matches(" |").trim();
        let may: BTreeSet<String> = imports
            .split(',')
            .map(|s| s.trim().to_string())
            .filter(|s| !s.is_empty() && s != "—")
            .collect();
        for name in cells[0].trim_start_matches("| ").split(", ") {
            let name = name.trim_matches('`');
            let name = name.trim_end_matches('/').trim_end_matches(".rs");
            out.push((name.to_string(), may.clone()));
        }
    }
    out
}

/// Every way the rooms break the table: a room missing from it, an import it does not
/// list, a listed room that stands above (or is) the importer, a listed import that is
/// not made (the table says exactly what each room imports).
pub fn violations(g: &Graph, rooms: &BTreeSet<String>, table: &Table) -> Vec<String> {
    let mut out = Vec::new();
    let rank: BTreeMap<&str, usize> = table
        .iter()
        .enumerate()
        .map(|(i, (r, _))| (r.as_str(), i))
        .collect();
    for r in rooms.iter().filter(|r| !rank.contains_key(r.as_str())) {
        out.push(format!(
            "room {r} is not in the table of docs/architecture.md"
        ));
    }
    let none = BTreeMap::new();
    for (room, may) in table {
        let made = g.get(room).unwrap_or(&none);
        for (to, imports) in made {
            if !may.contains(to) {
                let i = &imports[0];
                out.push(format!(
                    "{room} imports {to}, which its row does not list: {}:{}: {}",
                    i.file, i.line, i.text
                ));
            }
        }
        for to in may {
            match rank.get(to.as_str()) {
                None => out.push(format!("{room}'s row lists {to}, which is no room")),
                Some(&k) if k >= rank[room.as_str()] => out.push(format!(
                    "{room}'s row lists {to}, which stands above it in the table"
                )),
                Some(_) if !made.contains_key(to) => {
                    out.push(format!("{room}'s row lists {to}, which it does not import"))
                }
                Some(_) => {}
            }
        }
    }
    out
}

/// Files outside `capi/` that name the library (`jointlin::`): only `capi/` calls it.
pub fn library_calls_outside_capi(files: &[(String, String)]) -> Vec<String> {
    let mut out = Vec::new();
    for (file, text) in files {
        if file.starts_with("capi/") {
            continue;
        }
        for (n, line) in code_lines(text) {
            let hit = line.match_indices("jointlin::").any(|(at, _)| {
                let before = line[..at].chars().next_back();
                !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
            });
            if hit {
                out.push(format!("{file}:{n}: {}", line.trim()));
            }
        }
    }
    out
}
