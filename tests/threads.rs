//! Threads: what tests/ffi_uinter.rs does not cover already (16 threads of
//! LINPER = 1 calls against one store = a serial run). Here:
//!
//! * LINPER = 0 (time domain): 16 threads step their own points (separate STATEV) through
//!   the same increments at once, in lock step (a barrier per increment), with the shared
//!   store pointer passed as Abaqus would; every output is bitwise the serial run's.
//! * A mixed storm on one store: 16 threads at once register the same keys, query
//!   estimates, call UINTER LINPER = 1, report, and read status, counts, stats, the next
//!   action and the re-run list, while the main thread drives LOP 0–3 between increments;
//!   the store's state (per point key, increment and pass) is bitwise the serial run's.

mod ffi_common;

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
