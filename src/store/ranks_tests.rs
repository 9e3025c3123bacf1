//! Unit tests of the ranks' agreement: the summary encoding, what pass_agree refuses, the
//! file protocol's naming, waiting, timeout and cleanup.

use super::*;
use std::time::Duration;

fn config(initial: f64, restart: Option<PathBuf>) -> StoreConfig {
    let mut c = StoreConfig::new(initial);
    c.restart_path = restart;
    c
}

fn key(x: f64) -> PointKey {
    PointKey::new(b"R", 0, &[x, 0.0, 0.0]).unwrap()
}

/// Pass 1 over increments 1..=3 with one point reporting `amp(k)` against estimates: ends
/// after the last LOP 2 (the summary's moment).
fn pass_one(store: &Store, x: f64, amp: impl Fn(i32) -> f64) {
    let id = store.register(key(x)).unwrap();
    store.external_db(0, 0, 1, 0).unwrap();
    for k in 1..=3 {
        store.external_db(1, 0, 1, k).unwrap();
        store.estimate(id, k, 1).unwrap();
        store.report(id, k, [amp(k), 0.0]).unwrap();
        store.external_db(2, 0, 1, k).unwrap();
    }
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-ranks-unit-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn encoding_round_trips_and_the_maximum_shows_disagreement() {
    let a = PassSummary {
        pass: 3,
        increments: vec![1, 4, 7],
        rerun: vec![false, true, false],
    };
    let enc = a.encode().unwrap();
    assert_eq!(enc, vec![3, -3, 3, -3, 1, 4, 7, -1, -4, -7, 0, 1, 0]);
    assert_eq!(enc.len(), PassSummary::encoded_len(3));
    assert_eq!(PassSummary::decode(&enc).unwrap(), a);
    // Same pass and increments, other flags: the maximum is the union of the re-runs.
    let b = PassSummary {
        rerun: vec![true, false, false],
        ..a.clone()
    };
    let mut red = enc.clone();
    PassSummary::reduce_max(&mut red, &b.encode().unwrap()).unwrap();
    let agreed = PassSummary::decode(&red).unwrap();
    assert_eq!(agreed.rerun, vec![true, true, false]);
    // Another pass on one rank.
    let mut red = enc.clone();
    let c = PassSummary {
        pass: 4,
        ..a.clone()
    };
    PassSummary::reduce_max(&mut red, &c.encode().unwrap()).unwrap();
    let e = PassSummary::decode(&red).unwrap_err();
    assert!(
        matches!(e, StoreError::Sequence(ref m) if m.contains("3 to 4")),
        "{e}"
    );
    // Other increments on one rank.
    let mut red = enc.clone();
    let d = PassSummary {
        increments: vec![1, 5, 7],
        ..a.clone()
    };
    PassSummary::reduce_max(&mut red, &d.encode().unwrap()).unwrap();
    let e = PassSummary::decode(&red).unwrap_err();
    assert!(
        matches!(e, StoreError::Sequence(ref m) if m.contains("4 to 5")),
        "{e}"
    );
    // Different lengths cannot be reduced.
    let short = PassSummary {
        increments: vec![1],
        rerun: vec![false],
        pass: 3,
    };
    assert!(matches!(
        PassSummary::reduce_max(&mut enc.clone(), &short.encode().unwrap()),
        Err(StoreError::Sequence(_))
    ));
}

#[test]
fn malformed_summaries_are_out_of_range() {
    for buf in [
        vec![],
        vec![1, -1, 0],
        vec![1, -1, 1, -1, 5, -5],              // wrong length for n = 1
        vec![1, -1, 2, -2, 1, 2, -1, -2],       // too short for n = 2
        vec![0, 0, 0, 0],                       // pass 0
        vec![1, -1, 1, -1, 5, -5, 2],           // flag 2
        vec![1, -1, 2, -2, 3, 2, -3, -2, 0, 0], // not ascending
    ] {
        assert!(
            matches!(PassSummary::decode(&buf), Err(StoreError::OutOfRange(_))),
            "{buf:?}"
        );
    }
    let bad = PassSummary {
        pass: 1,
        increments: vec![i32::MIN],
        rerun: vec![true],
    };
    assert!(matches!(bad.encode(), Err(StoreError::OutOfRange(_))));
}

#[test]
fn summary_and_agreement_only_between_the_last_lop_2_and_lop_3() {
    let store = Store::new(config(1e-3, None)).unwrap();
    assert!(matches!(store.pass_summary(), Err(StoreError::Sequence(_))));
    let id = store.register(key(1.0)).unwrap();
    store.external_db(0, 0, 1, 0).unwrap();
    store.external_db(1, 0, 1, 1).unwrap();
    store.estimate(id, 1, 1).unwrap();
    // An increment is open.
    assert!(matches!(store.pass_summary(), Err(StoreError::Sequence(_))));
    store.report(id, 1, [1e-3, 0.0]).unwrap();
    store.external_db(2, 0, 1, 1).unwrap();
    let s = store.pass_summary().unwrap();
    assert_eq!(
        (s.pass, s.increments.clone(), s.rerun.clone()),
        (1, vec![1], vec![false])
    );
    store.external_db(3, 0, 1, 0).unwrap();
    assert!(matches!(store.pass_summary(), Err(StoreError::Sequence(_))));
    assert!(matches!(store.pass_agree(&s), Err(StoreError::Sequence(_))));
}

#[test]
fn agreement_refuses_what_is_not_a_maximum_including_this_rank() {
    let store = Store::new(config(1e-3, None)).unwrap();
    // Increment 3 out of tolerance here (its estimate is increment 2's 1e-3).
    pass_one(&store, 1.0, |k| if k == 3 { 5e-3 } else { 1e-3 });
    let own = store.pass_summary().unwrap();
    assert_eq!(own.rerun, vec![false, false, true]);
    let before = store.pass_summary().unwrap();
    for wrong in [
        PassSummary {
            rerun: vec![false, false, false], // drops this rank's re-run
            ..own.clone()
        },
        PassSummary {
            pass: 2,
            ..own.clone()
        },
        PassSummary {
            increments: vec![1, 2, 4],
            ..own.clone()
        },
    ] {
        assert!(matches!(
            store.pass_agree(&wrong),
            Err(StoreError::Sequence(_))
        ));
        assert_eq!(store.pass_summary().unwrap(), before, "unchanged on error");
    }
    // Another rank needs increment 2: LOP 3 re-runs both.
    store
        .pass_agree(&PassSummary {
            rerun: vec![false, true, true],
            ..own
        })
        .unwrap();
    store.external_db(3, 0, 1, 0).unwrap();
    assert_eq!(
        store.next_action().unwrap().unwrap().0,
        Action::RunPass(vec![2, 3])
    );
}

#[test]
fn ranked_restart_paths_and_stale_pass_files() {
    let dir = scratch("paths");
    let base = dir.join("job.restart");
    for (rank, ranks, name) in [
        (0, 1, "job.restart"),
        (0, 3, "job.restart.r0"),
        (2, 3, "job.restart.r2"),
    ] {
        let s = Store::new_ranked(config(1e-3, Some(base.clone())), rank, ranks).unwrap();
        assert_eq!(s.config().restart_path, Some(dir.join(name)));
    }
    for (rank, ranks) in [(0, 0), (3, 3), (5, 2)] {
        assert!(matches!(
            Store::new_ranked(config(1e-3, Some(base.clone())), rank, ranks),
            Err(StoreError::OutOfRange(_))
        ));
    }
    // A new iteration (no restart file of rank 1) deletes rank 1's pass files only.
    for f in [
        "job.restart.r1.pass1",
        "job.restart.r1.pass12",
        "job.restart.r1.passx",
        "job.restart.r0.pass1",
    ] {
        std::fs::write(dir.join(f), "x").unwrap();
    }
    Store::new_ranked(config(1e-3, Some(base.clone())), 1, 2).unwrap();
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["job.restart.r0.pass1", "job.restart.r1.passx"]);
    // With its restart file present (an iteration going on) nothing is deleted.
    std::fs::write(dir.join("job.restart.r0"), "x").unwrap();
    Store::new_ranked(config(1e-3, Some(base)), 0, 2).unwrap();
    assert!(dir.join("job.restart.r0.pass1").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn file_protocol_agrees_across_three_ranks_and_cleans_up() {
    let dir = scratch("files");
    let base = dir.join("j.restart");
    let stores: Vec<Store> = (0..3)
        .map(|r| Store::new_ranked(config(1e-3, Some(base.clone())), r, 3).unwrap())
        .collect();
    // Rank r is out of tolerance at increment r + 1 only.
    for (r, s) in stores.iter().enumerate() {
        pass_one(s, r as f64, |k| if k == r as i32 + 1 { 5e-3 } else { 1e-3 });
    }
    std::thread::scope(|sc| {
        for (r, s) in stores.iter().enumerate() {
            sc.spawn(move || {
                s.agree_by_files(r as u32, 3, Duration::from_secs(30))
                    .unwrap()
            });
        }
    });
    for s in &stores {
        s.external_db(3, 0, 1, 0).unwrap();
        assert_eq!(
            s.next_action().unwrap().unwrap().0,
            Action::RunPass(vec![1, 2, 3])
        );
    }
    for r in 0..3 {
        assert!(dir.join(format!("j.restart.r{r}.pass1")).is_file());
    }
    // Pass 2: everyone converged; the pass-1 files go.
    for s in &stores {
        s.external_db(0, 0, 1, 0).unwrap();
        let id = s.point_count().unwrap();
        for k in 1..=3 {
            s.external_db(1, 0, 1, k).unwrap();
            let a = s.estimate(id, k, 1).unwrap();
            s.report(id, k, a).unwrap();
            s.external_db(2, 0, 1, k).unwrap();
        }
    }
    std::thread::scope(|sc| {
        for (r, s) in stores.iter().enumerate() {
            sc.spawn(move || {
                s.agree_by_files(r as u32, 3, Duration::from_secs(30))
                    .unwrap()
            });
        }
    });
    for (r, s) in stores.iter().enumerate() {
        s.external_db(3, 0, 1, 0).unwrap();
        assert!(matches!(
            s.next_action().unwrap().unwrap().0,
            Action::RunFinal(_)
        ));
        assert!(!dir.join(format!("j.restart.r{r}.pass1")).exists());
        assert!(dir.join(format!("j.restart.r{r}.pass2")).is_file());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn file_protocol_times_out_naming_the_missing_ranks() {
    let dir = scratch("timeout");
    let s = Store::new_ranked(config(1e-3, Some(dir.join("t.restart"))), 1, 3).unwrap();
    pass_one(&s, 0.0, |_| 1e-3);
    let before = s.pass_summary().unwrap();
    let e = s
        .agree_by_files(1, 3, Duration::from_millis(100))
        .unwrap_err();
    assert!(
        matches!(e, StoreError::Io(ref m) if m.contains("[0, 2]") && m.contains("t.restart.r0.pass1")),
        "{e}"
    );
    assert_eq!(s.pass_summary().unwrap(), before);
    // A rank number the store was not made for, and no restart path at all.
    assert!(matches!(
        s.agree_by_files(2, 3, Duration::from_secs(1)),
        Err(StoreError::OutOfRange(_))
    ));
    let plain = Store::new_ranked(config(1e-3, None), 0, 2).unwrap();
    pass_one(&plain, 0.0, |_| 1e-3);
    assert!(matches!(
        plain.agree_by_files(0, 2, Duration::from_secs(1)),
        Err(StoreError::Io(_))
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}
