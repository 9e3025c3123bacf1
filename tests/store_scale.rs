//! The store's estimates in each point's own scale: amplitudes far below the user's
//! initial guess converge to their own value, and a point that does not move (zero load)
//! gets the estimate 0 and converges, so a zero excitation gives zero, not a floor.

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::store::*;

/// Runs passes until the store stops asking, with the host's response `respond(k, a)`
/// to estimate a at increment k; returns (final action, passes, last estimates per k).
fn iterate(
    store: *mut jointlin_store,
    kincs: &[i32],
    respond: impl Fn(i32, f64) -> f64,
) -> (i32, i32, Vec<f64>) {
    let name = b"JOINT";
    let mut id = 0i64;
    let coords = [0.0];
    let mut last = vec![f64::NAN; kincs.len()];
    for _ in 0..60 {
        let (action, _) = next_action(store);
        let run: Vec<i32> = match action {
            JOINTLIN_ACTION_RUN_SWEEP => kincs.to_vec(),
            JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL => increments(store),
            _ => break,
        };
        assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0);
        for k in run {
            assert_eq!(uexternaldb(store, 1, 0, 1, k), 0);
            let mut est = [0.0; 2];
            unsafe {
                let status = jointlin_store_register_point(
                    store,
                    name.as_ptr().cast(),
                    5,
                    0,
                    coords.as_ptr(),
                    1,
                    &mut id,
                );
                assert_eq!(status, 0);
                assert_eq!(jointlin_store_estimate(store, id, k, est.as_mut_ptr()), 0);
                assert!(est.iter().all(|a| a.is_finite() && *a >= 0.0), "{est:?}");
                let back = [respond(k, est[0]), respond(k, est[1])];
                assert_eq!(jointlin_store_report(store, id, k, back.as_ptr()), 0);
            }
            last[(k - 1) as usize] = est[0];
            assert_eq!(uexternaldb(store, 2, 0, 1, k), 0);
        }
        assert_eq!(uexternaldb(store, 3, 0, 1, 0), 0);
    }
    let (action, passes) = next_action(store);
    (action, passes, last)
}

#[test]
fn zero_load_gives_zero_estimates_and_converges() {
    // Every amplitude computed is exactly 0 (no excitation). The estimates were floored at
    // 1e-12 × initial_amplitude, never within the tolerance of 0: the sweep failed after
    // max_passes with nonzero k*-d* linearizations of a point that does not move.
    let store = new_store(1e-4, 1e-3, 0);
    let (action, passes, last) = iterate(store, &[1, 2, 3], |_, _| 0.0);
    assert_eq!(action, JOINTLIN_ACTION_DONE);
    assert!(passes <= 3, "{passes} passes");
    assert_eq!(last, vec![0.0; 3]);
    unsafe { jointlin_store_free(store) };
}

#[test]
fn amplitudes_far_below_the_initial_guess_converge_to_their_own_value() {
    // The response a* = a/2 + c has the fixed point 2c; with c = 5e-22 mm, six decades
    // below the old floor (1e-12 × 1e-4 mm), each increment converges to 1e-21 (was
    // stuck at the floor, not converged). The default secant rule solves this linear map
    // in a few passes (the direct rule would need ~80 halvings from the initial guess).
    for scheme in [JOINTLIN_SCHEME_SECANT] {
        let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
        assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
        cfg.initial_amplitude = 1e-4;
        cfg.rtol = 1e-4;
        cfg.scheme = scheme;
        cfg.max_passes = 40;
        let mut store = std::ptr::null_mut();
        assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
        let c = 5e-22;
        let (action, _, last) = iterate(store, &[1, 2], |_, a| 0.5 * a + c);
        assert_eq!(action, JOINTLIN_ACTION_DONE, "scheme {scheme}: {last:?}");
        for a in last {
            assert!((a / (2.0 * c) - 1.0).abs() < 1e-3, "scheme {scheme}: {a:e}");
        }
        unsafe { jointlin_store_free(store) };
    }
}
