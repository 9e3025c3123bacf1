//! Threads: the thread contract of the C API (the `jointlin_store` documentation in
//! include/jointlin.h, fortran-shim/README.md "Threads"), what tests/ffi_uinter.rs does not
//! cover already (16 threads of LINPER = 1 calls against one store = a serial run). Here:
//!
//! * the stateless functions (linearize, cubic, point step, screw preload) from 16 threads
//!   at once: every result bitwise the serial one;
//! * jointlin_last_error is per thread: 16 threads fail at once with different details and
//!   each reads its own;
//! * LINPER = 0 (time domain): 16 threads step their own points (separate STATEV) through
//!   the same increments at once, in lock step (a barrier per increment), with the shared
//!   store pointer passed as Abaqus would; every output is bitwise the serial run's.
//! * A mixed storm on one store: 16 threads at once register the same keys, query
//!   estimates, call UINTER LINPER = 1, report, and read status, counts, stats, the next
//!   action and the re-run list, while the main thread drives LOP 0–3 between increments;
//!   the store's state (per point key, increment and pass) is bitwise the serial run's;
//! * the calls that must not overlap, overlapping anyway (UINTER, estimate and report
//!   racing the increment's LOP 1 and LOP 2, two threads making UEXTERNALDB calls, a
//!   restore racing UINTER): every call returns JOINTLIN_OK or a named error code
//!   (JOINTLIN_ERR_SEQUENCE, JOINTLIN_ERR_UNKNOWN_POINT), never a panic, and the store
//!   then runs a clean pass;
//! * UINTER through the Fortran shim from 8 OpenMP threads (harness/fortran/uinter_omp.f90):
//!   the output of a multi-pass sweep is the one-thread run's, bitwise.

mod ffi_common;
mod hosts_common;

use ffi_common::*;
use jointlin::ffi::error::*;
use jointlin::ffi::store::*;
use std::collections::BTreeMap;
use std::sync::Barrier;

const THREADS: usize = 16;

/// Prescribed slips of point `p` at increment `k`: a drifting, growing two-direction
/// cycle that reaches Coulomb sliding in direction 1 and stays in microslip in 2.
fn slips(p: usize, k: usize) -> [f64; 3] {
    let d = 1.5 * 0.3 * 2.0 / 1282.7; // δ* at p = 2
    let t = k as f64 * 0.21 + p as f64 * 0.37;
    let grow = 0.3 + 0.02 * k as f64;
    let h = 2e-4 * (1.0 + 0.1 * (0.05 * k as f64 + p as f64).sin()); // pressure varies
    [
        h,
        grow * d * t.sin() + 1e-5 * k as f64,
        -0.4 * d * (0.7 * t).cos(),
    ]
}

/// Every output bit of the time-domain run of `points` points over `incs` increments,
/// with `threads` workers (1 = serial).
fn time_domain(threads: usize, points: usize, incs: usize) -> Vec<Vec<u64>> {
    let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
    let store_addr = store as usize;
    let barrier = Barrier::new(threads);
    let worker = |w: usize| -> Vec<(usize, Vec<u64>)> {
        let store = store_addr as *const jointlin_store;
        let mine: Vec<usize> = (w..points).step_by(threads).collect();
        let mut us: Vec<Uinter> = mine
            .iter()
            .map(|&p| {
                let mut props = block_props();
                props[1] = (p % 2) as f64; // thesis and Masing rules
                let mut u = Uinter::new(props, 3);
                u.coords = [p as f64, 0.0, 0.0];
                u
            })
            .collect();
        let mut trace: Vec<Vec<u64>> = vec![Vec::new(); mine.len()];
        for k in 1..=incs {
            if threads > 1 {
                barrier.wait(); // every thread calls UINTER for increment k at once
            }
            for (i, &p) in mine.iter().enumerate() {
                let u = &mut us[i];
                u.kinc = k as i32;
                for (dr, (new, old)) in u.drdisp.iter_mut().zip(slips(p, k).iter().zip(u.rdisp)) {
                    *dr = new - old;
                }
                u.rdisp = slips(p, k);
                u.linper = 0;
                assert_eq!(u.call(store), JOINTLIN_OK, "point {p} increment {k}");
                trace[i].extend(u.outputs().iter().map(|v| v.to_bits()));
            }
        }
        mine.into_iter().zip(trace).collect()
    };
    let mut all: Vec<(usize, Vec<u64>)> = if threads == 1 {
        worker(0)
    } else {
        std::thread::scope(|s| {
            let hs: Vec<_> = (0..threads).map(|w| s.spawn(move || worker(w))).collect();
            hs.into_iter().flat_map(|h| h.join().unwrap()).collect()
        })
    };
    all.sort_by_key(|(p, _)| *p);
    unsafe { jointlin_store_free(store) };
    all.into_iter().map(|(_, t)| t).collect()
}

#[test]
fn sixteen_threads_of_time_domain_uinter_match_a_serial_run_bitwise() {
    let (points, incs) = (64, 120);
    let serial = time_domain(1, points, incs);
    let parallel = time_domain(THREADS, points, incs);
    assert_eq!(serial.len(), points);
    for p in 0..points {
        assert_eq!(serial[p], parallel[p], "point {p}");
    }
    // The run is not trivial: some point slid (tangent 0 with a nonzero shear).
    let slid = (0..points).any(|p| {
        serial[p]
            .chunks(serial[p].len() / incs)
            .any(|o| f64::from_bits(o[7]) == 0.0 && f64::from_bits(o[1]) != 0.0)
        // DDSDDR(2,2), STRESS(2)
    });
    assert!(slid);
}

/// What the store knows at the end, keyed by point key (x coordinate) and increment, plus
/// the pass stats: the serial and the parallel run must agree bitwise.
type StoreState = (BTreeMap<(i64, i32), [u64; 8]>, Vec<jointlin_pass_stats>);

const KEYS: usize = 40;
const INCS: [i32; 3] = [1, 2, 3];

fn register(store: *const jointlin_store, key: usize) -> i64 {
    let name = b"STORM                    ";
    let coords = [key as f64, -0.0, 0.5];
    let mut id = 0;
    let s = unsafe {
        jointlin_store_register_point(
            store,
            name.as_ptr().cast(),
            name.len(),
            0,
            coords.as_ptr(),
            3,
            &mut id,
        )
    };
    assert_eq!(s, JOINTLIN_OK);
    id
}

/// A point's host response: a contraction towards a per-key amplitude.
fn host(key: usize, kinc: i32, est: [f64; 2]) -> [f64; 2] {
    let c = 1e-4 * (1.0 + 0.1 * key as f64 + 0.05 * f64::from(kinc));
    [0.5 * c + 0.5 * est[0], 0.8 * c + 0.2 * est[1]]
}

fn storm(threads: usize) -> StoreState {
    let store = new_store(1e-4, 1e-9, JOINTLIN_KINC_ORIGINAL);
    let addr = store as usize;
    loop {
        let (action, _) = next_action(store);
        let list = match action {
            JOINTLIN_ACTION_RUN_SWEEP => INCS.to_vec(),
            JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL => increments(store),
            JOINTLIN_ACTION_DONE => break,
            other => panic!("action {other}"),
        };
        assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
        for &kinc in &list {
            assert_eq!(uexternaldb(store, 1, 0, 2, kinc), 0);
            let work = |w: usize| {
                let store = addr as *const jointlin_store;
                // Every thread registers every key (same key → same id), then handles its
                // share: half through jointlin_uinter LINPER = 1, half through
                // estimate/report, with readers in between.
                let ids: Vec<i64> = (0..KEYS).map(|k| register(store, (k + w) % KEYS)).collect();
                for key in (w..KEYS).step_by(threads) {
                    let id = ids[(key + KEYS - w) % KEYS];
                    let est = if key % 2 == 0 {
                        let mut u = Uinter::new(block_props(), 3);
                        u.ciname = b"STORM".to_vec(); // same key as register()
                        u.coords = [key as f64, 0.0, 0.5];
                        u.stress[0] = 2.0;
                        u.linper = 1;
                        u.kstep = 2;
                        u.kinc = kinc;
                        assert_eq!(u.call(store), JOINTLIN_OK);
                        assert_eq!(u.report.point, id);
                        u.report.amplitude
                    } else {
                        let mut a = [0.0; 2];
                        assert_eq!(
                            unsafe { jointlin_store_estimate(store, id, kinc, a.as_mut_ptr()) },
                            0
                        );
                        a
                    };
                    let amp = host(key, kinc, est);
                    assert_eq!(
                        unsafe { jointlin_store_report(store, id, kinc, amp.as_ptr()) },
                        0
                    );
                    // Readers racing the writers: they must only ever see whole states.
                    let mut st = jointlin_point_status::default();
                    assert_eq!(
                        unsafe { jointlin_store_point_status(store, id, kinc, &mut st) },
                        0
                    );
                    assert_eq!(st.estimate, est);
                    let (mut n, mut action, mut pass) = (0i64, -1, -1);
                    assert_eq!(unsafe { jointlin_store_point_count(store, &mut n) }, 0);
                    assert!(n as usize <= KEYS && n >= 1);
                    assert_eq!(
                        unsafe { jointlin_store_next_action(store, &mut action, &mut pass) },
                        0
                    );
                    assert_eq!(action, JOINTLIN_ACTION_RUNNING);
                    let mut ps = jointlin_pass_stats::default();
                    assert_eq!(
                        unsafe { jointlin_store_pass_stats(store, pass, &mut ps) },
                        0
                    );
                    let mut count = 0usize;
                    assert_eq!(
                        unsafe {
                            jointlin_store_rerun_increments(
                                store,
                                std::ptr::null_mut(),
                                0,
                                &mut count,
                            )
                        },
                        0
                    );
                }
            };
            if threads == 1 {
                work(0);
            } else {
                std::thread::scope(|s| {
                    for w in 0..threads {
                        s.spawn(move || work(w));
                    }
                });
            }
            assert_eq!(uexternaldb(store, 2, 0, 2, kinc), 0);
        }
        assert_eq!(uexternaldb(store, 3, 0, 2, 0), 0);
    }
    let mut n = 0;
    assert_eq!(unsafe { jointlin_store_point_count(store, &mut n) }, 0);
    assert_eq!(n as usize, KEYS);
    let mut state = BTreeMap::new();
    for key in 0..KEYS {
        let id = register(store, key);
        for kinc in INCS {
            let mut st = jointlin_point_status::default();
            assert_eq!(
                unsafe { jointlin_store_point_status(store, id, kinc, &mut st) },
                0
            );
            let bits = [
                st.estimate[0].to_bits(),
                st.estimate[1].to_bits(),
                st.computed[0].to_bits(),
                st.computed[1].to_bits(),
                st.directions as u64,
                st.converged as u64,
                st.passes as u64,
                st.reason as u64,
            ];
            state.insert((key as i64, kinc), bits);
        }
    }
    let (_, passes) = next_action(store);
    let stats = (1..=passes)
        .map(|p| {
            let mut s = jointlin_pass_stats::default();
            assert_eq!(unsafe { jointlin_store_pass_stats(store, p, &mut s) }, 0);
            s
        })
        .collect();
    unsafe { jointlin_store_free(store) };
    (state, stats)
}

#[test]
fn mixed_register_estimate_report_storm_matches_a_serial_run() {
    let serial = storm(1);
    assert!(serial.1.len() >= 3, "several passes: {:?}", serial.1);
    for round in 0..3 {
        let parallel = storm(THREADS);
        assert_eq!(serial.1, parallel.1, "round {round}: pass stats");
        assert_eq!(serial.0, parallel.0, "round {round}: point states");
    }
}

#[test]
fn stateless_functions_from_sixteen_threads_match_a_serial_run_bitwise() {
    use jointlin::ffi::cubic::*;
    use jointlin::ffi::linearize::*;
    use jointlin::ffi::point::*;
    use jointlin::ffi::screw::*;
    // One worker's calls: a linearization per amplitude, the cubic spring, a point's slip
    // history, a screw preload; everything it returned, as text of the exact values.
    let calls = |w: usize| -> Vec<String> {
        let mut out = Vec::new();
        for i in 0..200 {
            let a = 1e-6 * (1.0 + (i * 7 + w * 3) as f64);
            let c = jointlin_contact {
                law: (i % 2) as i32,
                rule: ((i / 2) % 2) as i32,
                mu: 0.3,
                normal_force: 2.0 + 0.01 * i as f64,
                k_t0: 1282.7,
            };
            let mut l = jointlin_linearization::default();
            let code =
                unsafe { jointlin_linearize(&c, a, 1.3 + i as f64, std::ptr::null(), &mut l) };
            out.push(format!("{code} {l:?}"));
            let mut q = jointlin_cubic_linearization::default();
            let code = unsafe { jointlin_linearize_cubic(20.0, 40.0 - i as f64, a * 1e5, &mut q) };
            out.push(format!("{code} {q:?}"));
            let mut state = [0.0; JOINTLIN_POINT_STATE_LEN];
            for k in 0..20 {
                let slip = a * 100.0 * (0.3 * k as f64).sin();
                let mut step = jointlin_step::default();
                let mut next = [0.0; JOINTLIN_POINT_STATE_LEN];
                let code = unsafe {
                    jointlin_point_step(&c, state.as_ptr(), slip, next.as_mut_ptr(), &mut step)
                };
                state = next;
                out.push(format!("{code} {step:?}"));
            }
            let mut f = 0.0;
            let code = unsafe {
                jointlin_screw_preload(1000.0 + i as f64, 0.5, 2.675, 0.1, 0.12, 4.5, &mut f)
            };
            out.push(format!("{code} {f:?}"));
        }
        out
    };
    let serial: Vec<Vec<String>> = (0..THREADS).map(calls).collect();
    let parallel: Vec<Vec<String>> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..THREADS).map(|w| s.spawn(move || calls(w))).collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(serial, parallel);
    // The calls did compute (not all errors).
    assert!(serial[0].iter().filter(|r| r.starts_with("0 ")).count() > 4000);
}

#[test]
fn each_thread_reads_its_own_last_error() {
    let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
    let addr = store as usize;
    let barrier = Barrier::new(THREADS);
    std::thread::scope(|s| {
        for w in 0..THREADS {
            let barrier = &barrier;
            s.spawn(move || {
                let store = addr as *const jointlin_store;
                for round in 0..50 {
                    // A point id nobody registered, different per thread and round.
                    let id = 1000 + (round * THREADS + w) as i64;
                    let mut a = [0.0; 2];
                    let code = unsafe { jointlin_store_estimate(store, id, 1, a.as_mut_ptr()) };
                    assert_eq!(code, JOINTLIN_ERR_UNKNOWN_POINT);
                    barrier.wait(); // every thread has failed with its own detail
                    let mut buf = [0 as std::ffi::c_char; 128];
                    unsafe {
                        jointlin::ffi::error::jointlin_last_error(buf.as_mut_ptr(), buf.len())
                    };
                    let detail = unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) }
                        .to_string_lossy()
                        .into_owned();
                    assert!(
                        detail.ends_with(&format!("unknown contact point id {id}")),
                        "thread {w} round {round}: {detail}"
                    );
                    barrier.wait();
                }
            });
        }
    });
    unsafe { jointlin_store_free(store) };
}

/// The codes a call that overlaps what it must not overlap may return.
fn named(code: i32) -> bool {
    [
        JOINTLIN_OK,
        JOINTLIN_ERR_SEQUENCE,
        JOINTLIN_ERR_UNKNOWN_POINT,
    ]
    .contains(&code)
}

#[test]
fn calls_overlapping_uexternaldb_get_named_codes_and_leave_a_working_store() {
    use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
    let dir = std::env::temp_dir().join(format!("jointlin-threads-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("race.restart");
    let bytes = path.as_os_str().as_encoded_bytes();
    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = 1e-4;
    cfg.rtol = 1e-3;
    cfg.restart_path = bytes.as_ptr().cast();
    cfg.restart_path_len = bytes.len();
    let mut store = std::ptr::null_mut();
    assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
    let addr = store as usize;
    let ids: Vec<i64> = (0..KEYS).map(|k| register(store, k)).collect();
    // A restart file to restore from while others work.
    assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
    assert_eq!(uexternaldb(store, 1, 0, 2, 1), 0);
    assert_eq!(uexternaldb(store, 2, 1, 2, 1), 0);
    let kinc = AtomicI32::new(1);
    let stop = AtomicBool::new(false);
    let (ok, other) = (AtomicI32::new(0), AtomicI32::new(0));
    std::thread::scope(|s| {
        for w in 0..THREADS {
            let (kinc, stop, ok, other, ids) = (&kinc, &stop, &ok, &other, &ids);
            s.spawn(move || {
                let store = addr as *const jointlin_store;
                let mut i = w;
                while !stop.load(Ordering::Relaxed) {
                    let id = ids[i % KEYS];
                    let k = kinc.load(Ordering::Relaxed);
                    let codes = match w % 4 {
                        // UINTER LINPER = 1 and a report, racing LOP 1/2.
                        0 | 1 => {
                            let mut u = Uinter::new(block_props(), 3);
                            u.ciname = b"STORM".to_vec();
                            u.coords = [(i % KEYS) as f64, 0.0, 0.5];
                            u.stress[0] = 2.0;
                            u.linper = 1;
                            u.kstep = 2;
                            u.kinc = k;
                            let c = u.call(store);
                            let amp = [1e-4, 2e-4];
                            let r = unsafe { jointlin_store_report(store, id, k, amp.as_ptr()) };
                            vec![c, r]
                        }
                        // A second thread making UEXTERNALDB calls.
                        2 => vec![uexternaldb(store, 1 + (i % 2) as i32, 0, 2, k)],
                        // A restore (LOP 4) racing everything.
                        _ => vec![unsafe { jointlin_store_restore(store) }],
                    };
                    for c in codes {
                        assert!(named(c), "thread {w}: code {c}");
                        if c == JOINTLIN_OK {
                            ok.fetch_add(1, Ordering::Relaxed)
                        } else {
                            other.fetch_add(1, Ordering::Relaxed)
                        };
                    }
                    i += THREADS;
                }
            });
        }
        // The main thread drives increments underneath them: at least 200, and on until
        // both kinds of outcome were seen (a loaded machine may schedule the workers late),
        // at most a million.
        let mut k = 2;
        while k < 200
            || (k < 1_000_000
                && (ok.load(Ordering::Relaxed) == 0 || other.load(Ordering::Relaxed) == 0))
        {
            kinc.store(k, Ordering::Relaxed);
            for lop in [1, 2] {
                assert!(named(uexternaldb(store, lop, 0, 2, k)));
            }
            std::thread::yield_now();
            k += 1;
        }
        stop.store(true, Ordering::Relaxed);
    });
    // Both kinds of outcome happened: the race was real.
    assert!(ok.load(std::sync::atomic::Ordering::Relaxed) > 0);
    assert!(other.load(std::sync::atomic::Ordering::Relaxed) > 0);
    // The store is not poisoned: close whatever is open, then a clean pass decides.
    for k in 0..=200 {
        let _ = uexternaldb(store, 2, 0, 2, k);
    }
    let _ = uexternaldb(store, 3, 0, 2, 0);
    let (action, _) = next_action(store);
    assert!(
        [
            JOINTLIN_ACTION_RUN_PASS,
            JOINTLIN_ACTION_RUN_FINAL,
            JOINTLIN_ACTION_RUN_SWEEP
        ]
        .contains(&action),
        "{action}"
    );
    assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
    let list = if action == JOINTLIN_ACTION_RUN_SWEEP {
        vec![1]
    } else {
        increments(store)
    };
    for &k in &list {
        assert_eq!(uexternaldb(store, 1, 0, 2, k), 0);
        for &id in &ids {
            let mut a = [0.0; 2];
            assert_eq!(
                unsafe { jointlin_store_estimate(store, id, k, a.as_mut_ptr()) },
                0
            );
            assert_eq!(
                unsafe { jointlin_store_report(store, id, k, a.as_ptr()) },
                0
            );
        }
        assert_eq!(uexternaldb(store, 2, 0, 2, k), 0);
    }
    assert_eq!(uexternaldb(store, 3, 0, 2, 0), 0);
    unsafe { jointlin_store_free(store) };
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fortran_uinter_from_openmp_threads_through_the_shim_matches_one_thread() {
    use hosts_common::*;
    use std::process::Command;
    let dir = build_dir("threads");
    let lib = lib_dir();
    let shim = build_shim(&dir);
    let host = dir.join("fortran");
    run_ok(
        Command::new("make")
            .arg("-s")
            .arg("-f")
            .arg(root().join("harness/fortran/Makefile"))
            .arg(format!("BUILD={}", host.display()))
            .arg(format!("SHIM={}", shim.display()))
            .arg(format!("JOINTLIN_LIBDIR={}", lib.display()))
            .arg(host.join("uinter_omp")),
    );
    // stdout (the points' outputs), and the number of threads that handled points.
    let run = |threads: usize| -> (String, String) {
        let out = run_ok(
            Command::new(host.join("uinter_omp"))
                .env("OMP_NUM_THREADS", threads.to_string())
                .env(
                    "JOINTLIN_CONFIG",
                    root().join("harness/fortran/uinter_omp.cfg"),
                )
                .current_dir(scratch("uinter_omp")),
        );
        let stderr = String::from_utf8(out.stderr).unwrap();
        let workers = stderr
            .lines()
            .find_map(|l| l.strip_prefix("threads "))
            .unwrap_or_else(|| panic!("no thread count in {stderr}"))
            .to_string();
        (String::from_utf8(out.stdout).unwrap(), workers)
    };
    let (serial, one) = run(1);
    assert_eq!(one, "1");
    let passes: u32 = serial
        .lines()
        .last()
        .and_then(|l| l.strip_prefix("passes "))
        .and_then(|n| n.parse().ok())
        .expect("the last record is the number of passes");
    assert!(passes >= 3, "{passes} passes");
    for round in 0..3 {
        let (parallel, workers) = run(8);
        // 32 points over 8 threads, schedule(static, 1): every thread worked.
        assert_eq!(workers, "8", "round {round}");
        assert!(parallel == serial, "round {round}: 8 threads differ from 1");
    }
}
