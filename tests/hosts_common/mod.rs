//! Shared helpers of tests/hosts*.rs: find the libjointlin.so that cargo built for this
//! test run, build the C/Fortran programs against it with make, run them (optionally
//! under valgrind) and parse their `name number number ...` records.

#![allow(dead_code)]

pub mod sweep_model;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Relative tolerance between a host's numbers and the Rust API's: the same code runs on
/// both sides, so the only differences are the hosts' own arithmetic (complex division,
/// |x|) in the last bits.
pub const RTOL: f64 = 1e-12;

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// target/<profile>/deps, where the test executable lives.
fn exe_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    exe.parent().expect("deps directory").to_path_buf()
}

/// The SONAME build.rs gives libjointlin.so: `libjointlin.so.<ABI major>`. Programs linked
/// against the library load it by this name.
pub fn soname() -> String {
    format!(
        "libjointlin.so.{}",
        jointlin::ffi::JOINTLIN_ABI_VERSION_MAJOR
    )
}

/// The directory holding the libjointlin.so that `cargo test` built with this test
/// binary: target/<profile>/deps (or target/<profile> when cargo uplifted it). `cargo
/// test` builds the cdylib with the package's tests; should it be missing (another test
/// runner), `cargo build --lib` builds it into the same target directory and profile.
/// The directory also gets the link `libjointlin.so.<major>` → `libjointlin.so` (cargo
/// makes none), so that programs linked against it find it by its SONAME.
pub fn lib_dir() -> PathBuf {
    static LINKED: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    LINKED
        .get_or_init(|| {
            let dir = cargo_lib_dir();
            let link = dir.join(soname());
            if std::fs::symlink_metadata(&link).is_err() {
                // Another test binary may create it at the same time: only its existence
                // matters.
                let _ = std::os::unix::fs::symlink("libjointlin.so", &link);
            }
            assert!(link.exists(), "cannot create {}", link.display());
            dir
        })
        .clone()
}

fn cargo_lib_dir() -> PathBuf {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let deps = exe_dir();
        let profile_dir = deps.parent().unwrap().to_path_buf();
        let find = || {
            [deps.clone(), profile_dir.clone()]
                .into_iter()
                .find(|d| d.join("libjointlin.so").is_file())
        };
        if let Some(d) = find() {
            return d;
        }
        let profile = profile_dir
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
        let mut cmd = Command::new(cargo);
        cmd.args(["build", "-p", "jointlin", "--lib", "--profile"])
            .arg(if profile == "debug" { "dev" } else { &profile })
            .env("CARGO_TARGET_DIR", profile_dir.parent().unwrap())
            .current_dir(root());
        run_ok(&mut cmd);
        find().unwrap_or_else(|| {
            panic!(
                "libjointlin.so not found in {} after cargo build",
                deps.display()
            )
        })
    })
    .clone()
}

/// A per-suite build directory under target/<profile>/jointlin-hosts.
pub fn build_dir(suite: &str) -> PathBuf {
    let d = exe_dir()
        .parent()
        .unwrap()
        .join("jointlin-hosts")
        .join(suite);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A fresh scratch directory (unique within the process).
pub fn scratch(name: &str) -> PathBuf {
    static N: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let d = build_dir("scratch").join(format!("{name}-{}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs a command, panicking with its output when it fails.
pub fn run_ok(cmd: &mut Command) -> Output {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"));
    assert!(
        out.status.success(),
        "{cmd:?} failed ({}):\nstdout:\n{}\nstderr:\n{}",
        out.status,
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// `make -s -f <root>/<makefile> VAR=value ...`.
pub fn make(makefile: &str, vars: &[(&str, &Path)]) {
    let mut cmd = Command::new("make");
    cmd.arg("-s").arg("-f").arg(root().join(makefile));
    for (k, v) in vars {
        cmd.arg(format!("{k}={}", v.display()));
    }
    run_ok(&mut cmd);
}

/// Builds the Fortran shim into `<dir>/shim` and returns that directory.
pub fn build_shim(dir: &Path) -> PathBuf {
    let shim = dir.join("shim");
    make(
        "fortran-shim/Makefile",
        &[("BUILD", &shim), ("JOINTLIN_LIBDIR", &lib_dir())],
    );
    shim
}

/// Builds the shim into `<dir>/shim` and the Fortran host programs
/// (harness/fortran/Makefile) against it into `<dir>/fortran`; returns the latter.
pub fn build_fortran_hosts(dir: &Path) -> PathBuf {
    let shim = build_shim(dir);
    let fortran = dir.join("fortran");
    make(
        "harness/fortran/Makefile",
        &[
            ("BUILD", &fortran),
            ("SHIM", &shim),
            ("JOINTLIN_LIBDIR", &lib_dir()),
        ],
    );
    fortran
}

pub fn valgrind_available() -> bool {
    Command::new("valgrind")
        .arg("--version")
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false)
}

/// The valgrind command the CI runs the hosts under.
pub fn valgrind(program: &Path) -> Command {
    let mut cmd = Command::new("valgrind");
    cmd.args([
        "--error-exitcode=1",
        "--leak-check=full",
        "--errors-for-leak-kinds=definite",
        "--quiet",
    ])
    .arg(program);
    cmd
}

/// One output record: its name and its numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    pub name: String,
    pub values: Vec<f64>,
}

pub fn parse(stdout: &[u8]) -> Vec<Record> {
    String::from_utf8_lossy(stdout)
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let mut it = l.split_whitespace();
            let name = it.next().unwrap().to_string();
            let values = it
                .map(|v| {
                    v.parse::<f64>()
                        .unwrap_or_else(|_| panic!("not a number {v:?} in {l:?}"))
                })
                .collect();
            Record { name, values }
        })
        .collect()
}

/// |a − b| ≤ RTOL·max(|a|, |b|) (so exact zeros must be exact).
pub fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= RTOL * a.abs().max(b.abs())
}

/// Compares two record lists field by field.
pub fn assert_records(host: &str, got: &[Record], want: &[Record]) {
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.name, w.name, "{host}: record {i} name");
        assert_eq!(
            g.values.len(),
            w.values.len(),
            "{host}: record {i} ({}) length",
            g.name
        );
        for (j, (&a, &b)) in g.values.iter().zip(&w.values).enumerate() {
            assert!(
                close(a, b),
                "{host}: record {i} ({}) field {j}: host {a:e}, Rust {b:e}\nhost: {:?}\nRust: {:?}",
                g.name,
                g.values,
                w.values
            );
        }
    }
    assert_eq!(got.len(), want.len(), "{host}: number of records");
}
