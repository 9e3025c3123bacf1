//! Helpers the integration tests share: the repository's scenes, a scratch directory
//! per process, and the program's CSV tables read by column name. Each test binary
//! compiles this module and uses part of it, hence `dead_code` allowed here.
#![allow(dead_code)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// `scenes/<name>` of the repository.
pub fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name)
}

/// An empty path in the temporary directory, unique to this process and `tag`.
pub fn scratch(prefix: &str, tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-{prefix}-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// Runs `jointlin ARGS`, panicking with its stderr unless it succeeds; its stderr.
pub fn run_ok<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> String {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{log}");
    log
}

/// The rows of a CSV file as column → text.
pub fn rows(path: &Path) -> Vec<HashMap<String, String>> {
    let mut r = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    r.records()
        .map(|rec| {
            header
                .iter()
                .cloned()
                .zip(rec.unwrap().iter().map(String::from))
                .collect()
        })
        .collect()
}

/// The numeric cells of a CSV file's rows as column → value (text columns left out).
pub fn numbers(path: &Path) -> Vec<HashMap<String, f64>> {
    rows(path)
        .into_iter()
        .map(|r| {
            r.into_iter()
                .filter_map(|(k, v)| v.parse::<f64>().ok().map(|v| (k, v)))
                .collect()
        })
        .collect()
}

/// Column `col` of `row` as a number.
pub fn num(row: &HashMap<String, String>, col: &str) -> f64 {
    row.get(col)
        .unwrap_or_else(|| panic!("no column {col}"))
        .parse()
        .unwrap_or_else(|e| panic!("{col}: {e}"))
}
