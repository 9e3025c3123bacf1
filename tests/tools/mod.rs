//! What a test does when an external tool it needs is missing (CalculiX, Gmsh, MPI,
//! valgrind, a C or C++ compiler): on CI (`CI` set, neither empty nor "false") every one
//! is installed by scripts/deps.sh, so a missing one fails the test; elsewhere the test
//! says why it skips (stderr, and a file in `target/tmp/skipped/` that scripts/test.sh
//! counts at the end) and returns. Shared by the tests of both crates (`#[path]`).

#![allow(dead_code)]

/// True on CI.
pub fn on_ci() -> bool {
    matches!(std::env::var("CI").as_deref(), Ok(v) if !v.is_empty() && v != "false")
}

/// Reports `tool` missing for test `test` (`why`: what was tried): a panic on CI, else
/// the skip note. The caller returns after it.
pub fn missing(test: &str, tool: &str, why: &str) {
    assert!(
        !on_ci(),
        "{test}: {tool} missing on CI ({why}); scripts/deps.sh installs it"
    );
    eprintln!("SKIPPED {test}: {tool} missing ({why})");
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("skipped");
    let _ = std::fs::create_dir_all(&dir);
    let _ = std::fs::write(dir.join(test), format!("{tool} missing ({why})\n"));
}
