//! Store unit tests: multi-pass flows, schemes, restart, keys, sequence errors.

use super::*;
use crate::iterate::Scheme;

fn key(name: &str, node: i32, x: f64) -> PointKey {
    PointKey::new(name.as_bytes(), node, &[x, 0.0, 1.0]).unwrap()
}

/// Runs passes until Done/Failed with a toy host: `host(point index, sweep kinc, estimate)`
/// returns the computed amplitude. Returns the final action and the passes run.
fn drive(
    store: &Store,
    ids: &[i64],
    sweep: &[i32],
    host: impl Fn(usize, i32, [f64; 2]) -> [f64; 2],
) -> (Action, u32) {
    loop {
        let (action, number) = store.next_action().unwrap().unwrap();
        let list = match &action {
            Action::RunSweep => sweep.to_vec(),
            Action::RunPass(l) | Action::RunFinal(l) => l.clone(),
            Action::Done | Action::Failed(_) => return (action, number),
        };
        store.external_db(0, 0, 2, 0).unwrap();
        for (i, &k) in list.iter().enumerate() {
            let host_kinc = match store.config().numbering {
                KincNumbering::Original => k,
                KincNumbering::Sequential => i as i32 + 1,
            };
            store.external_db(1, 0, 2, host_kinc).unwrap();
            for (p, &id) in ids.iter().enumerate() {
                let est = store.estimate(id, host_kinc, 2).unwrap();
                store.report(id, host_kinc, host(p, k, est)).unwrap();
            }
            store.external_db(2, 1, 2, host_kinc).unwrap();
        }
        store.external_db(3, 0, 2, 0).unwrap();
    }
}

/// Linear contraction a* = c + s·a per point, increment, direction: fixed point c/(1 − s).
fn linear_host(p: usize, k: i32, a: [f64; 2]) -> [f64; 2] {
    let c = |d: usize| 1e-3 * (1.0 + p as f64 + 0.5 * k as f64 + 0.25 * d as f64);
    [c(0) + 0.4 * a[0], c(1) - 0.3 * a[1]]
}

#[test]
fn two_points_three_increments_converge_over_several_passes() {
    for scheme in [Scheme::Direct, Scheme::Relaxation, Scheme::Secant] {
        let mut cfg = StoreConfig::new(1e-3);
        cfg.scheme = scheme;
        cfg.rtol = 1e-6;
        cfg.max_passes = 60; // relaxation contracts by only 0.7 per pass here
        let store = Store::new(cfg).unwrap();
        let ids = [
            store.register(key("CP-1", 0, 1.0)).unwrap(),
            store.register(key("CP-1", 0, 2.0)).unwrap(),
        ];
        let (action, passes) = drive(&store, &ids, &[1, 2, 3], linear_host);
        assert_eq!(action, Action::Done, "{scheme:?}");
        // Pass 1 cannot converge (the map moves every estimate), so ≥ 1 re-run + final.
        assert!(passes >= 3, "{scheme:?}: {passes}");
        let first = store.pass_stats(1).unwrap().unwrap();
        assert_eq!((first.increments_run, first.evaluations), (3, 6));
        assert_eq!(first.increments_converged, 0);
        let last = store.pass_stats(passes).unwrap().unwrap();
        assert_eq!(last.kind, PassKind::Final);
        assert_eq!((last.increments_run, last.increments_converged), (3, 3));
        for (p, &id) in ids.iter().enumerate() {
            for k in 1..=3 {
                let st = store.point_status(id, k).unwrap().unwrap();
                assert!(st.converged);
                let c0 = 1e-3 * (1.0 + p as f64 + 0.5 * k as f64);
                let c1 = c0 + 0.25e-3;
                // Converged to rtol 1e-6 of a contraction with factor ≤ 0.4: the
                // estimate is within ~1e-6/(1 − 0.4) relative of the fixed point.
                assert!(
                    (st.estimate[0] / (c0 / 0.6) - 1.0).abs() < 3e-6,
                    "{scheme:?}"
                );
                assert!(
                    (st.estimate[1] / (c1 / 1.3) - 1.0).abs() < 3e-6,
                    "{scheme:?}"
                );
            }
        }
        // Past the end: no more passes.
        assert!(matches!(
            store.external_db(0, 0, 2, 0),
            Err(StoreError::Sequence(_))
        ));
    }
}

#[test]
fn pass_one_uses_the_initial_estimate_then_the_previous_increment() {
    let store = Store::new(StoreConfig::new(0.5)).unwrap();
    let id = store.register(key("I", 7, 0.0)).unwrap();
    store.begin_pass().unwrap();
    store.begin_increment(1).unwrap();
    assert_eq!(store.estimate(id, 1, 2).unwrap(), [0.5, 0.5]);
    store.report(id, 1, [0.25, 0.125]).unwrap();
    // A second query in the same increment returns the same estimate.
    assert_eq!(store.estimate(id, 1, 2).unwrap(), [0.5, 0.5]);
    store.end_increment(1).unwrap();
    store.begin_increment(2).unwrap();
    assert_eq!(store.estimate(id, 2, 2).unwrap(), [0.25, 0.125]);
}

#[test]
fn direct_two_cycles_where_secant_converges() {
    // a*(a) = 1/a: derivative −1 at the fixed point 1, so a ← a* flips 2 ↔ 0.5 forever
    // (Fig. 4.13); the secant on ln a*/a = −2 ln a is exact after two pairs.
    let host = |_: usize, _: i32, a: [f64; 2]| [1.0 / a[0], 1.0 / a[1]];
    let run = |scheme| {
        let mut cfg = StoreConfig::new(2.0);
        cfg.scheme = scheme;
        cfg.max_passes = 8;
        let store = Store::new(cfg).unwrap();
        let id = store.register(key("X", 1, 0.0)).unwrap();
        let out = drive(&store, &[id], &[1], host);
        (out, store.point_status(id, 1).unwrap().unwrap())
    };
    let ((action, passes), st) = run(Scheme::Direct);
    assert_eq!(action, Action::Failed(vec![1]));
    assert_eq!(passes, 8);
    assert_eq!(st.estimate[0], 0.5); // pass 8: 2, 0.5, 2, … → 0.5
    assert_eq!(st.reason, Reason::OutOfTolerance);
    let ((action, passes), st) = run(Scheme::Secant);
    assert_eq!(action, Action::Done);
    assert!(passes <= 5, "{passes}");
    assert!((st.estimate[0] - 1.0).abs() < 1e-3);
}

#[test]
fn a_point_queried_but_not_reported_is_not_converged() {
    let store = Store::new(StoreConfig::new(1.0)).unwrap();
    let (a, b) = (
        store.register(key("P", 0, 1.0)).unwrap(),
        store.register(key("P", 0, 2.0)).unwrap(),
    );
    store.begin_pass().unwrap();
    store.begin_increment(4).unwrap();
    store.estimate(a, 4, 1).unwrap();
    store.estimate(b, 4, 1).unwrap();
    // Direction 2 is not compared for a 1-direction point: its report may be anything.
    store.report(a, 4, [1.0, 99.0]).unwrap();
    store.end_increment(4).unwrap();
    store.end_pass().unwrap();
    assert_eq!(
        store.point_status(a, 4).unwrap().unwrap().reason,
        Reason::None
    );
    let sb = store.point_status(b, 4).unwrap().unwrap();
    assert_eq!((sb.converged, sb.reason), (false, Reason::NotReported));
    assert_eq!(store.pass_stats(1).unwrap().unwrap().not_reported, 1);
    assert_eq!(
        store.next_action().unwrap().unwrap(),
        (Action::RunPass(vec![4]), 2)
    );
}

#[test]
fn sequence_errors_are_named_not_panics() {
    let store = Store::new(StoreConfig::new(1.0)).unwrap();
    let id = store.register(key("S", 1, 0.0)).unwrap();
    let is_seq = |r: Result<_, StoreError>| matches!(r, Err(StoreError::Sequence(_)));
    assert!(is_seq(store.estimate(id, 1, 2).map(|_| ())));
    assert!(is_seq(store.external_db(1, 0, 1, 1)));
    assert!(is_seq(store.external_db(3, 0, 1, 1)));
    store.external_db(0, 0, 1, 0).unwrap();
    assert!(is_seq(store.external_db(0, 0, 1, 0)));
    assert!(is_seq(store.external_db(2, 0, 1, 1)));
    store.external_db(1, 0, 1, 1).unwrap();
    assert!(is_seq(store.external_db(1, 0, 1, 2)));
    assert!(is_seq(store.estimate(id, 2, 2).map(|_| ())));
    assert!(is_seq(store.report(id, 1, [1.0, 1.0])));
    assert!(is_seq(store.external_db(3, 0, 1, 1)));
    assert!(is_seq(store.external_db(2, 0, 1, 2)));
    assert_eq!(store.estimate(99, 1, 2), Err(StoreError::UnknownPoint(99)));
    assert!(matches!(
        store.external_db(9, 0, 1, 1),
        Err(StoreError::OutOfRange(_))
    ));
    // Still usable after all those errors.
    store.estimate(id, 1, 2).unwrap();
    store.report(id, 1, [1.0, 1.0]).unwrap();
    store.external_db(2, 0, 1, 1).unwrap();
    store.external_db(3, 0, 1, 0).unwrap();
    assert!(matches!(
        store.next_action().unwrap().unwrap().0,
        Action::RunFinal(_)
    ));
}

#[test]
fn an_increment_cut_back_is_entered_again() {
    // Abaqus re-enters an increment it cuts back with LOP 1 and the same KINC, and calls
    // LOP 2 only for the attempt that converged (with the default sweep_step = 0 every
    // step counts, a contact preload's cutbacks too). The first attempt's report is
    // replaced by the second's; another KINC while one is open is still an error.
    let store = Store::new(StoreConfig::new(1e-3)).unwrap();
    let id = store.register(key("C", 1, 0.0)).unwrap();
    store.external_db(0, 0, 1, 0).unwrap();
    store.external_db(1, 0, 1, 1).unwrap();
    let first = store.estimate(id, 1, 1).unwrap();
    store.report(id, 1, [5.0, 0.0]).unwrap();
    store.external_db(1, 0, 1, 1).unwrap();
    assert_eq!(store.estimate(id, 1, 1).unwrap(), first);
    store.report(id, 1, first).unwrap();
    assert!(matches!(
        store.external_db(1, 0, 1, 2),
        Err(StoreError::Sequence(_))
    ));
    store.external_db(2, 0, 1, 1).unwrap();
    store.external_db(3, 0, 1, 0).unwrap();
    let st = store.point_status(id, 1).unwrap().unwrap();
    assert_eq!((st.converged, st.reason), (true, Reason::None));
    assert_eq!(store.pass_stats(1).unwrap().unwrap().increments_run, 1);
}

#[test]
fn increments_outside_the_sweep_step_are_ignored() {
    let mut cfg = StoreConfig::new(1.0);
    cfg.sweep_step = 2;
    let store = Store::new(cfg).unwrap();
    store.external_db(0, 0, 1, 0).unwrap();
    store.external_db(5, 0, 1, 0).unwrap();
    store.external_db(1, 0, 1, 1).unwrap(); // static step: ignored
    store.external_db(2, 0, 1, 1).unwrap();
    store.external_db(6, 0, 1, 0).unwrap();
    // Pass 1 saw no sweep increment: a named error, not a silent "done".
    assert!(matches!(
        store.external_db(3, 0, 1, 0),
        Err(StoreError::Sequence(_))
    ));
}

#[test]
fn sequential_numbering_maps_rerun_kinc_to_the_schedule() {
    let mut cfg = StoreConfig::new(1e-3);
    cfg.numbering = KincNumbering::Sequential;
    cfg.rtol = 1e-6;
    let store = Store::new(cfg).unwrap();
    let ids = [store.register(key("Q", 0, 3.0)).unwrap()];
    // Increment 2 has a fixed point at the initial estimate: converged in pass 1, so
    // pass 2 re-runs only increments 1 and 3 as its KINC 1 and 2.
    let host = |_: usize, k: i32, a: [f64; 2]| {
        if k == 2 {
            a
        } else {
            linear_host(0, k, a)
        }
    };
    let (action, _) = drive(&store, &ids, &[1, 2, 3], host);
    assert_eq!(action, Action::Done);
    let second = store.pass_stats(2).unwrap().unwrap();
    assert_eq!((second.kind, second.increments_run), (PassKind::Rerun, 2));
    // Pass 1: increment 2 took increment 1's computed amplitude as its estimate and
    // kept it (identity map), so it converged at once and was never re-run.
    assert_eq!(store.point_status(ids[0], 2).unwrap().unwrap().passes, 2);
}

#[test]
fn restart_round_trip_continues_identically() {
    let dir = std::env::temp_dir().join(format!("jointlin-store-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("restart.txt");
    let mut cfg = StoreConfig::new(1e-3);
    cfg.restart_path = Some(path.clone());
    cfg.scheme = Scheme::Relaxation;
    let a = Store::new(cfg.clone()).unwrap();
    let ids = [
        a.register(key("R", 0, 1.0)).unwrap(),
        a.register(key("R", 0, -2.0)).unwrap(),
    ];
    // One full pass, then two increments of pass 2 with restart data written.
    let one_increment = |s: &Store, k: i32| {
        s.external_db(1, 0, 2, k).unwrap();
        for (p, &id) in ids.iter().enumerate() {
            let est = s.estimate(id, k, 2).unwrap();
            s.report(id, k, linear_host(p, k, est)).unwrap();
        }
        s.external_db(2, 1, 2, k).unwrap();
    };
    a.external_db(0, 0, 2, 0).unwrap();
    for k in 1..=3 {
        one_increment(&a, k);
    }
    a.external_db(3, 0, 2, 0).unwrap();
    a.external_db(0, 0, 2, 0).unwrap();
    one_increment(&a, 1);
    one_increment(&a, 2);
    // A new process restarts from the file (LOP 4) and must equal the original.
    let b = Store::new(cfg).unwrap();
    b.external_db(4, 0, 2, 2).unwrap();
    assert_eq!(a.serialize().unwrap(), b.serialize().unwrap());
    assert_eq!(*a.state.lock().unwrap(), *b.state.lock().unwrap());
    assert_eq!(b.register(key("R", 0, -2.0)).unwrap(), ids[1]);
    for s in [&a, &b] {
        one_increment(s, 3);
        s.external_db(3, 0, 2, 0).unwrap();
    }
    assert_eq!(a.serialize().unwrap(), b.serialize().unwrap());
    let (fa, na) = drive(&a, &ids, &[], linear_host);
    let (fb, nb) = drive(&b, &ids, &[], linear_host);
    assert_eq!((fa.clone(), na), (fb, nb));
    assert_eq!(fa, Action::Done);
    // A corrupt file is a named I/O error.
    std::fs::write(&path, "jointlin-store 1\nnext 7 0\n").unwrap();
    assert!(matches!(b.restore(), Err(StoreError::Io(_))));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn keys_never_collapse_on_node_zero() {
    let store = Store::new(StoreConfig::new(1.0)).unwrap();
    let ids: Vec<i64> = (0..5)
        .map(|i| store.register(key("SURF", 0, i as f64)).unwrap())
        .collect();
    assert_eq!(ids, vec![1, 2, 3, 4, 5]);
    // Same key → same id; Fortran blank padding, trailing NULs and −0.0 do not matter.
    let padded = PointKey::new(b"SURF    \0", 0, &[-0.0, 0.0, 1.0]).unwrap();
    assert_eq!(store.register(padded).unwrap(), 1);
    // Another interaction or node at the same place is another point.
    assert_eq!(store.register(key("SURF2", 0, 0.0)).unwrap(), 6);
    assert_eq!(store.register(key("SURF", 3, 0.0)).unwrap(), 7);
    assert_eq!(store.resolve(2, key("SURF", 0, 1.0)).unwrap(), 2);
    // A stale hint (id of another key) is not trusted.
    assert_eq!(store.resolve(2, key("SURF", 0, 4.0)).unwrap(), 5);
    assert_eq!(store.point_count().unwrap(), 7);
    assert!(PointKey::new(b"N", 0, &[f64::NAN]).is_err());
}

#[test]
fn config_is_validated() {
    let bad = |f: fn(&mut StoreConfig)| {
        let mut c = StoreConfig::new(1.0);
        f(&mut c);
        Store::new(c).is_err()
    };
    assert!(bad(|c| c.initial_amplitude = 0.0));
    assert!(bad(|c| c.initial_amplitude = f64::INFINITY));
    assert!(bad(|c| c.rtol = -1e-3));
    assert!(bad(|c| c.atol = f64::NAN));
    assert!(bad(|c| c.max_passes = 0));
    assert!(!bad(|c| c.atol = 1e-9));
}
