//! The chain model of tests/ranks.rs and tests/hosts_mpi.rs, run through the C API with
//! threads standing in for the ranks of a domain-decomposed FE job: 8 contact points (each
//! a unit mass on its joint to ground, neighbours coupled by springs of 400, the first one
//! forced with 0.25) swept over 5 frequencies, iterated over passes by ranked stores. Ranks
//! own contiguous blocks of points; per increment they exchange k*, d* (as an FE job's
//! distributed solve does), every rank solves the same chain and reports its own points'
//! amplitudes; at the end of a pass they agree on the re-run list by the element-wise
//! maximum of their summaries (what a host does with MPI_Allreduce) or through the file
//! protocol. harness/fortran/sweep_mpi.f90 is the same job as a Fortran MPI host.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;

use crate::ffi_common::*;
use jointlin::ffi::error::*;
use jointlin::ffi::store::*;
use jointlin::ffi::store_ranks::*;

pub const POINTS: usize = 8;
pub const FREQS: [f64; 5] = [1.5, 2.2, 3.0, 4.0, 5.0];
const MASS: f64 = 1.0;
const COUPLING: f64 = 400.0;
const FORCE: f64 = 0.25;

/// Overclosure of point j (so the points differ in pressure and slip limit).
pub fn overclosure(j: usize) -> f64 {
    2e-4 * (1.0 + 0.1 * j as f64)
}

type C = (f64, f64);
fn mul(a: C, b: C) -> C {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}
fn div(a: C, b: C) -> C {
    let n = b.0 * b.0 + b.1 * b.1;
    ((a.0 * b.0 + a.1 * b.1) / n, (a.1 * b.0 - a.0 * b.1) / n)
}
fn sub(a: C, b: C) -> C {
    (a.0 - b.0, a.1 - b.1)
}

/// |x_j| of the chain at angular frequency `omega` (tridiagonal, Thomas algorithm).
pub fn solve(omega: f64, k: &[f64], d: &[f64]) -> Vec<f64> {
    let n = k.len();
    let diag = |j: usize| {
        let springs = if j == 0 || j == n - 1 { 1.0 } else { 2.0 };
        (
            k[j] + springs * COUPLING - MASS * omega * omega,
            omega * d[j],
        )
    };
    let off = (-COUPLING, 0.0);
    let mut c = vec![(0.0, 0.0); n];
    let mut r = vec![(0.0, 0.0); n];
    let mut b = diag(0);
    c[0] = div(off, b);
    r[0] = div((FORCE, 0.0), b);
    for j in 1..n {
        b = sub(diag(j), mul(off, c[j - 1]));
        c[j] = div(off, b);
        r[j] = div(sub((0.0, 0.0), mul(off, r[j - 1])), b);
    }
    for j in (0..n - 1).rev() {
        r[j] = sub(r[j], mul(c[j], r[j + 1]));
    }
    r.iter().map(|x| x.0.hypot(x.1)).collect()
}

/// How the ranks agree at the end of a pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Agreement {
    /// Element-wise maximum of the summaries, exchanged in memory (as MPI_Allreduce).
    Max,
    /// jointlin_store_agree_files.
    Files,
}

/// Where the ranks stop, as if killed, to be restored from their restart files: in pass
/// `pass` after `done` increments of it.
#[derive(Clone, Copy, Debug)]
pub struct Kill {
    pub pass: i32,
    pub done: usize,
}

/// What a run shows: per (pass, sweep increment, point) the bits of estimate, k*, d*,
/// amplitude; per rank the sequence of (action, pass, list); the ranks' own re-run flags
/// per pass.
#[derive(Debug, Default, PartialEq)]
pub struct Run {
    pub incs: Vec<((i32, i32, usize), [u64; 4])>,
    pub actions: Vec<Vec<(i32, i32, Vec<i32>)>>,
    pub local: Vec<(i32, usize, Vec<i32>)>,
}

fn store_for(dir: &Path, rank: usize, ranks: usize) -> *mut jointlin_store {
    let path = dir.join("chain.restart");
    let bytes = path.as_os_str().as_encoded_bytes();
    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = 1e-4;
    cfg.rtol = 1e-6;
    cfg.sweep_step = 2;
    cfg.kinc_numbering = JOINTLIN_KINC_SEQUENTIAL;
    cfg.restart_path = bytes.as_ptr().cast();
    cfg.restart_path_len = bytes.len();
    let mut store = std::ptr::null_mut();
    assert_eq!(
        unsafe { jointlin_store_new_ranked(&cfg, rank as i32, ranks as i32, &mut store) },
        JOINTLIN_OK
    );
    store
}

/// A barrier for the ranks that a panicking rank breaks: the others then panic too instead
/// of waiting forever (a failed assertion in one rank must fail the test, not hang it), and
/// a rank that waits longer than `LIMIT` panics with the barrier's state.
struct RankBarrier {
    ranks: usize,
    state: Mutex<(usize, u64, bool)>, // (arrived, generation, broken)
    turn: Condvar,
}

impl RankBarrier {
    const LIMIT: Duration = Duration::from_secs(120);

    fn new(ranks: usize) -> Self {
        RankBarrier {
            ranks,
            state: Mutex::new((0, 0, false)),
            turn: Condvar::new(),
        }
    }

    fn wait(&self) {
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        assert!(!s.2, "another rank panicked");
        let generation = s.1;
        s.0 += 1;
        if s.0 == self.ranks {
            s.0 = 0;
            s.1 += 1;
            self.turn.notify_all();
            return;
        }
        while s.1 == generation && !s.2 {
            let (next, timeout) = self
                .turn
                .wait_timeout(s, Self::LIMIT)
                .unwrap_or_else(|e| e.into_inner());
            s = next;
            assert!(
                !timeout.timed_out(),
                "rank barrier: {} of {} ranks arrived within {:?}",
                s.0,
                self.ranks,
                Self::LIMIT
            );
        }
        assert!(!s.2, "another rank panicked");
    }

    fn break_it(&self) {
        self.state.lock().unwrap_or_else(|e| e.into_inner()).2 = true;
        self.turn.notify_all();
    }
}

/// Breaks the barrier when its rank unwinds.
struct BreakOnPanic<'a>(&'a RankBarrier);

impl Drop for BreakOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.break_it();
        }
    }
}

/// The shared memory of the ranks: k*, d* per point, summaries, a barrier.
struct Exchange {
    barrier: RankBarrier,
    k: Mutex<Vec<f64>>,
    d: Mutex<Vec<f64>>,
    summaries: Mutex<Vec<Vec<i32>>>,
}

fn block(rank: usize, ranks: usize) -> std::ops::Range<usize> {
    rank * POINTS / ranks..(rank + 1) * POINTS / ranks
}

fn summary(store: *const jointlin_store) -> Vec<i32> {
    let mut len = 0usize;
    assert_eq!(
        unsafe { jointlin_store_pass_summary(store, std::ptr::null_mut(), 0, &mut len) },
        JOINTLIN_ERR_SIZE
    );
    let mut buf = vec![0i32; len];
    assert_eq!(
        unsafe { jointlin_store_pass_summary(store, buf.as_mut_ptr(), len, &mut len) },
        JOINTLIN_OK
    );
    buf
}

/// Rank `rank` of `ranks`: runs passes until its store is done. Returns its records.
fn rank_main(
    rank: usize,
    ranks: usize,
    dir: &Path,
    agreement: Agreement,
    kill: Option<Kill>,
    ex: &Exchange,
) -> Run {
    let _guard = BreakOnPanic(&ex.barrier);
    let mine = block(rank, ranks);
    let mut points: Vec<Uinter> = mine
        .clone()
        .map(|j| {
            let mut u = Uinter::new(block_props(), 2);
            u.coords = [j as f64, 0.0, 0.0];
            u
        })
        .collect();
    let mut store = store_for(dir, rank, ranks);
    let mut run = Run {
        actions: vec![Vec::new()],
        ..Run::default()
    };
    let mut killed = false;
    loop {
        let (action, pass) = next_action(store);
        let list = match action {
            JOINTLIN_ACTION_RUN_SWEEP => (1..=FREQS.len() as i32).collect(),
            JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL => increments(store),
            _ => {
                run.actions[0].push((action, pass, increments(store)));
                break;
            }
        };
        run.actions[0].push((action, pass, list.clone()));
        // One analysis job: LOP 0, the static preload step, the sweep step.
        assert_eq!(uexternaldb(store, 0, 0, 0, 0), 0);
        let preload = |points: &mut Vec<Uinter>| {
            for (u, j) in points.iter_mut().zip(mine.clone()) {
                u.statev.fill(0.0);
                u.rdisp = [0.0; 3];
                u.kstep = 1;
                assert_eq!(u.step_to([overclosure(j), 0.0, 0.0]), 0);
            }
        };
        preload(&mut points);
        assert_eq!(uexternaldb(store, 5, 0, 2, 0), 0);
        let mut i = 0;
        while i < list.len() {
            let kinc = i as i32 + 1;
            let sweep = list[i];
            let f = FREQS[sweep as usize - 1];
            assert_eq!(uexternaldb(store, 1, 0, 2, kinc), 0);
            let mut est = Vec::new();
            for (u, j) in points.iter_mut().zip(mine.clone()) {
                u.linper = 1;
                u.kstep = 2;
                u.kinc = kinc;
                u.freqr = f;
                assert_eq!(u.call(store), 0);
                ex.k.lock().unwrap()[j] = u.ddsddr[3];
                ex.d.lock().unwrap()[j] = u.dviscous[3];
                est.push(u.report.amplitude[0]);
            }
            ex.barrier.wait(); // every rank's k*, d* are in
            let x = {
                let (k, d) = (ex.k.lock().unwrap().clone(), ex.d.lock().unwrap().clone());
                solve(2.0 * std::f64::consts::PI * f, &k, &d)
            };
            ex.barrier.wait(); // every rank has read them
            for ((u, j), e) in points.iter().zip(mine.clone()).zip(&est) {
                let amp = [x[j], 0.0];
                let id = u.report.point;
                assert_eq!(
                    unsafe { jointlin_store_report(store, id, kinc, amp.as_ptr()) },
                    0
                );
                let bits = [*e, u.ddsddr[3], u.dviscous[3], x[j]].map(f64::to_bits);
                run.incs.push(((pass, sweep, j), bits));
            }
            assert_eq!(uexternaldb(store, 2, 1, 2, kinc), 0); // restart data written
            i += 1;
            if let Some(k) = kill.filter(|k| !killed && k.pass == pass && k.done == i) {
                // Every rank "dies" after the same increment (an FE job writes its restart
                // data collectively) and a new job restarts from the files: LOP 4.
                let _ = k;
                killed = true;
                ex.barrier.wait();
                unsafe { jointlin_store_free(store) };
                store = store_for(dir, rank, ranks);
                assert_eq!(uexternaldb(store, 4, 0, 2, 0), 0);
                preload(&mut points);
            }
        }
        assert_eq!(uexternaldb(store, 6, 0, 2, 0), 0);
        let own = summary(store);
        let n = (own.len() - 4) / 3;
        run.local.push((pass, rank, own[4 + 2 * n..].to_vec()));
        match agreement {
            Agreement::Max => {
                ex.summaries.lock().unwrap().push(own);
                ex.barrier.wait();
                let mut reduced = ex.summaries.lock().unwrap()[0].clone();
                for s in ex.summaries.lock().unwrap().iter() {
                    for (a, b) in reduced.iter_mut().zip(s) {
                        *a = (*a).max(*b);
                    }
                }
                ex.barrier.wait();
                ex.summaries.lock().unwrap().clear();
                assert_eq!(
                    unsafe { jointlin_store_pass_agree(store, reduced.as_ptr(), reduced.len()) },
                    JOINTLIN_OK
                );
            }
            Agreement::Files => assert_eq!(
                unsafe { jointlin_store_agree_files(store, rank as i32, ranks as i32, 60.0) },
                JOINTLIN_OK
            ),
        }
        assert_eq!(uexternaldb(store, 3, 0, 0, 0), 0);
    }
    unsafe { jointlin_store_free(store) };
    run
}

/// All ranks of one job; their records merged (sorted by pass, increment, point).
pub fn run_job(ranks: usize, agreement: Agreement, kill: Option<Kill>) -> Run {
    let dir = scratch(&format!("ranks-{ranks}-{agreement:?}-{}", kill.is_some()));
    let ex = Exchange {
        barrier: RankBarrier::new(ranks),
        k: Mutex::new(vec![0.0; POINTS]),
        d: Mutex::new(vec![0.0; POINTS]),
        summaries: Mutex::new(Vec::new()),
    };
    let runs: Vec<Run> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..ranks)
            .map(|r| {
                let (dir, ex) = (&dir, &ex);
                s.spawn(move || rank_main(r, ranks, dir, agreement, kill, ex))
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    // Each rank's restart file is its own.
    for r in 0..ranks {
        let name = if ranks == 1 {
            "chain.restart".to_string()
        } else {
            format!("chain.restart.r{r}")
        };
        assert!(dir.join(&name).is_file(), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    let mut all = Run::default();
    for r in runs {
        all.incs.extend(r.incs);
        all.actions.extend(r.actions);
        all.local.extend(r.local);
    }
    all.incs.sort_by_key(|(key, _)| *key);
    all
}

/// A directory of its own for every job (tests run concurrently in one process, and two
/// jobs sharing the rank files would read each other's passes).
fn scratch(name: &str) -> PathBuf {
    static JOBS: AtomicUsize = AtomicUsize::new(0);
    let job = JOBS.fetch_add(1, Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!(
        "jointlin-ranks-{}-{job}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
