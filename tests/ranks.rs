//! Stores of a job with several processes, through the C API, with threads standing in for
//! the ranks (the chain model of tests/chain_common; tests/hosts_mpi.rs runs the same job
//! with real MPI processes through the Fortran shim). Checked: with 1, 2 and 4 ranks every
//! estimate, k*, d*, amplitude, pass and re-run list is bitwise the serial run's; in some
//! pass the ranks' own decisions differ (so without the agreement they would run different
//! increments); ranks whose stores are dropped in the middle of a pass and restored from
//! their restart files (LOP 4) finish bitwise like the uninterrupted run.

mod chain_common;
mod ffi_common;

use chain_common::*;
use ffi_common::uexternaldb;
use jointlin::ffi::store::*;

fn check_equal(serial: &Run, got: &Run, what: &str) {
    assert_eq!(serial.incs.len(), got.incs.len(), "{what}: evaluations");
    for (a, b) in serial.incs.iter().zip(&got.incs) {
        assert_eq!(a, b, "{what}: (pass, increment, point) and bits");
    }
    for (r, actions) in got.actions.iter().enumerate() {
        assert_eq!(actions, &serial.actions[0], "{what}: rank {r}'s actions");
    }
}

#[test]
fn one_two_and_four_ranks_agreeing_by_maximum_equal_the_serial_run_bitwise() {
    let serial = run_job(1, Agreement::Max, None);
    let passes = serial.actions[0].len() - 1;
    assert!(passes >= 3, "{:?}", serial.actions[0]);
    let last = serial.actions[0].last().unwrap();
    assert_eq!(last.0, JOINTLIN_ACTION_DONE, "{:?}", serial.actions[0]);
    println!(
        "serial: {passes} passes, {} point evaluations; re-run lists {:?}",
        serial.incs.len(),
        serial.actions[0]
            .iter()
            .map(|a| a.2.clone())
            .collect::<Vec<_>>()
    );
    let mut disagreed = false;
    for ranks in [2, 4] {
        let got = run_job(ranks, Agreement::Max, None);
        check_equal(&serial, &got, &format!("{ranks} ranks"));
        // Some pass where the ranks' own decisions differ: the agreement is what keeps
        // them running the same increments.
        for pass in 1..=passes as i32 {
            let flags: Vec<&Vec<i32>> = got
                .local
                .iter()
                .filter(|(p, _, _)| *p == pass)
                .map(|(_, _, f)| f)
                .collect();
            disagreed |= flags.windows(2).any(|w| w[0] != w[1]);
        }
    }
    assert!(
        disagreed,
        "the ranks never decided differently on their own"
    );
}

#[test]
fn the_file_protocol_gives_the_same_run() {
    let serial = run_job(1, Agreement::Files, None);
    for ranks in [2, 4] {
        let got = run_job(ranks, Agreement::Files, None);
        check_equal(&serial, &got, &format!("{ranks} ranks, files"));
    }
}

#[test]
fn ranks_restored_from_their_restart_files_finish_like_the_uninterrupted_run() {
    let whole = run_job(2, Agreement::Files, None);
    let passes = whole.actions[0].len() - 1;
    for kill in [
        Kill { pass: 1, done: 2 },
        Kill {
            pass: passes as i32 - 1,
            done: 1,
        },
    ] {
        let got = run_job(2, Agreement::Files, Some(kill));
        check_equal(&whole, &got, &format!("restarted at {kill:?}"));
    }
}

#[test]
fn the_c_api_names_every_misuse() {
    use jointlin::ffi::error::*;
    use jointlin::ffi::store_ranks::*;
    let null = std::ptr::null_mut::<jointlin_store>();
    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = 1e-4;
    let mut out = null;
    for (rank, ranks) in [(-1, 2), (2, 2), (0, 0), (0, -3)] {
        assert_eq!(
            unsafe { jointlin_store_new_ranked(&cfg, rank, ranks, &mut out) },
            JOINTLIN_ERR_OUT_OF_RANGE,
            "rank {rank} of {ranks}"
        );
        assert!(out.is_null());
    }
    assert_eq!(
        unsafe { jointlin_store_new_ranked(&cfg, 0, 2, std::ptr::null_mut()) },
        JOINTLIN_ERR_NULL
    );
    assert_eq!(
        unsafe { jointlin_store_new_ranked(std::ptr::null(), 0, 2, &mut out) },
        JOINTLIN_ERR_NULL
    );
    let mut bad = cfg;
    bad.initial_amplitude = f64::NAN;
    assert_eq!(
        unsafe { jointlin_store_new_ranked(&bad, 0, 2, &mut out) },
        JOINTLIN_ERR_NON_FINITE
    );
    assert_eq!(
        unsafe { jointlin_store_new_ranked(&cfg, 1, 2, &mut out) },
        0
    );
    let s = out;
    let mut len = 7usize;
    let mut buf = [0i32; 16];
    // No restart path: length 0.
    assert_eq!(
        unsafe { jointlin_store_restart_path(s, std::ptr::null_mut(), 0, &mut len) },
        0
    );
    assert_eq!(len, 0);
    assert_eq!(
        unsafe { jointlin_store_restart_path(null, std::ptr::null_mut(), 0, &mut len) },
        JOINTLIN_ERR_NULL
    );
    // No pass running.
    assert_eq!(
        unsafe { jointlin_store_pass_summary(s, buf.as_mut_ptr(), buf.len(), &mut len) },
        JOINTLIN_ERR_SEQUENCE
    );
    assert_eq!(
        unsafe { jointlin_store_pass_summary(s, std::ptr::null_mut(), 4, &mut len) },
        JOINTLIN_ERR_NULL
    );
    assert_eq!(
        unsafe { jointlin_store_pass_agree(s, std::ptr::null(), 4) },
        JOINTLIN_ERR_NULL
    );
    assert_eq!(
        unsafe { jointlin_store_pass_agree(s, buf.as_ptr(), 3) },
        JOINTLIN_ERR_OUT_OF_RANGE
    );
    for t in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e300] {
        let code = unsafe { jointlin_store_agree_files(s, 1, 2, t) };
        assert!(
            code == JOINTLIN_ERR_OUT_OF_RANGE || code == JOINTLIN_ERR_NON_FINITE,
            "timeout {t}: {code}"
        );
    }
    assert_eq!(
        unsafe { jointlin_store_agree_files(s, 2, 2, 1.0) },
        JOINTLIN_ERR_OUT_OF_RANGE
    );
    // A pass with one increment and no points: summary, then an agreement that is not a
    // maximum over ranks at the same pass.
    assert_eq!(uexternaldb(s, 0, 0, 1, 0), 0);
    assert_eq!(uexternaldb(s, 1, 0, 1, 1), 0);
    assert_eq!(uexternaldb(s, 2, 0, 1, 1), 0);
    assert_eq!(
        unsafe { jointlin_store_pass_summary(s, buf.as_mut_ptr(), 3, &mut len) },
        JOINTLIN_ERR_SIZE
    );
    assert_eq!(len, 7);
    assert_eq!(
        unsafe { jointlin_store_pass_summary(s, buf.as_mut_ptr(), buf.len(), &mut len) },
        0
    );
    assert_eq!(&buf[..7], &[1, -1, 1, -1, 1, -1, 0]);
    let mut other = buf;
    other[1] = -2; // another rank at pass 2
    assert_eq!(
        unsafe { jointlin_store_pass_agree(s, other.as_ptr(), 7) },
        JOINTLIN_ERR_SEQUENCE
    );
    // No restart path: the file protocol cannot work.
    assert_eq!(
        unsafe { jointlin_store_agree_files(s, 1, 2, 1.0) },
        JOINTLIN_ERR_IO
    );
    assert_eq!(unsafe { jointlin_store_pass_agree(s, buf.as_ptr(), 7) }, 0);
    assert_eq!(uexternaldb(s, 3, 0, 1, 0), 0);
    unsafe { jointlin_store_free(s) };
}
