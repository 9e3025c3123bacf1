//! The Fortran MPI host (harness/fortran/sweep_mpi.f90: the chain of tests/chain_common as
//! a domain-decomposed job, 8 contact points, 5 frequencies, every pass a separate job)
//! built with OpenMPI's mpif90 against the real libjointlin.so and the Abaqus-signature
//! shim, run with mpirun on 1, 2 and 4 ranks:
//!
//! * shim built MPI=yes: the ranks agree through the communicator (GETCOMMUNICATOR);
//!   every estimate, k*, d*, amplitude (all 17 digits), every pass and re-run list of every
//!   rank equals the serial run's (1 rank), which equals the C-API run of
//!   tests/chain_common to 1e-12 with the same passes; in some pass the ranks' own
//!   decisions differed, so the agreement was needed;
//! * shim built MPI=no: the same through the file protocol (jointlin_store_agree_files);
//! * a rank SIGKILLed after an increment's restart data (LOP 2, LRESTART = 1) ends the job;
//!   a restart job (LOP 4 on every rank, each from its own restart file chain.restart.r<rank>)
//!   finishes it, and the records of both jobs together equal the uninterrupted run's.
//!
//! Skipped, with the reason printed, only where mpif90 or mpirun is missing
//! (scripts/deps.sh installs openmpi-bin and libopenmpi-dev).

#[path = "tools/mod.rs"]
mod tools;

mod chain_common;
mod ffi_common;
mod hosts_common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use hosts_common::{build_dir, lib_dir, root, scratch};
use jointlin::ffi::store::JOINTLIN_ACTION_DONE;

/// Why the MPI tests cannot run here, if they cannot.
fn missing_mpi() -> Option<String> {
    for tool in ["mpif90", "mpirun"] {
        let ok = Command::new(tool)
            .arg("--version")
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false);
        if !ok {
            return Some(format!(
                "{tool} not found (Debian: openmpi-bin, libopenmpi-dev; scripts/deps.sh)"
            ));
        }
    }
    None
}

macro_rules! require_mpi {
    () => {
        if let Some(why) = missing_mpi() {
            tools::missing("hosts_mpi", "MPI", &why);
            return;
        }
    };
}

struct Hosts {
    /// Agreement through the communicator (shim MPI=yes).
    comm: PathBuf,
    /// Agreement through files (shim MPI=no, the host itself still uses MPI).
    files: PathBuf,
}

fn hosts() -> &'static Hosts {
    static H: OnceLock<Hosts> = OnceLock::new();
    H.get_or_init(|| {
        let dir = build_dir("mpi");
        let lib = lib_dir();
        let mut out = Vec::new();
        for mpi in ["yes", "no"] {
            let shim = dir.join(format!("shim-mpi-{mpi}"));
            let mut cmd = Command::new("make");
            cmd.arg("-s")
                .arg("-f")
                .arg(root().join("fortran-shim/Makefile"))
                .arg(format!("BUILD={}", shim.display()))
                .arg(format!("JOINTLIN_LIBDIR={}", lib.display()))
                .arg(format!("MPI={mpi}"))
                .arg("FC=mpif90")
                .arg("all")
                .arg(shim.join("abaqus_standin_mpi.o"));
            hosts_common::run_ok(&mut cmd);
            let host = dir.join(format!("host-mpi-{mpi}"));
            hosts_common::run_ok(
                Command::new("make")
                    .arg("-s")
                    .arg("-f")
                    .arg(root().join("harness/fortran/Makefile"))
                    .arg(format!("BUILD={}", host.display()))
                    .arg(format!("SHIM={}", shim.display()))
                    .arg(format!("JOINTLIN_LIBDIR={}", lib.display()))
                    .arg(host.join("sweep_mpi")),
            );
            out.push(host.join("sweep_mpi"));
        }
        Hosts {
            comm: out[0].clone(),
            files: out[1].clone(),
        }
    })
}

/// One mpirun of `program` on `ranks` ranks in `dir`; returns whether it succeeded and its
/// output. Killed after 10 minutes (a hang is a failure, not a stuck test run).
fn mpirun(program: &Path, ranks: usize, dir: &Path, env: &[(&str, String)]) -> (bool, String) {
    let version = Command::new("mpirun").arg("--version").output().unwrap();
    let mut cmd = Command::new("mpirun");
    if String::from_utf8_lossy(&version.stdout).contains("Open MPI") {
        cmd.args(["--oversubscribe", "--allow-run-as-root"]);
    }
    cmd.arg("-np")
        .arg(ranks.to_string())
        .arg(program)
        .current_dir(dir)
        .env(
            "JOINTLIN_CONFIG",
            root().join("harness/fortran/sweep_mpi.cfg"),
        )
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    for (k, v) in env {
        cmd.env(k, v);
    }
    let child = cmd.spawn().expect("mpirun");
    let pid = child.id();
    let done = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let watchdog = {
        let done = done.clone();
        std::thread::spawn(move || {
            let start = Instant::now();
            while !done.load(std::sync::atomic::Ordering::Relaxed) {
                if start.elapsed() > Duration::from_secs(600) {
                    let _ = Command::new("kill").arg("-9").arg(pid.to_string()).status();
                    return;
                }
                std::thread::sleep(Duration::from_millis(200));
            }
        })
    };
    let out = child.wait_with_output().unwrap();
    done.store(true, std::sync::atomic::Ordering::Relaxed);
    watchdog.join().unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

/// The records of all ranks of a run directory.
#[derive(Debug, Default)]
struct Records {
    /// (pass, sweep increment, point 1-based) -> estimate, k*, d*, amplitude.
    incs: BTreeMap<(i32, i32, usize), [f64; 4]>,
    /// Per rank: (action, pass, increments) after each pass.
    next: Vec<Vec<(i32, i32, Vec<i32>)>>,
    /// (pass, rank) -> this rank's own re-run flags before the agreement.
    local: BTreeMap<(i32, usize), Vec<i32>>,
}

fn records(dir: &Path, ranks: usize) -> Records {
    let mut r = Records::default();
    for rank in 0..ranks {
        let text = std::fs::read_to_string(dir.join(format!("records.r{rank}"))).unwrap();
        let mut next = Vec::new();
        for line in text.lines() {
            let w: Vec<&str> = line.split_whitespace().collect();
            let int = |i: usize| w[i].parse::<i32>().unwrap();
            match w[0] {
                "inc" => {
                    let v = [4, 5, 6, 7].map(|i| w[i].parse::<f64>().unwrap());
                    let key = (int(1), int(2), int(3) as usize);
                    // A point's record appears once (a restarted pass does not repeat it).
                    assert!(r.incs.insert(key, v).is_none(), "{key:?} twice");
                }
                "next" => next.push((int(1), int(2), (4..w.len()).map(int).collect())),
                "local" => {
                    r.local
                        .insert((int(1), int(2) as usize), (3..w.len()).map(int).collect());
                }
                other => panic!("unknown record {other}"),
            }
        }
        r.next.push(next);
    }
    r
}

fn run_dir(name: &str) -> PathBuf {
    scratch(&format!("mpi-{name}"))
}

/// Runs `program` on `ranks` ranks to the end; its records.
fn run(program: &Path, ranks: usize, name: &str) -> (PathBuf, Records) {
    let dir = run_dir(name);
    let (ok, out) = mpirun(program, ranks, &dir, &[]);
    assert!(ok, "{name}: mpirun failed:\n{out}");
    for rank in 0..ranks {
        let restart = if ranks == 1 {
            "chain.restart".to_string()
        } else {
            format!("chain.restart.r{rank}")
        };
        assert!(dir.join(&restart).is_file(), "{name}: no {restart}");
    }
    let action = std::fs::read_to_string(dir.join("chain.next")).unwrap();
    assert!(action.starts_with("action DONE\n"), "{name}: {action}");
    let recs = records(&dir, ranks);
    (dir, recs)
}

/// Every evaluation bitwise, every rank's next actions equal to the serial run's.
fn assert_same(serial: &Records, got: &Records, what: &str) {
    assert_eq!(
        serial.incs.keys().collect::<Vec<_>>(),
        got.incs.keys().collect::<Vec<_>>(),
        "{what}: evaluations"
    );
    for (key, v) in &serial.incs {
        let g = got.incs[key];
        assert_eq!(
            v.map(f64::to_bits),
            g.map(f64::to_bits),
            "{what}: {key:?}: serial {v:?}, got {g:?}"
        );
    }
    for (rank, next) in got.next.iter().enumerate() {
        assert_eq!(next, &serial.next[0], "{what}: rank {rank}'s actions");
    }
}

fn serial() -> &'static Records {
    static S: OnceLock<Records> = OnceLock::new();
    S.get_or_init(|| run(&hosts().comm, 1, "serial").1)
}

#[test]
fn serial_mpi_host_equals_the_c_api_chain() {
    require_mpi!();
    let s = serial();
    let reference = chain_common::run_job(1, chain_common::Agreement::Max, None);
    let passes: Vec<(i32, i32, Vec<i32>)> = reference.actions[0][1..].to_vec();
    assert_eq!(s.next[0], passes, "the same passes and re-run lists");
    assert_eq!(s.next[0].last().unwrap().0, JOINTLIN_ACTION_DONE);
    assert_eq!(s.incs.len(), reference.incs.len());
    for ((pass, sweep, j), bits) in &reference.incs {
        let want = bits.map(f64::from_bits);
        let got = s.incs[&(*pass, *sweep, j + 1)];
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() <= 1e-12 * w.abs(),
                "pass {pass} increment {sweep} point {j}: Fortran {got:?}, C API {want:?}"
            );
        }
    }
    println!(
        "serial MPI host: {} passes, {} point evaluations",
        s.next[0].len(),
        s.incs.len()
    );
}

#[test]
fn two_and_four_ranks_agreeing_through_the_communicator_equal_the_serial_run() {
    require_mpi!();
    let mut disagreed = false;
    for ranks in [2, 4] {
        let (dir, got) = run(&hosts().comm, ranks, &format!("comm-{ranks}"));
        assert_same(serial(), &got, &format!("{ranks} ranks, communicator"));
        // The communicator, not the file protocol, carried the agreement.
        let files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(".pass"))
            .collect();
        assert!(files.is_empty(), "pass files with MPI=yes: {files:?}");
        for pass in 1..=serial().next[0].len() as i32 {
            let flags: Vec<&Vec<i32>> = (0..ranks).map(|r| &got.local[&(pass, r)]).collect();
            disagreed |= flags.windows(2).any(|w| w[0] != w[1]);
        }
    }
    assert!(
        disagreed,
        "the ranks never decided differently on their own"
    );
}

#[test]
fn two_and_four_ranks_agreeing_through_files_equal_the_serial_run() {
    require_mpi!();
    for ranks in [2, 4] {
        let (dir, got) = run(&hosts().files, ranks, &format!("files-{ranks}"));
        assert_same(serial(), &got, &format!("{ranks} ranks, files"));
        // The last pass's files stay, one per rank; earlier ones were deleted.
        let last = serial().next[0].last().unwrap().1;
        for r in 0..ranks {
            assert!(dir.join(format!("chain.restart.r{r}.pass{last}")).is_file());
            assert!(!dir
                .join(format!("chain.restart.r{r}.pass{}", last - 1))
                .exists());
        }
    }
}

#[test]
fn a_killed_rank_restarts_from_its_restart_file_and_the_job_resumes() {
    require_mpi!();
    // A re-run pass with at least two increments: killed after its first.
    let (pass, list) = serial().next[0]
        .iter()
        .find(|(_, p, l)| *p > 1 && l.len() >= 2)
        .map(|(_, p, l)| (*p, l.clone()))
        .expect("a re-run pass of two increments");
    for (ranks, victim, done) in [(2, 1, 1), (4, 2, list.len() - 1)] {
        let what = format!("{ranks} ranks, rank {victim} killed in pass {pass} after {done}");
        let dir = run_dir(&format!("kill-{ranks}"));
        let stop = format!("{pass} {done} {victim}");
        let (ok, out) = mpirun(&hosts().comm, ranks, &dir, &[("JL_KILL", stop)]);
        assert!(!ok, "{what}: the job did not die:\n{out}");
        let (ok, out) = mpirun(
            &hosts().comm,
            ranks,
            &dir,
            &[("JL_RESUME", format!("{pass} {done}"))],
        );
        assert!(ok, "{what}: the restart job failed:\n{out}");
        assert_same(serial(), &records(&dir, ranks), &what);
    }
}
