//! The layering checks of both crates.
//!
//! - The harness's rooms (top-level modules) import exactly what the table of
//!   docs/architecture.md says, each only rooms listed below it there, with no circle;
//!   a room missing from the table fails. The binary's files (main.rs, cli/) sit above
//!   every room and reach them as `jointlin_harness::`, so they are not rooms.
//! - No file-level circle in the harness or the library: two files that neither contains
//!   the other never import each other, directly or around a loop.
//! - Only `harness/src/capi/` names the library (`jointlin::`).
//! - No harness file over 500 lines, no function over 120 (test code aside), but those
//!   listed in [`OVERSIZED`] at no more than their listed size: the list only shrinks.
//!
//! Comments and test code are left out: a unit test may compare a room with a higher one,
//! e.g. a solver with its time-domain reference. Each rule is also run on a planted file
//! set to show that it fails on a violation.
//!
//! Run: `cargo test --release -p jointlin-harness --test layering`.

#[path = "layering/circles.rs"]
mod circles;
#[path = "layering/modules.rs"]
mod modules;
#[path = "layering/orphans.rs"]
mod orphans;
#[path = "layering/rooms.rs"]
mod rooms;
#[path = "layering/sizes.rs"]
mod sizes;
#[path = "layering/source.rs"]
mod source;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use circles::circles;
use source::{crate_files, files};

fn harness_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn architecture() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/architecture.md");
    std::fs::read_to_string(path).expect("docs/architecture.md")
}

fn rooms_of(tree: &[(String, String)]) -> BTreeSet<String> {
    tree.iter().filter_map(|(f, _)| rooms::room(f)).collect()
}

#[test]
fn the_harness_rooms_import_what_the_architecture_table_says() {
    let tree = crate_files(&harness_src());
    let g = rooms::graph(&tree);
    // The check sees the rooms (guards against reading nothing).
    assert!(g.contains_key("capi") && g.contains_key("solve"), "{g:?}");
    let c = circles(&g);
    assert!(
        c.is_empty(),
        "the rooms import each other in circles:\n{}",
        c.join("\n")
    );
    let table = rooms::table(&architecture());
    assert!(table.len() >= 10, "{table:?}");
    let v = rooms::violations(&g, &rooms_of(&tree), &table);
    assert!(
        v.is_empty(),
        "docs/architecture.md's table of rooms:\n{}",
        v.join("\n")
    );
}

#[test]
fn no_file_level_circle_in_either_crate() {
    let library = Path::new(env!("CARGO_MANIFEST_DIR")).join("../src");
    for src in [harness_src(), library] {
        let g = modules::graph(&crate_files(&src));
        assert!(g.len() > 20, "{}: {} files import", src.display(), g.len());
        let c = circles(&g);
        assert!(
            c.is_empty(),
            "{}: files in circles:\n{}",
            src.display(),
            c.join("\n")
        );
    }
}

#[test]
fn every_source_file_is_a_module_of_its_crate() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for src in [harness_src(), root.join("src"), root.join("python/rust")] {
        let tree = crate_files(&src);
        assert!(tree.len() > 4, "{}: read nothing", src.display());
        let o = orphans::orphans(&tree);
        assert!(
            o.is_empty(),
            "{}: files no module declares (never compiled):\n{}",
            src.display(),
            o.join("\n")
        );
    }
}

#[test]
fn a_planted_orphan_file_fails() {
    let tree = files(&[
        ("lib.rs", "mod a;\npub mod b;\n"),
        (
            "a.rs",
            "#[cfg(test)]\n#[path = \"a_tests.rs\"]\nmod tests;\n",
        ),
        ("a_tests.rs", "#[test]\nfn t() {}\n"),
        ("b/mod.rs", "mod c;\n"),
        ("b/c.rs", ""),
        ("b/d.rs", ""),
        ("e_tests.rs", "#[test]\nfn t() {}\n"),
        ("f/g.rs", ""),
    ]);
    assert_eq!(orphans::orphans(&tree), ["b/d.rs", "e_tests.rs", "f/g.rs"]);
}

#[test]
fn only_capi_names_the_library() {
    let calls = rooms::library_calls_outside_capi(&crate_files(&harness_src()));
    assert!(
        calls.is_empty(),
        "the library named outside capi/:\n{}",
        calls.join("\n")
    );
}

/// Files and functions over the size limits, at most this many lines: what is left to
/// split (nothing now; the planted-violation test keeps the rule honest). A listed item
/// that grows, a new one, or one that no longer needs listing fails.
const OVERSIZED: &[(&str, usize)] = &[];

/// What breaks the size rule in `found` against `listed`.
fn size_violations(found: &[(String, usize)], listed: &[(&str, usize)]) -> Vec<String> {
    let mut out = Vec::new();
    for (item, n) in found {
        match listed.iter().find(|(l, _)| l == item) {
            None => out.push(format!("{item}: {n} lines (not listed)")),
            Some((_, max)) if n > max => out.push(format!("{item}: {n} lines, listed at {max}")),
            Some(_) => {}
        }
    }
    for (item, max) in listed {
        if !found.iter().any(|(f, _)| f == item) {
            out.push(format!(
                "{item} (listed at {max}) is within the limits now: unlist it"
            ));
        }
    }
    out
}

#[test]
fn no_file_or_function_over_the_limits_beyond_the_listed() {
    let found = sizes::oversized(&crate_files(&harness_src()));
    let v = size_violations(&found, OVERSIZED);
    assert!(
        v.is_empty(),
        "sizes (files ≤ {} lines, functions ≤ {}):\n{}",
        sizes::FILE_MAX,
        sizes::FUNCTION_MAX,
        v.join("\n")
    );
}

#[test]
fn a_planted_long_function_and_file_fail() {
    let body = "    let x = 1;\n".repeat(119);
    let text =
        format!("pub(crate) fn long() {{\n    let s = \"}}\"; // }}\n{body}}}\nfn short() {{}}\n");
    let tests = "#[cfg(test)]\nmod tests {\n".to_string() + &"    // x\n".repeat(600) + "}\n";
    let tree = files(&[
        ("a.rs", &text),
        ("b.rs", &tests),
        ("c.rs", &"// y\n".repeat(501)),
    ]);
    let found = sizes::oversized(&tree);
    assert_eq!(
        found,
        [("a.rs::long".to_string(), 122), ("c.rs".to_string(), 501)]
    );
    assert_eq!(
        size_violations(&found, &[("a.rs::long", 122), ("c.rs", 501)]),
        Vec::<String>::new()
    );
    let v = size_violations(&found, &[("a.rs::long", 121), ("d.rs", 600)]);
    assert_eq!(
        v,
        [
            "a.rs::long: 122 lines, listed at 121",
            "c.rs: 501 lines (not listed)",
            "d.rs (listed at 600) is within the limits now: unlist it",
        ]
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
    let c = circles(&rooms::graph(&tree));
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
    assert!(circles(&rooms::graph(&tree)).is_empty());
    assert!(circles(&modules::graph(&tree)).is_empty());
    // The same import outside test code closes the circle.
    let tree = files(&[
        ("a.rs", "use crate::b::X;\n"),
        ("b/mod.rs", "use crate::a::Y;\n"),
    ]);
    assert_eq!(circles(&rooms::graph(&tree)).len(), 1);
}

/// A planted table: low ← mid ← top, side.
const TABLE: &str = "# Rooms\n\n## The rooms\n\n| room | what | imports |\n|---|---|---|\n\
| `low/` | bottom | — |\n| `mid.rs` | middle | low |\n| `top/`, `side/` | top | mid, low |\n\n## Next\n";

#[test]
fn the_table_is_read_and_each_of_its_rules_fails_when_broken() {
    let table = rooms::table(TABLE);
    let names: Vec<&str> = table.iter().map(|(r, _)| r.as_str()).collect();
    assert_eq!(names, ["low", "mid", "top", "side"]);
    let check = |list: &[(&str, &str)], table: &rooms::Table| {
        let tree = files(list);
        rooms::violations(&rooms::graph(&tree), &rooms_of(&tree), table)
    };
    let good = [
        ("low/mod.rs", "pub fn f() {}\n"),
        ("mid.rs", "use crate::low::f;\n"),
        ("top/mod.rs", "use crate::mid::g;\nuse crate::low::f;\n"),
        ("side/mod.rs", "use crate::{low::f, mid::g};\n"),
    ];
    assert_eq!(check(&good, &table), Vec::<String>::new());
    let mut unlisted = good.to_vec();
    unlisted[0] = ("low/mod.rs", "use crate::mid::g;\n");
    let v = check(&unlisted, &table);
    let first = "low imports mid, which its row does not list: low/mod.rs:1";
    assert!(v.iter().any(|m| m.starts_with(first)), "{v:?}");
    let mut stale = good.to_vec();
    stale[2] = ("top/mod.rs", "use crate::mid::g;\n");
    assert_eq!(
        check(&stale, &table),
        ["top's row lists low, which it does not import"]
    );
    let mut missing = good.to_vec();
    missing.push(("extra.rs", "pub fn h() {}\n"));
    assert_eq!(
        check(&missing, &table),
        ["room extra is not in the table of docs/architecture.md"]
    );
    let upside = rooms::table(&TABLE.replace("| bottom | — |", "| bottom | mid |"));
    let v = check(&good, &upside);
    let above = "low's row lists mid, which stands above it in the table";
    assert!(v.iter().any(|m| m == above), "{v:?}");
}

#[test]
fn a_planted_file_circle_fails_and_ancestors_do_not_count() {
    // A parent re-exporting its children, children using their parent: no circle.
    let family = [
        ("lib.rs", "pub mod a;\n"),
        (
            "a/mod.rs",
            "mod b;\nmod c;\npub use b::B;\npub use self::c::C;\npub struct P;\n",
        ),
        ("a/b.rs", "use super::P;\npub struct B;\n"),
        ("a/c.rs", "use super::{b::B, P};\npub struct C;\n"),
    ];
    assert_eq!(
        circles(&modules::graph(&files(&family))),
        Vec::<String>::new()
    );
    // Two siblings naming each other, one through a multi-line use tree: a circle.
    let mut siblings = family.to_vec();
    siblings[2] = (
        "a/b.rs",
        "use crate::a::{\n    c::C,\n    P,\n};\npub struct B;\n",
    );
    let c = circles(&modules::graph(&files(&siblings)));
    assert_eq!(c.len(), 1, "{c:?}");
    assert!(
        c[0].starts_with("circle between a/b.rs, a/c.rs:"),
        "{}",
        c[0]
    );
    let import = "a/b.rs -> a/c.rs: a/b.rs:1: use crate::a::{ c::C, P, };";
    assert!(c[0].contains(import), "{}", c[0]);
    // A path in an expression counts too.
    let mut expr = family.to_vec();
    expr[2] = ("a/b.rs", "pub fn f() -> u8 { super::c::g() }\n");
    assert_eq!(circles(&modules::graph(&files(&expr))).len(), 1);
}

#[test]
fn a_planted_library_call_outside_capi_fails() {
    let tree = files(&[
        (
            "capi/mod.rs",
            "use jointlin::ffi::linearize::jointlin_linearize;\n",
        ),
        (
            "solve/x.rs",
            "// jointlin::ffi in a comment\nlet v = my_jointlin::f();\n",
        ),
        (
            "solve/y.rs",
            "fn f() { jointlin::ffi::error::jointlin_last_error(); }\n",
        ),
    ]);
    assert_eq!(
        rooms::library_calls_outside_capi(&tree),
        ["solve/y.rs:1: fn f() { jointlin::ffi::error::jointlin_last_error(); }"]
    );
}
