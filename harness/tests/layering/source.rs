//! Reading a crate's source for the layering checks: its files, the lines that are code
//! (not comments, not test items), and an import found on one of them.

use std::path::Path;

/// An import of one room or file by another: where it is and the line's text.
#[derive(Debug, Clone)]
pub struct Import {
    pub file: String,
    pub line: usize,
    pub text: String,
}

/// Every .rs file under `dir`, path relative to `root` with `/` separators, and its text.
pub fn read_tree(root: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
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

/// The source files of the crate directory `src` (…/src).
pub fn crate_files(src: &Path) -> Vec<(String, String)> {
    let mut tree = Vec::new();
    read_tree(src, src, &mut tree);
    tree
}

/// A planted file set: (path, text) pairs.
pub fn files(list: &[(&str, &str)]) -> Vec<(String, String)> {
    list.iter()
        .map(|(f, t)| (f.to_string(), t.to_string()))
        .collect()
}

/// A file that holds only test code: `tests.rs`, `*_tests.rs`, or any file under a
/// `tests/` directory (a `#[cfg(test)] mod tests;` split into files).
pub fn is_test_file(file: &str) -> bool {
    let name = file.rsplit('/').next().unwrap_or(file);
    name == "tests.rs" || name.ends_with("_tests.rs") || file.split('/').any(|d| d == "tests")
}

/// The lines of `text` outside `#[cfg(test)]` items, numbered from 1.
pub fn non_test_lines(text: &str) -> Vec<(usize, &str)> {
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
        out.push((i + 1, line));
    }
    out
}

/// The lines of `text` outside `#[cfg(test)]` items and `//` comments, numbered from 1.
pub fn code_lines(text: &str) -> Vec<(usize, &str)> {
    non_test_lines(text)
        .into_iter()
        .filter(|(_, l)| !l.trim().starts_with("//"))
        .collect()
}
