//! Every `#[test]` of both crates can fail: its body asserts (`assert…!`, `panic!`,
//! `unreachable!`, `.expect(`, `.unwrap_err(`, a `?` on a fallible comparison is not
//! enough), or calls a function of the same crates that does, or the test expects a
//! panic (`#[should_panic]`). Allowed exceptions are listed in [`ALLOWED`] with the
//! reason. The scan reads the sources as text: comments, strings and characters are
//! skipped when matching braces.

use std::path::{Path, PathBuf};

/// Tests without an assertion of their own, with the reason they may be.
const ALLOWED: [(&str, &str); 2] = [
    (
        "host_process",
        "the restart tests' host process, ignored as a test (tests/restart.rs)",
    ),
    (
        "regenerate_unit_cell_table",
        "writes the committed table, ignored as a test; the_committed_table_is_the_integrated_unit_cell_at_its_nodes checks it",
    ),
];

/// What makes a body able to fail.
const FAILS: [&str; 6] = [
    "assert",
    "panic!",
    "unreachable!",
    ".expect(",
    ".unwrap_err(",
    "todo!",
];

struct Function {
    file: PathBuf,
    name: String,
    attributes: String,
    body: String,
}

/// Index just after the literal or comment starting at `i`, or None if none starts there.
fn skip_literal(b: &[u8], i: usize) -> Option<usize> {
    let rest = &b[i..];
    if rest.starts_with(b"//") {
        return Some(
            b[i..]
                .iter()
                .position(|&c| c == b'\n')
                .map_or(b.len(), |p| i + p),
        );
    }
    if rest.starts_with(b"/*") {
        return Some(find(b, i + 2, b"*/").map_or(b.len(), |p| p + 2));
    }
    if rest.starts_with(b"r\"") || rest.starts_with(b"r#") {
        let hashes = rest[1..].iter().take_while(|&&c| c == b'#').count();
        if rest.get(1 + hashes) == Some(&b'"') {
            let mut close = vec![b'"'];
            close.extend(std::iter::repeat_n(b'#', hashes));
            return Some(find(b, i + 2 + hashes, &close).map_or(b.len(), |p| p + close.len()));
        }
    }
    if rest[0] == b'"' {
        let mut j = i + 1;
        while j < b.len() && b[j] != b'"' {
            j += if b[j] == b'\\' { 2 } else { 1 };
        }
        return Some(j + 1);
    }
    if rest[0] == b'\'' {
        // A character ('x', '\n', '\u{..}'), not a lifetime ('a).
        if rest.get(1) == Some(&b'\\') {
            return find(b, i + 2, b"'").map(|p| p + 1);
        }
        let ch = std::str::from_utf8(&rest[1..rest.len().min(6)])
            .ok()
            .or_else(|| std::str::from_utf8(&rest[1..rest.len().min(5)]).ok())
            .and_then(|s| s.chars().next());
        if let Some(c) = ch {
            if rest.get(1 + c.len_utf8()) == Some(&b'\'') {
                return Some(i + 2 + c.len_utf8());
            }
        }
    }
    None
}

/// `text` with its comments, strings and characters left out.
fn code_only(text: &str) -> String {
    let b = text.as_bytes();
    let (mut out, mut i, mut kept) = (Vec::new(), 0, 0);
    while i < b.len() {
        match skip_literal(b, i) {
            Some(next) => {
                out.extend_from_slice(&b[kept..i]);
                out.push(b' ');
                i = next.min(b.len());
                kept = i;
            }
            None => i += 1,
        }
    }
    out.extend_from_slice(&b[kept..]);
    String::from_utf8_lossy(&out).into_owned()
}

fn find(b: &[u8], from: usize, pat: &[u8]) -> Option<usize> {
    (from..=b.len().saturating_sub(pat.len())).find(|&j| &b[j..j + pat.len()] == pat)
}

/// Index of the bracket that closes the one at `open` (`(`/`)` or `{`/`}`).
fn closing(b: &[u8], open: usize) -> Option<usize> {
    let (o, c) = (b[open], if b[open] == b'(' { b')' } else { b'}' });
    let (mut depth, mut i) = (0usize, open);
    while i < b.len() {
        if let Some(next) = skip_literal(b, i) {
            i = next;
            continue;
        }
        if b[i] == o {
            depth += 1;
        } else if b[i] == c {
            depth -= 1;
            if depth == 0 {
                return Some(i);
            }
        }
        i += 1;
    }
    None
}

/// The functions with bodies in `text`, each with the attributes right before it.
fn functions(file: &Path, text: &str) -> Vec<Function> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if let Some(next) = skip_literal(b, i) {
            i = next;
            continue;
        }
        let word_start = i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        if !(word_start && b[i..].starts_with(b"fn ")) {
            i += 1;
            continue;
        }
        let name_start = i + 3;
        let name_end = (name_start..b.len())
            .find(|&j| !(b[j].is_ascii_alphanumeric() || b[j] == b'_'))
            .unwrap_or(b.len());
        let Some(paren) = (name_end..b.len()).find(|&j| b[j] == b'(') else {
            break;
        };
        let Some(after) = closing(b, paren) else {
            break;
        };
        let Some(brace) = (after..b.len()).find(|&j| b[j] == b'{' || b[j] == b';') else {
            break;
        };
        if b[brace] == b';' {
            i = brace + 1;
            continue;
        }
        let end = closing(b, brace).unwrap_or(b.len() - 1);
        // Attributes: the lines right above `fn` that are attributes, doc comments or
        // qualifiers.
        let line_start = text[..i].rfind('\n').map_or(0, |p| p + 1);
        let mut attributes = String::new();
        for line in text[..line_start].lines().rev() {
            let t = line.trim();
            if t.starts_with("#[")
                || t.starts_with("///")
                || t.starts_with("//")
                || t.ends_with(']')
            {
                attributes.insert_str(0, &format!("{t}\n"));
            } else {
                break;
            }
        }
        attributes.push_str(&text[line_start..i]);
        out.push(Function {
            file: file.to_path_buf(),
            name: text[name_start..name_end].to_string(),
            attributes,
            body: code_only(&text[brace..=end]),
        });
        i = brace + 1; // nested functions are scanned too
    }
    out
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

fn calls(body: &str, name: &str) -> bool {
    body.match_indices(name).any(|(k, _)| {
        let before = body[..k].chars().next_back();
        let after = body[k + name.len()..].trim_start();
        !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
            && (after.starts_with('(') || after.starts_with("::<") || after.starts_with('!'))
    })
}

/// The test functions under `dirs` that cannot fail: (file, name).
fn weak_tests(dirs: &[PathBuf]) -> (usize, Vec<(PathBuf, String)>) {
    let mut files = Vec::new();
    for d in dirs {
        rust_files(d, &mut files);
    }
    let all: Vec<Function> = files
        .iter()
        .flat_map(|f| functions(f, &std::fs::read_to_string(f).unwrap()))
        .collect();
    let fails = |body: &str| FAILS.iter().any(|f| body.contains(f));
    // A helper counts for a test in its own file, or anywhere when it is test code
    // itself (a file under a `tests` folder): the library's own asserts do not.
    let shared = |f: &Function| f.file.components().any(|c| c.as_os_str() == "tests");
    let mut strong: Vec<bool> = all.iter().map(|f| fails(&f.body)).collect();
    loop {
        let mut changed = false;
        for (i, f) in all.iter().enumerate() {
            if strong[i] {
                continue;
            }
            let helps = all.iter().zip(&strong).any(|(h, &s)| {
                s && h.name.len() > 2 && (h.file == f.file || shared(h)) && calls(&f.body, &h.name)
            });
            if helps {
                strong[i] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let is_test = |f: &Function| f.attributes.lines().any(|l| l.trim() == "#[test]");
    let count = all.iter().filter(|f| is_test(f)).count();
    let weak = all
        .iter()
        .zip(&strong)
        .filter(|(f, &s)| {
            is_test(f)
                && !s
                && !f.attributes.contains("should_panic")
                && !ALLOWED.iter().any(|(n, _)| *n == f.name)
        })
        .map(|(f, _)| (f.file.clone(), f.name.clone()))
        .collect();
    (count, weak)
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_test_can_fail() {
    let r = root();
    let dirs = ["src", "tests", "harness/src", "harness/tests"].map(|d| r.join(d));
    let (count, weak) = weak_tests(&dirs);
    assert!(count > 400, "only {count} tests found: the scan is broken");
    let list: Vec<String> = weak
        .iter()
        .map(|(f, n)| format!("{}: {n}", f.strip_prefix(&r).unwrap().display()))
        .collect();
    assert!(
        list.is_empty(),
        "tests without an assertion:\n{}",
        list.join("\n")
    );
}

#[test]
fn a_planted_test_without_an_assertion_is_found() {
    let dir = std::env::temp_dir().join(format!("jointlin-test-scan-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("planted.rs"),
        "fn helper(x: [f64; 2]) { assert!(x[0] < 1.0, \"{\"); }\n\
         #[test]\nfn delegates() { helper([0.0; 2]); }\n\
         #[test]\nfn prints_only() { let s = \"assert!(false)\"; println!(\"{s} }\"); }\n\
         #[test]\n#[should_panic]\nfn expects_a_panic() { let _ = 1; }\n",
    )
    .unwrap();
    let (count, weak) = weak_tests(std::slice::from_ref(&dir));
    let names: Vec<&str> = weak.iter().map(|(_, n)| n.as_str()).collect();
    assert_eq!((count, names), (3, vec!["prints_only"]));
    let _ = std::fs::remove_dir_all(&dir);
}
