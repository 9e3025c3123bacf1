//! The C hosts (harness/c) and the Fortran hosts (harness/fortran, through the
//! Abaqus-signature shim in fortran-shim) built with gcc/gfortran against the
//! libjointlin.so of this cargo build, run, and checked number by number against the Rust
//! API (`jointlin::hysteresis`, `jointlin::linearize`, `jointlin::store`) to 1e-12
//! relative; then run again under valgrind memcheck (zero errors, nothing definitely
//! lost) when valgrind is installed.

#[path = "tools/mod.rs"]
mod tools;

mod hosts_common;

use std::f64::consts::PI;
use std::path::PathBuf;
use std::process::Command;
use std::sync::OnceLock;

use hosts_common::sweep_model::*;
use hosts_common::*;
use jointlin::hysteresis::{PointState, Rule};
use jointlin::linearize::{linearize, Method};
use jointlin::store::KincNumbering;

// The block host's data (harness/c/host.h, harness/fortran/host_data.f90); the rest in
// hosts_common::sweep_model.
const OMEGA: f64 = 1.3;
const AMPLITUDE: f64 = 4.401e-4;
const STEPS: usize = 48;
const CYCLES: usize = 3;

struct Programs {
    c: PathBuf,
    fortran: PathBuf,
}

/// Builds both host sets once per test binary.
fn programs() -> &'static Programs {
    static P: OnceLock<Programs> = OnceLock::new();
    P.get_or_init(|| {
        let dir = build_dir("hosts");
        let lib = lib_dir();
        let c = dir.join("c");
        make(
            "harness/c/Makefile",
            &[
                ("BUILD", &c),
                ("JOINTLIN_LIBDIR", &lib),
                ("JOINTLIN_INCDIR", &root().join("include")),
            ],
        );
        let fortran = build_fortran_hosts(&dir);
        Programs { c, fortran }
    })
}

/// The command that runs a Fortran host: its store configuration (harness/fortran/*.cfg)
/// through JOINTLIN_CONFIG, in a fresh working directory (restart and action files).
fn command(program: PathBuf, fortran: bool, under_valgrind: bool) -> Command {
    let name = program.file_name().unwrap().to_string_lossy().into_owned();
    let mut cmd = if under_valgrind {
        valgrind(&program)
    } else {
        Command::new(&program)
    };
    let kind = if fortran { "fortran" } else { "c" };
    cmd.current_dir(scratch(&format!("{kind}-{name}-{under_valgrind}")));
    if fortran {
        cmd.env(
            "JOINTLIN_CONFIG",
            root().join(format!("harness/fortran/{name}.cfg")),
        );
    }
    cmd
}

fn run_host(fortran: bool, name: &str) -> Vec<Record> {
    let p = programs();
    let dir = if fortran { &p.fortran } else { &p.c };
    parse(&run_ok(&mut command(dir.join(name), fortran, false)).stdout)
}

/// The Rust API's version of block_stick, fed with the slips and the frequency the host
/// printed (so that only the library's numbers are compared, not the hosts' sin/cos).
fn block_stick_reference(host: &[Record]) -> Vec<Record> {
    let mut want = Vec::new();
    let p = KN * H_BLOCK; // linear normal law p = k_N h
    let point = contact(p).point().unwrap().expect("closed contact");
    let mut states = [PointState::virgin(Rule::Thesis, 0.0); 2];
    let mut dissipation = 0.0;
    let td: Vec<_> = host.iter().filter(|r| r.name == "td").collect();
    assert_eq!(td.len(), CYCLES * STEPS, "time-domain increments");
    let dt = 2.0 * PI / (OMEGA * STEPS as f64);
    for (k, r) in td.iter().enumerate() {
        let t = (k + 1) as f64 * dt;
        let s = [r.values[2], r.values[3]];
        // The prescribed loop, to the last bits of the hosts' own sin/cos.
        assert!(
            (s[0] - AMPLITUDE * (OMEGA * t).sin()).abs() < 1e-18,
            "slip 1 {k}"
        );
        assert!((s[1] - 0.5 * AMPLITUDE * (1.0 - (OMEGA * t).cos())).abs() < 1e-18);
        let mut out = vec![(k + 1) as f64, r.values[1], s[0], s[1], p];
        let mut tangents = Vec::new();
        let mut sfd = 0.0;
        for i in 0..2 {
            let (next, step) = point.step(&states[i], s[i]).unwrap();
            states[i] = next;
            out.push(step.force);
            tangents.push(step.tangent);
            sfd += step.dissipated;
        }
        dissipation += sfd;
        out.extend(tangents);
        out.extend([sfd, dissipation]);
        want.push(rec("td", out));
    }
    // Steady state: both points at the store's estimate (the initial amplitude).
    let freqr = host.iter().find(|r| r.name == "ss").unwrap().values[1];
    assert!((freqr - OMEGA / (2.0 * PI)).abs() < 1e-15);
    let omega = 2.0 * PI * freqr; // as jointlin_uinter turns FREQR into omega
    let l = linearize(&contact(p), AMPLITUDE, omega, Method::default()).unwrap();
    assert!(l.k_star > 0.0 && l.k_star < KT0 && l.d_star > 0.0);
    let energy = 0.0 + l.energy_per_cycle + l.energy_per_cycle;
    for (id, structural) in [(1.0, false), (2.0, true)] {
        let (dv, ds) = if structural {
            (0.0, omega * l.d_star)
        } else {
            (l.d_star, 0.0)
        };
        want.push(rec(
            "ss",
            vec![
                id,
                freqr,
                p,
                AMPLITUDE,
                AMPLITUDE,
                l.k_star,
                l.k_star,
                dv,
                dv,
                ds,
                ds,
                KN,
                l.k_star,
                l.k_star,
                l.d_star,
                l.d_star,
                energy,
                energy * freqr,
                id,
            ],
        ));
    }
    // One pass, every point converged (reported = estimate): the final pass is next.
    want.push(rec("ss_action", vec![3.0, 2.0]));
    want
}

fn check_sweep(host: &str, got: &[Record], numbering: KincNumbering) {
    let want = sweep_reference(numbering);
    assert_records(host, got, &want);
    // The multi-pass logic really ran: re-run passes, then the final pass, then done.
    let passes = want.iter().filter(|r| r.name == "stats").count();
    assert!(passes >= 3, "{host}: only {passes} passes");
    let last = want.iter().rev().find(|r| r.name == "next").unwrap();
    assert_eq!(last.values[0], 4.0, "{host}: the iteration ends DONE");
}

#[test]
fn c_block_stick_matches_the_rust_api() {
    let got = run_host(false, "block_stick");
    assert_records("C block_stick", &got, &block_stick_reference(&got));
}

#[test]
fn fortran_block_stick_through_uinter_matches_the_rust_api() {
    let got = run_host(true, "block_stick");
    assert_records("Fortran block_stick", &got, &block_stick_reference(&got));
}

#[test]
fn c_sweep_matches_the_rust_store() {
    let got = run_host(false, "sweep");
    check_sweep("C sweep", &got, KincNumbering::Original);
}

#[test]
fn fortran_sweep_as_separate_jobs_matches_the_rust_store() {
    let got = run_host(true, "sweep");
    check_sweep("Fortran sweep", &got, KincNumbering::Sequential);
}

/// The Abaqus example job's jointlin.cfg (examples/abaqus/block-on-plane, written by
/// `jointlin export`) read by the shim's own parser: the Fortran sweep host, run as
/// separate jobs with it, iterates exactly as with its own configuration (the same start
/// amplitude 1e-4, rtol 1e-6, secant scheme, sweep step 2, sequential numbering; 50
/// passes allowed instead of 30, and it needs fewer; the host's atol). The host reads its action file by
/// name, so the configuration's file names become the host's (sweep.next, sweep.restart).
#[test]
fn fortran_sweep_with_the_exported_abaqus_configuration() {
    let p = programs();
    let mut cmd = command(p.fortran.join("sweep"), true, false);
    let work = scratch("fortran-sweep-exported-cfg");
    let cfg = std::fs::read_to_string(root().join("examples/abaqus/block-on-plane/jointlin.cfg"))
        .unwrap();
    // The host's reference iterates without an absolute tolerance: the exported one
    // (the block's scale) becomes 0.
    let renamed: String = cfg
        .replace("= jointlin.restart", "= sweep.restart")
        .replace("= jointlin.next", "= sweep.next")
        .lines()
        .map(|l| match l.split_once('#') {
            Some((kv, comment)) if kv.trim_start().starts_with("atol") => {
                format!("atol = 0.0   #{comment}\n")
            }
            _ => format!("{l}\n"),
        })
        .collect();
    assert!(renamed.contains("atol = 0.0"), "{renamed}");
    assert_ne!(renamed, cfg, "the exported configuration names its files");
    std::fs::write(work.join("exported.cfg"), renamed).unwrap();
    cmd.current_dir(&work)
        .env("JOINTLIN_CONFIG", work.join("exported.cfg"));
    let got = parse(&run_ok(&mut cmd).stdout);
    check_sweep(
        "Fortran sweep with the exported jointlin.cfg",
        &got,
        KincNumbering::Sequential,
    );
}

/// The Fortran sweep host reporting as an Abaqus job does: it writes each increment's
/// contact output (node header 1504, CDISP 1521 with real and imaginary parts) to the
/// stand-in results file and calls the shim's URDFIL, which reads it through the stand-in
/// POSFIL and DBFILE and reports per node (jointlin_store_report_node). The iteration is
/// the one of direct jl_report calls, record for record, over separate jobs with restarts.
/// A CDISP record of 5 attributes stops the analysis with a message naming it.
#[test]
fn fortran_sweep_reporting_through_urdfil_matches_the_rust_store() {
    let p = programs();
    let mut cmd = command(p.fortran.join("sweep"), true, false);
    cmd.current_dir(scratch("fortran-sweep-urdfil"))
        .arg("urdfil");
    let got = parse(&run_ok(&mut cmd).stdout);
    check_sweep(
        "Fortran sweep through URDFIL",
        &got,
        KincNumbering::Sequential,
    );

    let mut cmd = command(p.fortran.join("sweep"), true, false);
    cmd.current_dir(scratch("fortran-sweep-urdfil-corrupt"))
        .arg("urdfil-corrupt");
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains(
            "STDB_ABQERR -3: jointlin URDFIL: contact output record 1521 (CDISP) of node 1 has 5 attributes"
        ),
        "{err}"
    );
}

#[test]
fn hosts_link_the_shared_library_with_an_rpath() {
    let p = programs();
    for exe in [p.c.join("sweep"), p.fortran.join("sweep")] {
        let out = run_ok(Command::new("readelf").arg("-d").arg(&exe));
        let dynamic = String::from_utf8_lossy(&out.stdout);
        assert!(
            dynamic.contains(&format!("Shared library: [{}]", soname())),
            "{} does not load the library by its SONAME:\n{dynamic}",
            exe.display()
        );
        assert!(
            dynamic.contains(&lib_dir().display().to_string()),
            "{} has no rpath to {}:\n{dynamic}",
            exe.display(),
            lib_dir().display()
        );
    }
}

fn memcheck(fortran: bool, name: &str) {
    if !valgrind_available() {
        tools::missing(&format!("memcheck_{name}"), "valgrind", "not on PATH");
        return;
    }
    let p = programs();
    let dir = if fortran { &p.fortran } else { &p.c };
    let out = run_ok(&mut command(dir.join(name), fortran, true));
    // The run under valgrind prints the same records.
    assert_eq!(
        parse(&out.stdout),
        run_host(fortran, name),
        "{name} under valgrind"
    );
}

#[test]
fn c_block_stick_is_clean_under_valgrind() {
    memcheck(false, "block_stick");
}

#[test]
fn c_sweep_is_clean_under_valgrind() {
    memcheck(false, "sweep");
}

#[test]
fn fortran_block_stick_is_clean_under_valgrind() {
    memcheck(true, "block_stick");
}

#[test]
fn fortran_sweep_is_clean_under_valgrind() {
    memcheck(true, "sweep");
}
