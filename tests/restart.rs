//! Restart: a multi-pass sweep run as a child process (this test binary
//! re-executed in "host" mode), SIGKILLed after k increments — between increments, or in
//! the middle of one (after its UINTER calls, before LOP 2) — and resumed in a new process
//! from the restart file that jointlin_uexternaldb wrote at LOP 2 (LRESTART = 1): LOP 4,
//! then the rest of the running pass and the remaining passes. Every number the host saw
//! (estimates, k*, d*, computed amplitudes, pass stats, final point states) is bitwise the
//! uninterrupted run's. Also: a corrupt or missing restart file is JOINTLIN_ERR_IO and
//! leaves the store unchanged.
//!
//! The host is the two-point, coupled 2×2 system of tests/ffi_sweep.rs with four
//! frequencies and KINC numbered 1..m in every pass (each pass a new Abaqus job).

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::error::*;
use jointlin::ffi::store::*;
use std::f64::consts::PI;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const FREQS: [f64; 4] = [1.5, 2.2, 3.0, 4.0];
const MASS: f64 = 1.0;
const COUPLING: f64 = 400.0;
const FORCE: f64 = 0.25;
const OVERCLOSURE: [f64; 2] = [2e-4, 1.5e-4];

/// |x| of the 2×2 complex system (tests/ffi_sweep.rs).
fn solve(omega: f64, k: [f64; 2], d: [f64; 2]) -> [f64; 2] {
    type C = (f64, f64);
    let mul = |a: C, b: C| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let div = |a: C, b: C| {
        let n = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / n, (a.1 * b.0 - a.0 * b.1) / n)
    };
    let z11 = (k[0] + COUPLING - MASS * omega * omega, omega * d[0]);
    let z22 = (k[1] + COUPLING - MASS * omega * omega, omega * d[1]);
    let det = {
        let zz = mul(z11, z22);
        (zz.0 - COUPLING * COUPLING, zz.1)
    };
    let x1 = div(mul((FORCE, 0.0), z22), det);
    let x2 = div((COUPLING * FORCE, 0.0), det);
    [x1.0.hypot(x1.1), x2.0.hypot(x2.1)]
}

fn store_at(path: &Path) -> *mut jointlin_store {
    let bytes = path.as_os_str().as_encoded_bytes();
    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = 1e-4;
    cfg.rtol = 1e-7;
    cfg.sweep_step = 2;
    cfg.kinc_numbering = JOINTLIN_KINC_SEQUENTIAL;
    cfg.restart_path = bytes.as_ptr().cast();
    cfg.restart_path_len = bytes.len();
    let mut store = std::ptr::null_mut();
    assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
    store
}

/// Where and how the host stops itself to be killed: after `increments` completed
/// increments (counted over all passes), either right after that LOP 2 or inside the next
/// increment (after its UINTER calls, before its reports and LOP 2).
#[derive(Clone, Copy, Debug)]
struct Stop {
    increments: usize,
    inside_next: bool,
}

/// The host program. Writes to `out` one line per completed increment and per pass, and
/// to `progress` "<completed increments> <pass> <done in pass> <list>" after each LOP 2;
/// at `stop` it writes "STOP" to `progress` and waits to be killed.
struct Host {
    store: *mut jointlin_store,
    points: [Uinter; 2],
    out: std::fs::File,
    progress: std::fs::File,
    completed: usize,
    stop: Option<Stop>,
}

impl Host {
    fn new(store: *mut jointlin_store, out: &Path, progress: &Path, stop: Option<Stop>) -> Self {
        let open = |p: &Path| {
            std::fs::OpenOptions::new()
                .create(true)
                .append(true)
                .open(p)
                .unwrap()
        };
        let points = [0, 1].map(|p| {
            let mut u = Uinter::new(block_props(), 2);
            u.coords = [p as f64, 0.0, 0.0];
            u.area = [1.0, 0.8][p];
            u
        });
        Self {
            store,
            points,
            out: open(out),
            progress: open(progress),
            completed: 0,
            stop,
        }
    }

    /// The static step (general, LINPER = 0): a new job recomputes its base state.
    fn preload(&mut self) {
        for (p, u) in self.points.iter_mut().enumerate() {
            u.statev.fill(0.0);
            u.rdisp = [0.0; 3];
            u.kstep = 1;
            assert_eq!(u.step_to([OVERCLOSURE[p], 0.0, 0.0]), 0);
        }
    }

    fn wait_for_kill(&mut self) -> ! {
        writeln!(self.progress, "STOP").unwrap();
        self.progress.flush().unwrap();
        loop {
            std::thread::sleep(Duration::from_secs(1));
        }
    }

    /// Increments `from..` of a pass over the sweep increments `list` (KINC 1..m).
    fn increments(&mut self, pass: i32, list: &[i32], from: usize) {
        let s = self.store;
        for (i, &sweep) in list.iter().enumerate().skip(from) {
            let kinc = i as i32 + 1;
            let f = FREQS[sweep as usize - 1];
            assert_eq!(uexternaldb(s, 1, 0, 2, kinc), 0);
            let (mut k, mut d, mut ids, mut est) = ([0.0; 2], [0.0; 2], [0; 2], [0.0; 2]);
            for (p, u) in self.points.iter_mut().enumerate() {
                u.linper = 1;
                u.kstep = 2;
                u.kinc = kinc;
                u.freqr = f;
                assert_eq!(u.call(s), 0);
                k[p] = u.ddsddr[3] * u.area;
                d[p] = u.dviscous[3] * u.area;
                ids[p] = u.report.point;
                est[p] = u.report.amplitude[0];
            }
            if let Some(stop) = self.stop {
                if stop.inside_next && self.completed == stop.increments {
                    self.wait_for_kill(); // killed in the middle of an increment
                }
            }
            let x = solve(2.0 * PI * f, k, d);
            for p in 0..2 {
                let amp = [x[p], 0.0];
                assert_eq!(
                    unsafe { jointlin_store_report(s, ids[p], kinc, amp.as_ptr()) },
                    0
                );
                let bits = [est[p], k[p], d[p], x[p]].map(f64::to_bits);
                writeln!(self.out, "inc {pass} {sweep} {p} {bits:?}").unwrap();
            }
            assert_eq!(uexternaldb(s, 2, 1, 2, kinc), 0); // restart data written
            self.out.flush().unwrap();
            self.completed += 1;
            writeln!(
                self.progress,
                "{} {pass} {} {list:?}",
                self.completed,
                i + 1
            )
            .unwrap();
            self.progress.flush().unwrap();
            if let Some(stop) = self.stop {
                if !stop.inside_next && self.completed == stop.increments {
                    self.wait_for_kill();
                }
            }
        }
        assert_eq!(uexternaldb(s, 6, 0, 2, 0), 0);
        assert_eq!(uexternaldb(s, 3, 0, 2, 0), 0);
        let mut st = jointlin_pass_stats::default();
        assert_eq!(unsafe { jointlin_store_pass_stats(s, pass, &mut st) }, 0);
        writeln!(self.out, "stats {st:?}").unwrap();
    }

    /// Runs analyses (jobs) until the store is done.
    fn run_jobs(&mut self) {
        for _ in 0..30 {
            let (action, pass) = next_action(self.store);
            let list = match action {
                JOINTLIN_ACTION_RUN_SWEEP => vec![1, 2, 3, 4],
                JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL => increments(self.store),
                JOINTLIN_ACTION_DONE => return self.finish(),
                other => panic!("action {other}"),
            };
            assert_eq!(uexternaldb(self.store, 0, 0, 0, 0), 0);
            self.preload();
            assert_eq!(uexternaldb(self.store, 5, 0, 2, 0), 0);
            self.increments(pass, &list, 0);
        }
        panic!("no convergence in 30 passes");
    }

    fn finish(&mut self) {
        for id in 1..=2 {
            for kinc in 1..=4 {
                let mut st = jointlin_point_status::default();
                assert_eq!(
                    unsafe { jointlin_store_point_status(self.store, id, kinc, &mut st) },
                    0
                );
                let bits = [st.estimate[0], st.computed[0]].map(f64::to_bits);
                writeln!(
                    self.out,
                    "final {id} {kinc} {bits:?} {} {}",
                    st.converged, st.passes
                )
                .unwrap();
            }
        }
        writeln!(self.out, "done").unwrap();
        self.out.flush().unwrap();
    }
}

/// Host mode: the host process the tests start by re-executing this test binary with
/// JOINTLIN_RESTART_HOST set (ignored in a test run: it is no test of its own).
#[test]
#[ignore = "the host process of the restart tests, run by them with JOINTLIN_RESTART_HOST"]
fn host_process() {
    let Ok(mode) = std::env::var("JOINTLIN_RESTART_HOST") else {
        eprintln!("host_process: not a test; the restart tests run it as their host");
        return;
    };
    let dir = PathBuf::from(std::env::var("JOINTLIN_RESTART_DIR").unwrap());
    let stop = std::env::var("JOINTLIN_RESTART_STOP").ok().map(|s| {
        let (n, inside) = s.split_once(',').unwrap();
        Stop {
            increments: n.parse().unwrap(),
            inside_next: inside == "inside",
        }
    });
    let store = store_at(&dir.join("store.restart"));
    let mut host = Host::new(store, &dir.join("out.txt"), &dir.join("progress.txt"), stop);
    if mode == "resume" {
        // A restart analysis: LOP 4 restores the store; Abaqus continues the step after
        // the last increment that wrote restart data (our host's own restart data is the
        // progress line of that increment: pass, increments done, the pass's list).
        let last = std::fs::read_to_string(dir.join("progress.txt")).unwrap();
        let line = last
            .lines()
            .rev()
            .find(|l| !l.starts_with("STOP"))
            .expect("a completed increment");
        let mut it = line.splitn(4, ' ');
        let _completed: usize = it.next().unwrap().parse().unwrap();
        let pass: i32 = it.next().unwrap().parse().unwrap();
        let done: usize = it.next().unwrap().parse().unwrap();
        let list: Vec<i32> = it
            .next()
            .unwrap()
            .trim_matches(|c| c == '[' || c == ']')
            .split(", ")
            .map(|k| k.parse().unwrap())
            .collect();
        assert_eq!(uexternaldb(store, 4, 0, 2, 0), JOINTLIN_OK);
        host.preload(); // STATEV as Abaqus's restart would restore them
        host.increments(pass, &list, done);
    }
    host.run_jobs();
    unsafe { jointlin_store_free(store) };
}

fn host_command(dir: &Path, mode: &str, stop: Option<Stop>) -> Command {
    let mut cmd = Command::new(std::env::current_exe().unwrap());
    cmd.args([
        "--exact",
        "host_process",
        "--ignored",
        "--nocapture",
        "--test-threads",
        "1",
    ])
    .env("JOINTLIN_RESTART_HOST", mode)
    .env("JOINTLIN_RESTART_DIR", dir)
    .stdout(Stdio::null())
    .stderr(Stdio::piped());
    if let Some(s) = stop {
        let how = if s.inside_next { "inside" } else { "after" };
        cmd.env("JOINTLIN_RESTART_STOP", format!("{},{how}", s.increments));
    }
    cmd
}

fn fresh_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-restart-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs the host to the end in one process; returns its output.
fn uninterrupted() -> String {
    let dir = fresh_dir("whole");
    let out = host_command(&dir, "run", None).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("out.txt")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    text
}

/// Runs the host until it stops at `stop`, SIGKILLs it, resumes in a new process.
fn killed_and_resumed(stop: Stop) -> String {
    use std::os::unix::process::ExitStatusExt;
    let dir = fresh_dir(&format!("{}-{}", stop.increments, stop.inside_next));
    let mut child = host_command(&dir, "run", Some(stop)).spawn().unwrap();
    let start = Instant::now();
    loop {
        let p = std::fs::read_to_string(dir.join("progress.txt")).unwrap_or_default();
        if p.lines().any(|l| l == "STOP") {
            break;
        }
        if let Some(status) = child.try_wait().unwrap() {
            panic!("host ended before its stop {stop:?}: {status}");
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "host never reached {stop:?}"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap(); // SIGKILL: no destructor, no flush, no LOP 3
    let status = child.wait().unwrap();
    assert_eq!(status.signal(), Some(9), "{status}");
    let out = host_command(&dir, "resume", None).output().unwrap();
    assert!(
        out.status.success(),
        "resume: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("out.txt")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    text
}

#[test]
fn a_sweep_killed_midway_resumes_to_the_same_result_bitwise() {
    let whole = uninterrupted();
    let incs = whole.lines().filter(|l| l.starts_with("inc ")).count() / 2;
    let passes = whole.lines().filter(|l| l.starts_with("stats ")).count();
    assert!(passes >= 3, "pass 1, a re-run and the final:\n{whole}");
    assert!(whole.ends_with("done\n"));
    eprintln!("uninterrupted: {incs} increments in {passes} passes");
    // Kill points: in pass 1 between and inside increments, at a pass boundary (after the
    // last increment of pass 1, before LOP 3), and in later passes.
    let stops = [
        Stop {
            increments: 1,
            inside_next: false,
        },
        Stop {
            increments: 2,
            inside_next: true,
        },
        Stop {
            increments: 4,
            inside_next: false,
        },
        Stop {
            increments: 5,
            inside_next: true,
        },
        Stop {
            increments: incs - 1,
            inside_next: false,
        },
    ];
    for stop in stops {
        let resumed = killed_and_resumed(stop);
        assert_eq!(resumed, whole, "killed at {stop:?}");
    }
}

#[test]
fn a_corrupt_or_missing_restart_file_is_an_io_error_and_changes_nothing() {
    let dir = fresh_dir("corrupt");
    let path = dir.join("store.restart");
    let store = store_at(&path);
    // Missing file.
    assert_eq!(unsafe { jointlin_store_restore(store) }, JOINTLIN_ERR_IO);
    assert_eq!(uexternaldb(store, 4, 0, 2, 0), JOINTLIN_ERR_IO);
    // A real file from one increment, then truncated and garbled copies of it.
    assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
    assert_eq!(uexternaldb(store, 1, 0, 2, 1), 0);
    let mut u = Uinter::new(block_props(), 3);
    u.stress[0] = 2.0;
    u.linper = 1;
    u.kstep = 2;
    assert_eq!(u.call(store), 0);
    let amp = [2e-4, 1e-4];
    assert_eq!(
        unsafe { jointlin_store_report(store, u.report.point, 1, amp.as_ptr()) },
        0
    );
    assert_eq!(uexternaldb(store, 2, 1, 2, 1), 0);
    let good = std::fs::read_to_string(&path).unwrap();
    let mut status_before = jointlin_point_status::default();
    assert_eq!(
        unsafe { jointlin_store_point_status(store, 1, 1, &mut status_before) },
        0
    );
    // (Every prefix short of the final "end" token; the last byte is only a newline.)
    let mut bad: Vec<String> = (0..good.len() - 1)
        .step_by(7)
        .map(|n| good[..n].to_string())
        .collect();
    bad.push(good.replace("jointlin-store 4", "jointlin-store 5"));
    bad.push(good.replace("records 1", "records 5"));
    bad.push(good.replace("phase 1", "phase 7"));
    bad.push("garbage".into());
    for text in &bad {
        std::fs::write(&path, text).unwrap();
        assert_eq!(
            unsafe { jointlin_store_restore(store) },
            JOINTLIN_ERR_IO,
            "{text:?}"
        );
        let mut st = jointlin_point_status::default();
        assert_eq!(
            unsafe { jointlin_store_point_status(store, 1, 1, &mut st) },
            0
        );
        assert_eq!(st, status_before);
    }
    // The good file restores.
    std::fs::write(&path, &good).unwrap();
    assert_eq!(uexternaldb(store, 4, 0, 2, 0), JOINTLIN_OK);
    unsafe { jointlin_store_free(store) };
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Restart files that parse but contradict themselves (a running pass with no pass
/// statistics; 4294967295 iteration passes) are JOINTLIN_ERR_IO at restore, never a panic
/// at a later LOP (they used to poison the store).
#[test]
fn an_inconsistent_restart_file_is_an_io_error() {
    let dir = fresh_dir("inconsistent");
    let path = dir.join("store.restart");
    for text in [
        "jointlin-store 1\nnext 0 0\nphase 1 1 0 0 0\ncounters 0 0\nstats 0\nincrements 0\npoints 0\nrecords 0\nend\n",
        "jointlin-store 1\nnext 0 0\nphase 1 1 0 0 0\ncounters 4294967295 0\nstats 1\n1 0 0 0 0 0\nincrements 1 1 0\npoints 0\nrecords 0\nend\n",
    ] {
        let store = store_at(&path);
        std::fs::write(&path, text).unwrap();
        let restored = unsafe { jointlin_store_restore(store) };
        if restored == JOINTLIN_OK {
            // If accepted, the sequence must still never panic.
            for (lop, kinc) in [(1, 1), (2, 1), (3, 0)] {
                assert_ne!(uexternaldb(store, lop, 0, 2, kinc), JOINTLIN_ERR_PANIC, "{text}");
            }
        }
        assert_eq!(restored, JOINTLIN_ERR_IO, "{text}");
        unsafe { jointlin_store_free(store) };
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
