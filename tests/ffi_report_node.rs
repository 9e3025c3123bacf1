//! jointlin_store_report_node: a host that knows its results per node (an Abaqus URDFIL
//! reading CDISP records) reports to the point registered for that node; a node without
//! a point is skipped (reported = 0), a node with several points (one per interaction) is
//! a named error, and hard inputs write nothing.

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::error::*;
use jointlin::ffi::store::*;
use std::ptr::{null, null_mut};

/// Registers a point of interaction `name` at `node`, returning its id.
fn register(store: *const jointlin_store, name: &[u8], node: i32, x: f64) -> i64 {
    let mut id = 0;
    let coords = [x, 0.0, 0.0];
    let st = unsafe {
        jointlin_store_register_point(
            store,
            name.as_ptr().cast(),
            name.len(),
            node,
            coords.as_ptr(),
            3,
            &mut id,
        )
    };
    assert_eq!(st, JOINTLIN_OK);
    id
}

#[test]
fn reports_reach_the_point_of_the_node_and_only_it() {
    let store = new_store(1e-4, 1e-6, JOINTLIN_KINC_ORIGINAL);
    let a7 = register(store, b"PAIR-A", 7, 0.0);
    let a8 = register(store, b"PAIR-A", 8, 1.0);
    let b7 = register(store, b"PAIR-B", 7, 0.0); // another interaction at node 7
    assert_eq!(uexternaldb(store, 0, 0, 1, 0), JOINTLIN_OK);
    assert_eq!(uexternaldb(store, 1, 0, 1, 1), JOINTLIN_OK);
    let mut est = [0.0; 2];
    for id in [a7, a8, b7] {
        assert_eq!(
            unsafe { jointlin_store_estimate(store, id, 1, est.as_mut_ptr()) },
            JOINTLIN_OK
        );
    }
    let amp = [2e-4, 3e-5];
    let mut reported = -1;
    unsafe {
        // Node 8: its one point gets the report.
        assert_eq!(
            jointlin_store_report_node(store, 8, 1, amp.as_ptr(), &mut reported),
            JOINTLIN_OK
        );
        assert_eq!(reported, 1);
        let mut status = jointlin_point_status::default();
        assert_eq!(
            jointlin_store_point_status(store, a8, 1, &mut status),
            JOINTLIN_OK
        );
        assert_eq!(status.computed, amp);
        // Node 9 has no point (a slave node UINTER never saw): nothing to do.
        reported = -1;
        assert_eq!(
            jointlin_store_report_node(store, 9, 1, amp.as_ptr(), &mut reported),
            JOINTLIN_OK
        );
        assert_eq!(reported, 0);
        // Node 7 has two points: which one is meant cannot be told.
        reported = -1;
        assert_eq!(
            jointlin_store_report_node(store, 7, 1, amp.as_ptr(), &mut reported),
            JOINTLIN_ERR_UNKNOWN_POINT
        );
        assert!(
            last_error().contains("node 7: 2 contact points"),
            "{}",
            last_error()
        );
        assert_eq!(reported, -1, "nothing written on error");
        // Hard inputs.
        assert_eq!(
            jointlin_store_report_node(null(), 8, 1, amp.as_ptr(), &mut reported),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_report_node(store, 8, 1, null(), &mut reported),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_report_node(store, 8, 1, amp.as_ptr(), null_mut()),
            JOINTLIN_ERR_NULL
        );
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                jointlin_store_report_node(store, 8, 1, [bad, 0.0].as_ptr(), &mut reported),
                JOINTLIN_ERR_NON_FINITE
            );
        }
        assert_eq!(
            jointlin_store_report_node(store, 8, 1, [-1.0, 0.0].as_ptr(), &mut reported),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(reported, -1, "nothing written on error");
        // Outside the increment that queried it: a sequence error.
        assert_eq!(uexternaldb(store, 2, 0, 1, 1), JOINTLIN_OK);
        assert_eq!(
            jointlin_store_report_node(store, 8, 2, amp.as_ptr(), &mut reported),
            JOINTLIN_ERR_SEQUENCE
        );
        jointlin_store_free(store);
    }
}
