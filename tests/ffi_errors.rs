//! Hard inputs at the C ABI: every NULL argument gives JOINTLIN_ERR_NULL, NaN/±∞ in every
//! double input a named error, bad sizes and codes their own codes, and on any error
//! nothing is written (so no NaN ever reaches the host). Status messages exist for every
//! code.

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::cubic::*;
use jointlin::ffi::error::*;
use jointlin::ffi::linearize::*;
use jointlin::ffi::point::*;
use jointlin::ffi::store::*;
use jointlin::ffi::uexternaldb::jointlin_uexternaldb;
use jointlin::ffi::*;
use std::ffi::CStr;
use std::ptr::{null, null_mut};

const BAD: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
/// Sentinel left in outputs to prove they were not written.
const SENTINEL: f64 = 12345.0;

/// One way of spoiling a UINTER input.
type Case = Box<dyn Fn(&mut Uinter)>;

fn block() -> jointlin_contact {
    jointlin_contact {
        law: JOINTLIN_LAW_MINDLIN,
        rule: JOINTLIN_RULE_THESIS,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    }
}

fn sentinel_lin() -> jointlin_linearization {
    jointlin_linearization {
        k_star: SENTINEL,
        ..Default::default()
    }
}

#[test]
fn status_messages_exist_for_every_code() {
    let mut seen = std::collections::HashSet::new();
    for code in JOINTLIN_OK..=JOINTLIN_ERR_PANIC {
        let p = jointlin_status_message(code);
        assert!(!p.is_null());
        let s = unsafe { CStr::from_ptr(p) }.to_str().unwrap();
        assert!(!s.is_empty());
        assert!(seen.insert(s.to_owned()), "duplicate message {s}");
    }
    let unknown = unsafe { CStr::from_ptr(jointlin_status_message(999)) };
    assert_eq!(unknown.to_str().unwrap(), "unknown status code");
    assert_eq!(
        jointlin_abi_version(),
        (JOINTLIN_ABI_VERSION_MAJOR << 16) | JOINTLIN_ABI_VERSION_MINOR
    );
}

#[test]
fn linearize_cubic_rejects_hard_inputs_without_writing() {
    let sentinel = jointlin_cubic_linearization {
        k_star: SENTINEL,
        ..Default::default()
    };
    let mut out = sentinel;
    unsafe {
        assert_eq!(
            jointlin_linearize_cubic(20.0, 40.0, 0.4, null_mut()),
            JOINTLIN_ERR_NULL
        );
        for bad in BAD {
            for field in 0..3 {
                let mut v = [20.0, 40.0, 0.4];
                v[field] = bad;
                assert_eq!(
                    jointlin_linearize_cubic(v[0], v[1], v[2], &mut out),
                    JOINTLIN_ERR_NON_FINITE
                );
            }
        }
        assert_eq!(
            jointlin_linearize_cubic(20.0, 40.0, -0.4, &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            jointlin_linearize_cubic(20.0, 40.0, 1e200, &mut out),
            JOINTLIN_ERR_OVERFLOW
        );
        assert!(last_error().contains("cubic k*"), "{}", last_error());
        assert_eq!(out, sentinel);
        // The Duffing oscillator (B.1) at the thesis's amplitude: k* = 20 + 3/4·40·0.395² (3.8).
        assert_eq!(
            jointlin_linearize_cubic(20.0, 40.0, 0.395, &mut out),
            JOINTLIN_OK
        );
        assert!((out.k_star - 24.680_75).abs() < 1e-12, "{out:?}");
        assert_eq!((out.d_star, out.energy_per_cycle), (0.0, 0.0));
    }
}

#[test]
fn cubic_force_rejects_hard_inputs_without_writing() {
    let (mut f, mut t) = (SENTINEL, SENTINEL);
    unsafe {
        assert_eq!(
            jointlin_cubic_force(20.0, 40.0, 0.4, null_mut(), &mut t),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_cubic_force(20.0, 40.0, 0.4, &mut f, null_mut()),
            JOINTLIN_ERR_NULL
        );
        for bad in BAD {
            for field in 0..3 {
                let mut v = [20.0, 40.0, 0.4];
                v[field] = bad;
                assert_eq!(
                    jointlin_cubic_force(v[0], v[1], v[2], &mut f, &mut t),
                    JOINTLIN_ERR_NON_FINITE
                );
            }
        }
        assert_eq!(
            jointlin_cubic_force(20.0, 40.0, 1e200, &mut f, &mut t),
            JOINTLIN_ERR_OVERFLOW
        );
        assert_eq!((f, t), (SENTINEL, SENTINEL));
        // (4.1) at x = -0.5 (softening α): F = 20·(-0.5) - 40·(-0.125) = -5, dF/dx = 20 - 3·40·0.25 = -10.
        assert_eq!(
            jointlin_cubic_force(20.0, -40.0, -0.5, &mut f, &mut t),
            JOINTLIN_OK
        );
        assert!(
            (f + 5.0).abs() < 1e-15 && (t + 10.0).abs() < 1e-15,
            "{f} {t}"
        );
        // The tangent is the force's derivative: central difference, error O(h²) ≈ 1e-9 relative.
        let h = 1e-5;
        let (mut fp, mut fm, mut dummy) = (0.0, 0.0, 0.0);
        assert_eq!(
            jointlin_cubic_force(20.0, 40.0, 0.3 + h, &mut fp, &mut dummy),
            JOINTLIN_OK
        );
        assert_eq!(
            jointlin_cubic_force(20.0, 40.0, 0.3 - h, &mut fm, &mut dummy),
            JOINTLIN_OK
        );
        assert_eq!(
            jointlin_cubic_force(20.0, 40.0, 0.3, &mut f, &mut t),
            JOINTLIN_OK
        );
        assert!(((fp - fm) / (2.0 * h) - t).abs() < 1e-8 * t, "{t}");
    }
}

#[test]
fn linearize_rejects_null_and_non_finite_without_writing() {
    let c = block();
    let mut out = sentinel_lin();
    unsafe {
        assert_eq!(
            jointlin_linearize(null(), 1e-4, 1.3, null(), &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_linearize(&c, 1e-4, 1.3, null(), null_mut()),
            JOINTLIN_ERR_NULL
        );
        assert!(last_error().contains("out is NULL"), "{}", last_error());
        for bad in BAD {
            for field in 0..5 {
                let mut c = block();
                let (mut a, mut w) = (1e-4, 1.3);
                match field {
                    0 => c.mu = bad,
                    1 => c.normal_force = bad,
                    2 => c.k_t0 = bad,
                    3 => a = bad,
                    _ => w = bad,
                }
                assert_eq!(
                    jointlin_linearize(&c, a, w, null(), &mut out),
                    JOINTLIN_ERR_NON_FINITE
                );
            }
        }
        assert_eq!(out, sentinel_lin());
        // Codes and ranges.
        let mut c = block();
        c.law = 7;
        assert_eq!(
            jointlin_linearize(&c, 1e-4, 1.3, null(), &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        let m = jointlin_method {
            kind: JOINTLIN_METHOD_SIMPSON,
            points: 3,
        };
        assert_eq!(
            jointlin_linearize(&block(), 1e-4, 1.3, &m, &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            jointlin_linearize(&block(), -1e-4, 1.3, null(), &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            jointlin_linearize(&block(), 1e-4, 0.0, null(), &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        let mut c = block();
        c.mu = -0.1;
        assert_eq!(
            jointlin_linearize(&c, 1e-4, 1.3, null(), &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(out, sentinel_lin());
        // Open contact: OK and zeros.
        let mut c = block();
        c.normal_force = -1.0;
        assert_eq!(
            jointlin_linearize(&c, 1e-4, 1.3, null(), &mut out),
            JOINTLIN_OK
        );
        assert_eq!(
            (out.k_star, out.d_star, out.regime),
            (0.0, 0.0, JOINTLIN_REGIME_OPEN)
        );
        // Extreme but finite inputs: either a named error or finite outputs, never NaN.
        for a in [0.0, 1e-300, 1e-12, 1e300] {
            for w in [1e-300, 1.0, 1e300] {
                let mut out = sentinel_lin();
                let rc = jointlin_linearize(&block(), a, w, null(), &mut out);
                let v = [
                    out.k_star,
                    out.d_star,
                    out.eta,
                    out.energy_per_cycle,
                    out.peak_force,
                    out.slip_limit,
                    out.amplitude_ratio,
                ];
                assert!(v.iter().all(|x| x.is_finite()), "A {a} ω {w}: {out:?}");
                assert!(
                    rc == JOINTLIN_OK || (rc == JOINTLIN_ERR_OVERFLOW && out == sentinel_lin()),
                    "A {a} ω {w}: {rc}"
                );
            }
        }
    }
}

#[test]
fn point_step_rejects_null_and_non_finite_without_writing() {
    let c = block();
    let state = [0.0; JOINTLIN_POINT_STATE_LEN];
    let mut next = [SENTINEL; JOINTLIN_POINT_STATE_LEN];
    let mut out = jointlin_step {
        force: SENTINEL,
        tangent: SENTINEL,
        dissipated: SENTINEL,
    };
    let keep = out;
    unsafe {
        assert_eq!(
            jointlin_point_step(null(), state.as_ptr(), 1e-4, next.as_mut_ptr(), &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_point_step(&c, null(), 1e-4, next.as_mut_ptr(), &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_point_step(&c, state.as_ptr(), 1e-4, null_mut(), &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_point_step(&c, state.as_ptr(), 1e-4, next.as_mut_ptr(), null_mut()),
            JOINTLIN_ERR_NULL
        );
        for bad in BAD {
            assert_eq!(
                jointlin_point_step(&c, state.as_ptr(), bad, next.as_mut_ptr(), &mut out),
                JOINTLIN_ERR_NON_FINITE
            );
            for i in 0..JOINTLIN_POINT_STATE_LEN {
                let mut s = state;
                s[i] = bad;
                assert_eq!(
                    jointlin_point_step(&c, s.as_ptr(), 1e-4, next.as_mut_ptr(), &mut out),
                    JOINTLIN_ERR_NON_FINITE
                );
            }
            let mut cb = c;
            cb.mu = bad;
            assert_eq!(
                jointlin_point_step(&cb, state.as_ptr(), 1e-4, next.as_mut_ptr(), &mut out),
                JOINTLIN_ERR_NON_FINITE
            );
        }
        // A corrupt state (unknown rule tag) is a named error, not a panic.
        let mut corrupt = state;
        corrupt[0] = 7.0;
        assert_eq!(
            jointlin_point_step(&c, corrupt.as_ptr(), 1e-4, next.as_mut_ptr(), &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(out, keep);
        assert!(next.iter().all(|&v| v == SENTINEL));
        // In place (state_out == state) is allowed.
        let mut s = state;
        assert_eq!(
            jointlin_point_step(&c, s.as_ptr(), 1e-4, s.as_mut_ptr(), &mut out),
            JOINTLIN_OK
        );
        assert!(out.force > 0.0 && s[0] == 1.0);
    }
}

#[test]
fn store_functions_reject_null_and_non_finite() {
    let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
    let name = b"CP";
    let coords = [0.0, 1.0, 2.0];
    let mut id = -7i64;
    let mut amp = [SENTINEL; 2];
    let (mut a, mut p, mut n) = (0i32, 0i32, 0usize);
    let mut buf = [0i32; 4];
    let mut count = 0i64;
    let mut stats = jointlin_pass_stats::default();
    let mut status = jointlin_point_status::default();
    let time = [0.0; 2];
    unsafe {
        let mut cfg = std::mem::zeroed::<jointlin_store_config>();
        assert_eq!(jointlin_store_config_default(null_mut()), JOINTLIN_ERR_NULL);
        assert_eq!(jointlin_store_config_default(&mut cfg), JOINTLIN_OK);
        cfg.initial_amplitude = 1e-4;
        let mut s2 = null_mut();
        assert_eq!(jointlin_store_new(null(), &mut s2), JOINTLIN_ERR_NULL);
        assert_eq!(jointlin_store_new(&cfg, null_mut()), JOINTLIN_ERR_NULL);
        for bad in BAD {
            for field in 0..3 {
                let mut c = cfg;
                match field {
                    0 => c.initial_amplitude = bad,
                    1 => c.rtol = bad,
                    _ => c.atol = bad,
                }
                assert_eq!(jointlin_store_new(&c, &mut s2), JOINTLIN_ERR_NON_FINITE);
            }
        }
        let mut c = cfg;
        c.restart_path_len = 3; // NULL path with a length
        assert_eq!(jointlin_store_new(&c, &mut s2), JOINTLIN_ERR_NULL);
        let mut c = cfg;
        c.scheme = 9;
        assert_eq!(jointlin_store_new(&c, &mut s2), JOINTLIN_ERR_OUT_OF_RANGE);
        let mut c = cfg;
        c.initial_amplitude = 0.0;
        assert_eq!(jointlin_store_new(&c, &mut s2), JOINTLIN_ERR_OUT_OF_RANGE);
        assert!(s2.is_null(), "no handle written on failure");
        jointlin_store_free(null_mut()); // a no-op

        let reg = jointlin_store_register_point;
        assert_eq!(
            reg(
                null(),
                name.as_ptr().cast(),
                2,
                0,
                coords.as_ptr(),
                3,
                &mut id
            ),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            reg(store, null(), 2, 0, coords.as_ptr(), 3, &mut id),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            reg(store, name.as_ptr().cast(), 2, 0, null(), 3, &mut id),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            reg(
                store,
                name.as_ptr().cast(),
                2,
                0,
                coords.as_ptr(),
                3,
                null_mut()
            ),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            reg(
                store,
                name.as_ptr().cast(),
                2,
                0,
                coords.as_ptr(),
                4,
                &mut id
            ),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        for bad in BAD {
            for i in 0..3 {
                let mut x = coords;
                x[i] = bad;
                assert_eq!(
                    reg(store, name.as_ptr().cast(), 2, 0, x.as_ptr(), 3, &mut id),
                    JOINTLIN_ERR_NON_FINITE
                );
            }
        }
        assert_eq!(id, -7);
        assert_eq!(
            reg(
                store,
                name.as_ptr().cast(),
                2,
                0,
                coords.as_ptr(),
                3,
                &mut id
            ),
            JOINTLIN_OK
        );
        assert_eq!(id, 1);

        assert_eq!(
            jointlin_store_estimate(null(), 1, 1, amp.as_mut_ptr()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_estimate(store, 1, 1, null_mut()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_report(null(), 1, 1, amp.as_ptr()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_report(store, 1, 1, null()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_next_action(null(), &mut a, &mut p),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_next_action(store, null_mut(), &mut p),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_next_action(store, &mut a, null_mut()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_rerun_increments(null(), buf.as_mut_ptr(), 4, &mut n),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_rerun_increments(store, null_mut(), 4, &mut n),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_rerun_increments(store, buf.as_mut_ptr(), 4, null_mut()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_pass_stats(null(), 1, &mut stats),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_pass_stats(store, 1, null_mut()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_point_status(null(), 1, 1, &mut status),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_point_status(store, 1, 1, null_mut()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_point_count(null(), &mut count),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_store_point_count(store, null_mut()),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(jointlin_store_restore(null()), JOINTLIN_ERR_NULL);
        assert_eq!(
            jointlin_uexternaldb(null(), 0, 0, time.as_ptr(), 0.0, 1, 0),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_uexternaldb(store, 0, 0, null(), 0.0, 1, 0),
            JOINTLIN_ERR_NULL
        );
        // Non-finite time/dtime and reports.
        for bad in BAD {
            assert_eq!(
                jointlin_uexternaldb(store, 0, 0, [0.0, bad].as_ptr(), 0.0, 1, 0),
                JOINTLIN_ERR_NON_FINITE
            );
            assert_eq!(
                jointlin_uexternaldb(store, 0, 0, time.as_ptr(), bad, 1, 0),
                JOINTLIN_ERR_NON_FINITE
            );
        }
        // Sequence, unknown point, sizes.
        assert_eq!(
            jointlin_store_estimate(store, 1, 1, amp.as_mut_ptr()),
            JOINTLIN_ERR_SEQUENCE
        );
        assert_eq!(amp, [SENTINEL; 2]);
        assert_eq!(jointlin_store_restore(store), JOINTLIN_ERR_IO); // no path configured
        assert_eq!(uexternaldb(store, 0, 0, 1, 0), JOINTLIN_OK);
        assert_eq!(uexternaldb(store, 1, 0, 1, 1), JOINTLIN_OK);
        assert_eq!(
            jointlin_store_estimate(store, 2, 1, amp.as_mut_ptr()),
            JOINTLIN_ERR_UNKNOWN_POINT
        );
        assert_eq!(
            jointlin_store_estimate(store, 1, 1, amp.as_mut_ptr()),
            JOINTLIN_OK
        );
        for bad in BAD {
            assert_eq!(
                jointlin_store_report(store, 1, 1, [bad, 1e-4].as_ptr()),
                JOINTLIN_ERR_NON_FINITE
            );
        }
        assert_eq!(
            jointlin_store_report(store, 1, 1, [-1.0, 1e-4].as_ptr()),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            jointlin_store_report(store, 1, 1, [2e-4, 1e-4].as_ptr()),
            JOINTLIN_OK
        );
        assert_eq!(uexternaldb(store, 1, 0, 1, 2), JOINTLIN_ERR_SEQUENCE);
        assert!(last_error().contains("LOP 2 missing"), "{}", last_error());
        assert_eq!(uexternaldb(store, 2, 0, 1, 1), JOINTLIN_OK);
        assert_eq!(uexternaldb(store, 3, 0, 1, 0), JOINTLIN_OK);
        assert_eq!(uexternaldb(store, 8, 0, 1, 0), JOINTLIN_ERR_OUT_OF_RANGE);
        assert_eq!(next_action(store).0, JOINTLIN_ACTION_RUN_PASS);
        assert_eq!(
            jointlin_store_rerun_increments(store, buf.as_mut_ptr(), 0, &mut n),
            JOINTLIN_ERR_SIZE
        );
        assert_eq!(
            n, 1,
            "the size is reported even when the buffer is too small"
        );
        n = 0;
        assert_eq!(
            jointlin_store_rerun_increments(store, null_mut(), 0, &mut n),
            JOINTLIN_ERR_SIZE,
            "a NULL buffer with cap 0 is a size query"
        );
        assert_eq!(n, 1);
        assert_eq!(
            jointlin_store_pass_stats(store, 2, &mut stats),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            jointlin_store_point_status(store, 1, 5, &mut status),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
        assert_eq!(
            jointlin_store_point_status(store, 1, 1, &mut status),
            JOINTLIN_OK
        );
        assert_eq!((status.converged, status.reason, status.passes), (0, 1, 1));
        jointlin_store_free(store);
    }
}

/// Every pointer argument of jointlin_uinter, by position.
const UINTER_POINTERS: [&str; 14] = [
    "stress",
    "ddsddr",
    "dviscous",
    "dstructural",
    "statev",
    "sfd",
    "pnewdt",
    "rdisp",
    "drdisp",
    "time",
    "ciname",
    "props",
    "coords",
    "lopenclose",
];

/// Calls jointlin_uinter with pointer `null_at` (index into UINTER_POINTERS) set to NULL.
fn uinter_with_null(u: &mut Uinter, store: *const jointlin_store, null_at: usize) -> i32 {
    let nul = |i: usize, p: *mut f64| if i == null_at { null_mut() } else { p };
    unsafe {
        jointlin::ffi::uinter::jointlin_uinter(
            store,
            nul(0, u.stress.as_mut_ptr()),
            nul(1, u.ddsddr.as_mut_ptr()),
            nul(2, u.dviscous.as_mut_ptr()),
            nul(3, u.dstructural.as_mut_ptr()),
            nul(4, u.statev.as_mut_ptr()),
            nul(5, &mut u.sfd),
            nul(6, &mut u.pnewdt),
            nul(7, u.rdisp.as_mut_ptr()),
            nul(8, u.drdisp.as_mut_ptr()),
            nul(9, u.time.as_mut_ptr()),
            u.dtime,
            u.freqr,
            if null_at == 10 {
                null()
            } else {
                u.ciname.as_ptr().cast()
            },
            u.ciname.len(),
            nul(11, u.props.as_mut_ptr()),
            nul(12, u.coords.as_mut_ptr()),
            u.area,
            u.node,
            u.ndir,
            u.statev.len() as i32,
            u.props.len() as i32,
            u.mcrd,
            u.kstep,
            u.kinc,
            u.linper,
            if null_at == 13 {
                null_mut()
            } else {
                &mut u.lopenclose
            },
            &mut u.report,
        )
    }
}

fn closed_point() -> Uinter {
    let mut u = Uinter::new(block_props(), 3);
    u.rdisp = [2e-4, 1e-4, -5e-5];
    u.drdisp = [2e-4, 1e-4, -5e-5];
    u.stress = [SENTINEL; 3];
    u.ddsddr = [SENTINEL; 9];
    u.dviscous = [SENTINEL; 9];
    u.dstructural = [SENTINEL; 9];
    u.sfd = SENTINEL;
    u
}

#[test]
fn uinter_rejects_every_null_pointer_without_writing() {
    for linper in [0, 1] {
        let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
        assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0);
        assert_eq!(uexternaldb(store, 1, 0, 1, 1), 0);
        for (at, name) in UINTER_POINTERS.iter().enumerate() {
            let mut u = closed_point();
            u.linper = linper;
            u.stress[0] = 2.0;
            let before = u.outputs();
            assert_eq!(
                uinter_with_null(&mut u, store, at),
                JOINTLIN_ERR_NULL,
                "{name}"
            );
            assert_eq!(u.outputs(), before, "{name}");
        }
        // The store may be NULL only at LINPER = 0.
        let mut u = closed_point();
        u.linper = linper;
        u.stress[0] = 2.0;
        let expect = if linper == 0 {
            JOINTLIN_OK
        } else {
            JOINTLIN_ERR_NULL
        };
        assert_eq!(u.call(null()), expect);
        // The report may always be NULL.
        let mut u = closed_point();
        u.linper = linper;
        u.stress[0] = 2.0;
        let rc = unsafe {
            jointlin::ffi::uinter::jointlin_uinter(
                store,
                u.stress.as_mut_ptr(),
                u.ddsddr.as_mut_ptr(),
                u.dviscous.as_mut_ptr(),
                u.dstructural.as_mut_ptr(),
                u.statev.as_mut_ptr(),
                &mut u.sfd,
                &mut u.pnewdt,
                u.rdisp.as_ptr(),
                u.drdisp.as_ptr(),
                u.time.as_ptr(),
                u.dtime,
                u.freqr,
                u.ciname.as_ptr().cast(),
                u.ciname.len(),
                u.props.as_ptr(),
                u.coords.as_ptr(),
                u.area,
                u.node,
                u.ndir,
                60,
                7,
                3,
                u.kstep,
                u.kinc,
                linper,
                &mut u.lopenclose,
                null_mut(),
            )
        };
        assert_eq!(rc, JOINTLIN_OK);
        unsafe { jointlin_store_free(store) };
    }
}

#[test]
fn uinter_rejects_non_finite_in_every_double_input_without_writing() {
    let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
    assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0);
    assert_eq!(uexternaldb(store, 1, 0, 1, 1), 0);
    for linper in [0, 1] {
        for bad in BAD {
            let mut cases: Vec<Case> = vec![
                Box::new(move |u| u.dtime = bad),
                Box::new(move |u| u.freqr = bad),
                Box::new(move |u| u.area = bad),
                Box::new(move |u| u.pnewdt = bad),
            ];
            for i in 0..3 {
                cases.push(Box::new(move |u| u.stress[i] = bad));
                cases.push(Box::new(move |u| u.rdisp[i] = bad));
                cases.push(Box::new(move |u| u.drdisp[i] = bad));
                cases.push(Box::new(move |u| u.coords[i] = bad));
            }
            for i in 0..2 {
                cases.push(Box::new(move |u| u.time[i] = bad));
            }
            for i in 0..7 {
                cases.push(Box::new(move |u| u.props[i] = bad));
            }
            for i in 0..57 {
                cases.push(Box::new(move |u| u.statev[i] = bad));
            }
            for (n, case) in cases.iter().enumerate() {
                let mut u = closed_point();
                u.linper = linper;
                case(&mut u);
                let before = u.outputs();
                assert_eq!(
                    u.call(store),
                    JOINTLIN_ERR_NON_FINITE,
                    "case {n}, LINPER {linper}"
                );
                // Unchanged (NaN compared by bits).
                let same = u
                    .outputs()
                    .iter()
                    .zip(&before)
                    .all(|(a, b)| a.to_bits() == b.to_bits());
                assert!(same, "case {n}: outputs written");
            }
        }
    }
    unsafe { jointlin_store_free(store) };
}

/// jointlin_uinter_props_check reads a table as jointlin_uinter does: the same code for
/// every good or bad table, NULL and non-finite entries named.
#[test]
fn props_check_agrees_with_uinter() {
    use jointlin::ffi::props::jointlin_uinter_props_check;
    let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
    type Change = dyn Fn(&mut Vec<f64>);
    let cases: [(&Change, i32); 13] = [
        (&|_| {}, JOINTLIN_OK),
        (&|p| p.truncate(6), JOINTLIN_ERR_SIZE),
        (&|p| p[0] = 2.0, JOINTLIN_ERR_PROPS), // no law 2: refused, not read as Jenkins
        (&|p| p[0] = 0.5, JOINTLIN_ERR_PROPS),
        (&|p| p[1] = 2.0, JOINTLIN_ERR_PROPS),
        (&|p| p[2] = -0.3, JOINTLIN_ERR_PROPS),
        (&|p| p[3] = 0.0, JOINTLIN_ERR_PROPS),
        (&|p| p[4] = 2.0, JOINTLIN_ERR_PROPS),
        (&|p| p[5] = 0.0, JOINTLIN_ERR_PROPS),
        (&|p| p.extend([1.0, 1.0]), JOINTLIN_ERR_PROPS),
        (&|p| p.extend([0.0, 0.0, 2.0]), JOINTLIN_ERR_PROPS),
        (&|p| p.extend([0.0, 0.0, 0.0, 1.0, 3.0]), JOINTLIN_ERR_PROPS),
        (&|p| p[2] = f64::NAN, JOINTLIN_ERR_NON_FINITE),
    ];
    for (n, (change, expect)) in cases.iter().enumerate() {
        let mut u = closed_point();
        change(&mut u.props);
        let checked =
            unsafe { jointlin_uinter_props_check(u.props.as_ptr(), u.props.len() as i32) };
        assert_eq!(checked, *expect, "case {n}: props_check");
        assert_eq!(u.call(store), *expect, "case {n}: uinter");
    }
    assert_eq!(
        unsafe { jointlin_uinter_props_check(null(), 12) },
        JOINTLIN_ERR_NULL
    );
    unsafe { jointlin_store_free(store) };
}

#[test]
fn uinter_sizes_codes_and_ranges_have_named_errors() {
    let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
    let check = |f: &dyn Fn(&mut Uinter), expect: i32| {
        let mut u = closed_point();
        f(&mut u);
        let before = u.outputs();
        assert_eq!(u.call(store), expect);
        assert_eq!(u.outputs(), before);
    };
    check(&|u| u.ndir = 0, JOINTLIN_ERR_OUT_OF_RANGE);
    check(&|u| u.ndir = 4, JOINTLIN_ERR_OUT_OF_RANGE);
    check(&|u| u.mcrd = 0, JOINTLIN_ERR_OUT_OF_RANGE);
    check(&|u| u.linper = 2, JOINTLIN_ERR_OUT_OF_RANGE);
    check(&|u| u.area = 0.0, JOINTLIN_ERR_OUT_OF_RANGE);
    check(&|u| u.area = -1.0, JOINTLIN_ERR_OUT_OF_RANGE);
    check(&|u| u.statev.truncate(56), JOINTLIN_ERR_SIZE);
    check(&|u| u.props.truncate(6), JOINTLIN_ERR_SIZE);
    check(&|u| u.props[0] = 2.0, JOINTLIN_ERR_PROPS); // law
    check(&|u| u.props[0] = 0.5, JOINTLIN_ERR_PROPS);
    check(&|u| u.props[1] = -1.0, JOINTLIN_ERR_PROPS); // rule
    check(&|u| u.props[2] = -0.3, JOINTLIN_ERR_PROPS); // μ < 0
    check(&|u| u.props[3] = 0.0, JOINTLIN_ERR_PROPS); // k_T0
    check(&|u| u.props[4] = 3.0, JOINTLIN_ERR_PROPS); // normal law
    check(&|u| u.props[5] = 0.0, JOINTLIN_ERR_PROPS); // k_N
    check(&|u| u.props.extend([1.0, 1.0]), JOINTLIN_ERR_PROPS); // k_T0 from Hertz needs Hertz
    check(&|u| u.props.extend([0.0, 0.0, 2.0]), JOINTLIN_ERR_PROPS); // damping code
    check(
        &|u| u.props.extend([0.0, 0.0, 0.0, 1.0, 3.0]),
        JOINTLIN_ERR_PROPS,
    ); // odd Simpson
    check(&|u| u.statev[5] = 9.0, JOINTLIN_ERR_OUT_OF_RANGE); // corrupt hysteresis tag
    check(
        &|u| {
            u.linper = 1;
            u.stress[0] = 2.0;
            u.freqr = 0.0;
        },
        JOINTLIN_ERR_OUT_OF_RANGE,
    );
    // LINPER = 1 outside an increment: the store's sequence error.
    check(
        &|u| {
            u.linper = 1;
            u.stress[0] = 2.0;
        },
        JOINTLIN_ERR_SEQUENCE,
    );
    // F_N ≤ 0 is an open contact: OK, zeros, never NaN.
    let mut u = closed_point();
    u.rdisp[0] = -1e-3;
    assert_eq!(u.call(store), JOINTLIN_OK);
    assert_eq!((u.stress, u.lopenclose), ([0.0; 3], 0));
    assert!(u.outputs().iter().all(|v| v.is_finite()));
    // μ = 0: closed, frictionless.
    let mut u = closed_point();
    u.props[2] = 0.0;
    assert_eq!(u.call(store), JOINTLIN_OK);
    assert_eq!((u.stress[1], u.ddsddr[4], u.lopenclose), (0.0, 0.0, 1));
    // Huge slips stay finite (sliding at μp).
    let mut u = closed_point();
    u.rdisp = [2e-4, 1e300, -1e300];
    assert_eq!(u.call(store), JOINTLIN_OK);
    assert!(u.outputs().iter().all(|v| v.is_finite()));
    unsafe { jointlin_store_free(store) };
}
