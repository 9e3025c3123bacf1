//! The Abaqus pass drivers users run where Abaqus runs (examples/abaqus/passes.sh and
//! passes.py). Here the `abaqus` they start is harness/fortran/abaqus_job: one Abaqus job
//! of the sweep hosts' two-point model per call, through the shim's UEXTERNALDB, UINTER
//! and URDFIL and the real libjointlin.so, each job a process of its own that knows the
//! earlier passes only through the restart file. Each driver runs the jobs until DONE:
//! as many jobs as the Rust store has passes, the last job's amplitudes those of the Rust
//! store's final pass to 1e-12, sweep.frq restored; a second start refuses the first's
//! restart file (exit 2); a failing job stops the driver (exit 1) with sweep.frq
//! restored.

#[path = "tools/mod.rs"]
mod tools;

mod hosts_common;

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use hosts_common::sweep_model::{sweep_reference, SWEEP_OMEGA};
use hosts_common::*;
use jointlin::store::KincNumbering;

/// harness/fortran/abaqus_job, built once per test binary.
fn abaqus_job() -> &'static PathBuf {
    static P: OnceLock<PathBuf> = OnceLock::new();
    P.get_or_init(|| build_fortran_hosts(&build_dir("drivers")).join("abaqus_job"))
}

/// A job directory as `jointlin export` leaves it for the sweep model: sweep.frq (one
/// `f,` line per frequency, cycles per time), jointlin.cfg (harness/fortran/sweep.cfg's
/// iteration with the exported file names) and the input file.
fn job_dir(name: &str) -> PathBuf {
    let dir = scratch(name);
    let frq: String = SWEEP_OMEGA
        .iter()
        .map(|w| format!("{:?},\n", w / (2.0 * PI)))
        .collect();
    std::fs::write(dir.join("sweep.frq"), frq).unwrap();
    std::fs::write(
        dir.join("jointlin.cfg"),
        "initial_amplitude = 1e-4\nrtol = 1e-6\nscheme = secant\nmax_passes = 30\n\
         sweep_step = 2\nkinc_numbering = sequential\nrestart_file = jointlin.restart\n\
         action_file = jointlin.next\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("model.inp"),
        "** the stand-in job reads sweep.frq only\n",
    )
    .unwrap();
    dir
}

/// The driver `driver` (passes.sh or passes.py) run in `dir` with `abaqus` as its Abaqus.
fn drive(driver: &str, dir: &Path, abaqus: &Path) -> Output {
    let script = root().join("examples/abaqus").join(driver);
    let mut cmd = if driver.ends_with(".py") {
        Command::new("python3")
    } else {
        Command::new("bash")
    };
    cmd.arg(script)
        .arg("model.inp")
        .current_dir(dir)
        .env("ABAQUS", abaqus)
        .env_remove("JOINTLIN_CONFIG")
        .output()
        .unwrap()
}

/// Per sweep increment, the two points' amplitudes of the Rust store's final pass, and
/// the number of passes.
fn reference() -> (Vec<[f64; 2]>, usize) {
    let want = sweep_reference(KincNumbering::Sequential);
    let passes = want.iter().filter(|r| r.name == "stats").count();
    let last = want
        .iter()
        .rev()
        .find(|r| r.name == "stats")
        .unwrap()
        .values[0];
    let amps: Vec<f64> = want
        .iter()
        .filter(|r| r.name == "inc" && r.values[0] == last)
        .map(|r| r.values[6])
        .collect();
    (amps.chunks(2).map(|c| [c[0], c[1]]).collect(), passes)
}

/// The amplitudes of a job's NAME.dat ("increment k frequency f amplitude a1 a2").
fn job_amplitudes(dat: &Path) -> Vec<[f64; 2]> {
    std::fs::read_to_string(dat)
        .unwrap()
        .lines()
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            [w[5].parse().unwrap(), w[6].parse().unwrap()]
        })
        .collect()
}

fn check_driver(driver: &str) {
    let dir = job_dir(driver);
    let before = std::fs::read_to_string(dir.join("sweep.frq")).unwrap();
    let out = drive(driver, &dir, abaqus_job());
    let log = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{driver}: {log}");
    let (want, passes) = reference();
    assert_eq!(passes, 8, "the README's 8 jobs");
    let answer = format!("pass{passes}");
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), answer, "{log}");
    assert!(
        log.contains("RUN_FINAL") && log.contains("next action DONE"),
        "{log}"
    );
    let jobs = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| {
            let n = e.as_ref().unwrap().file_name();
            n.to_string_lossy().ends_with(".dat")
        })
        .count();
    assert_eq!(jobs, passes, "one job per pass");
    let got = job_amplitudes(&dir.join(format!("{answer}.dat")));
    assert_eq!(got.len(), want.len(), "the final job runs every frequency");
    for (g, w) in got.iter().zip(&want) {
        for p in 0..2 {
            assert!(close(g[p], w[p]), "{driver}: {} vs {}", g[p], w[p]);
        }
    }
    assert_eq!(
        std::fs::read_to_string(dir.join("sweep.frq")).unwrap(),
        before
    );
    assert!(!dir.join("frequencies.frq").exists());

    // Started again over the first run's store: refused, nothing run.
    let again = drive(driver, &dir, abaqus_job());
    let log = String::from_utf8_lossy(&again.stderr);
    assert_eq!(again.status.code(), Some(2), "{log}");
    assert!(log.contains("jointlin.restart exists"), "{log}");

    // A job that fails stops the passes; the full sweep is back in sweep.frq.
    let dir = job_dir(&format!("{driver}-failing"));
    let failed = drive(driver, &dir, Path::new("false"));
    let log = String::from_utf8_lossy(&failed.stderr);
    assert_eq!(failed.status.code(), Some(1), "{log}");
    assert!(log.contains("job pass1 failed"), "{log}");
    assert_eq!(
        std::fs::read_to_string(dir.join("sweep.frq")).unwrap(),
        before
    );
    assert!(!dir.join("frequencies.frq").exists());
}

/// SIGTERM to the driver's process group (a batch system's time limit) while a job runs:
/// the driver stops with the full sweep back in sweep.frq.
fn check_terminated(driver: &str) {
    use std::os::unix::process::CommandExt;
    let dir = job_dir(&format!("{driver}-terminated"));
    let before = std::fs::read_to_string(dir.join("sweep.frq")).unwrap();
    let slow = dir.join("slow-abaqus");
    std::fs::write(&slow, "#!/bin/sh\nsleep 30\n").unwrap();
    std::fs::set_permissions(&slow, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    let mut cmd = Command::new(if driver.ends_with(".py") {
        "python3"
    } else {
        "bash"
    });
    let mut child = cmd
        .arg(root().join("examples/abaqus").join(driver))
        .arg("model.inp")
        .current_dir(&dir)
        .env("ABAQUS", &slow)
        .env_remove("JOINTLIN_CONFIG")
        .process_group(0)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while !dir.join("frequencies.frq").exists() {
        assert!(
            started.elapsed().as_secs() < 20,
            "{driver} never started its passes"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let group = format!("-{}", child.id());
    assert!(Command::new("kill")
        .args(["-TERM", "--", &group])
        .status()
        .unwrap()
        .success());
    let status = child.wait().unwrap();
    assert!(!status.success(), "{driver} went on after SIGTERM");
    assert!(
        started.elapsed().as_secs() < 25,
        "{driver} waited for the job to end"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("sweep.frq")).unwrap(),
        before
    );
    assert!(!dir.join("frequencies.frq").exists());
}

#[test]
fn bash_driver_runs_the_passes_to_the_rust_stores_answer() {
    check_driver("passes.sh");
    check_terminated("passes.sh");
}

#[test]
fn python_driver_runs_the_passes_to_the_rust_stores_answer() {
    if Command::new("python3").arg("--version").output().is_err() {
        tools::missing("pass_drivers", "python3", "not found");
        return;
    }
    check_driver("passes.py");
    check_terminated("passes.py");
}
