//! Every repository path the README and the docs name in backticks exists: a file or
//! folder moved without its mentions fails here. A path is looked up from the
//! repository's root, `harness/`, `harness/src/`, `src/`, `examples/abaqus/` and the
//! document's own folder; a bare folder name (`sweep/`) anywhere under `src/` or
//! `harness/src/`. Paths of a run's output or of an installation (below) are not the
//! repository's.

use std::path::{Path, PathBuf};

/// Prefixes of paths that name a run's output or an installed tree, not the repository.
const NOT_REPOSITORY: [&str; 7] = ["out/", "job/", "DIR/", "bin/", "lib/", "share/", "./"];

/// File endings of the paths checked (and a trailing `/` for folders).
const ENDINGS: [&str; 15] = [
    ".rs", ".sh", ".toml", ".inp", ".geo", ".f90", ".f", ".h", ".md", ".csv", ".py", ".json",
    ".svg", ".cfg", ".frq",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Backticked spans of `text` that look like repository paths, with their line numbers.
fn paths(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        for (k, span) in line.split('`').enumerate() {
            let path_like = k % 2 == 1
                && span.contains('/')
                && !span.contains(char::is_whitespace)
                && !span.contains(['*', '<', '{', '$', '~'])
                && !span.starts_with(['/', '-'])
                && !span.starts_with("http")
                && !span.starts_with("../")
                && (span.ends_with('/') || ENDINGS.iter().any(|e| span.ends_with(e)));
            if path_like && !NOT_REPOSITORY.iter().any(|p| span.starts_with(p)) {
                out.push((i + 1, span.to_string()));
            }
        }
    }
    out
}

/// True when a folder named `name` exists somewhere under `dir`.
fn folder_below(dir: &Path, name: &str) -> bool {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return false;
    };
    entries.flatten().any(|e| {
        let p = e.path();
        p.is_dir() && (p.file_name().is_some_and(|f| f == name) || folder_below(&p, name))
    })
}

fn exists(doc: &Path, path: &str) -> bool {
    let r = root();
    let bases = [
        r.clone(),
        r.join("harness"),
        r.join("harness/src"),
        r.join("src"),
        r.join("examples/abaqus"),
        doc.parent().unwrap().to_path_buf(),
    ];
    if bases.iter().any(|b| b.join(path).exists()) {
        return true;
    }
    let name = path.trim_end_matches('/');
    path.ends_with('/')
        && !name.contains('/')
        && (folder_below(&r.join("src"), name) || folder_below(&r.join("harness/src"), name))
}

#[test]
fn every_path_the_readme_and_docs_name_exists() {
    let r = root();
    let mut docs = vec![r.join("README.md"), r.join("fortran-shim/README.md")];
    for e in std::fs::read_dir(r.join("docs")).unwrap().flatten() {
        if e.path().extension().is_some_and(|x| x == "md") {
            docs.push(e.path());
        }
    }
    let mut checked = 0;
    let mut missing = Vec::new();
    for doc in &docs {
        let text = std::fs::read_to_string(doc).unwrap();
        for (line, path) in paths(&text) {
            checked += 1;
            if !exists(doc, &path) {
                let name = doc.strip_prefix(&r).unwrap().display();
                missing.push(format!("{name}:{line}: `{path}`"));
            }
        }
    }
    assert!(
        checked > 200,
        "only {checked} paths found: the scan is broken"
    );
    assert!(
        missing.is_empty(),
        "paths that do not exist:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_scan_finds_a_planted_stale_path() {
    let text = "see `harness/src/mhb/tests.rs` and `src/law/` and `out/x.csv`";
    let found = paths(text);
    assert_eq!(found.len(), 2, "{found:?}");
    let doc = root().join("README.md");
    assert!(!exists(&doc, &found[0].1));
    assert!(exists(&doc, &found[1].1));
}
