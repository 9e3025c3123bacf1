//! Where an output came from: the head every run.json starts with — the schema version,
//! the jointlin that wrote it, the command line, the time, and the input files read
//! (the scene, the deck, its `*INCLUDE` and `INPUT=` files, a shim configuration; not
//! yet the `[[matrices]]` files) with their sizes and SHA-256, so a result can be traced
//! to the exact bytes it was computed from (`sha256sum FILE` prints the same digest).

use std::time::SystemTime;

use serde::Serialize;
use serde_json::{json, Map, Value};
use sha2::{Digest, Sha256};

/// The version of the run.json layout (docs/outputs.md); raised when a key changes
/// meaning or disappears, not when one is added.
pub const SCHEMA_VERSION: u32 = 1;

/// One input file as it was read.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct SourceFile {
    /// The path as given (relative to the working directory, or to the including file's
    /// directory joined to it).
    pub file: String,
    pub bytes: u64,
    /// SHA-256 of the file's bytes, lowercase hex.
    pub sha256: String,
}

impl SourceFile {
    /// The record of `bytes` read from `file`.
    pub fn of(file: &str, bytes: &[u8]) -> SourceFile {
        SourceFile {
            file: file.to_string(),
            bytes: bytes.len() as u64,
            sha256: Sha256::digest(bytes)
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect(),
        }
    }
}

/// The head of a run.json: `schema_version`, `command` (the subcommand, e.g. "run",
/// "backbone"), `jointlin` (the harness's version and the loaded library's C ABI
/// version), `command_line`, `written_at` (UTC, RFC 3339) and `inputs` (each file
/// once, in reading order).
pub fn head(command: &str, library_abi: &str, inputs: &[SourceFile]) -> Map<String, Value> {
    let mut seen = std::collections::HashSet::new();
    let inputs: Vec<&SourceFile> = inputs
        .iter()
        .filter(|s| seen.insert((&s.file, &s.sha256)))
        .collect();
    let mut m = Map::new();
    m.insert("schema_version".into(), json!(SCHEMA_VERSION));
    m.insert("command".into(), json!(command));
    m.insert(
        "jointlin".into(),
        json!({"harness": env!("CARGO_PKG_VERSION"), "library_abi": library_abi}),
    );
    m.insert(
        "command_line".into(),
        // Lossy: a path that is not UTF-8 is still recorded, never a panic.
        json!(std::env::args_os()
            .map(|a| a.to_string_lossy().into_owned())
            .collect::<Vec<_>>()),
    );
    m.insert(
        "written_at".into(),
        json!(humantime::format_rfc3339_seconds(SystemTime::now()).to_string()),
    );
    m.insert("inputs".into(), json!(inputs));
    m
}

/// `head` followed by the keys of `body` (an object; anything else is put under
/// "body").
pub fn with_head(head: Map<String, Value>, body: Value) -> Value {
    let mut m = head;
    match body {
        Value::Object(b) => m.extend(b),
        other => {
            m.insert("body".into(), other);
        }
    }
    Value::Object(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_digest_is_sha256_and_inputs_are_listed_once() {
        // SHA-256 of "abc" (FIPS 180-2, appendix B.1).
        let s = SourceFile::of("a.inp", b"abc");
        assert_eq!(
            s.sha256,
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(s.bytes, 3);
        let h = head("run", "0.6.0", &[s.clone(), s]);
        assert_eq!(h["inputs"].as_array().unwrap().len(), 1);
        assert_eq!(h["schema_version"], SCHEMA_VERSION);
        let t = h["written_at"].as_str().unwrap();
        assert!(t.ends_with('Z') && t.len() == 20, "{t}");
        let v = with_head(h, json!({"mode": "fast"}));
        assert_eq!(v["mode"], "fast");
        assert_eq!(v["command"], "run");
    }
}
