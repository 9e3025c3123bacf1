//! Hard inputs of the three-direction point's C API: NULL in every pointer argument,
//! NaN/±∞ in every input, corrupt and foreign states, misaligned pointers and displacements
//! too large to represent give named status codes and leave every output untouched; the
//! state may be updated in place.

use jointlin::ffi::error::*;
use jointlin::ffi::linearize::{JOINTLIN_LAW_JENKINS, JOINTLIN_LAW_MINDLIN};
use jointlin::ffi::point3d::*;
use std::ptr::{null, null_mut};

const BAD: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
const SENTINEL: f64 = 12345.0;
const LEN: usize = JOINTLIN_POINT3D_STATE_LEN;

fn mindlin() -> jointlin_contact3d {
    jointlin_contact3d {
        law: JOINTLIN_LAW_MINDLIN,
        cells: 8,
        mu: 0.3,
        k_t0: 1282.7,
        normal_law: JOINTLIN_NORMAL_HERTZ,
        normal_stiffness: 1.15e5,
        r_star: 5.0,
    }
}

fn sentinel_step() -> jointlin_step3d {
    jointlin_step3d {
        force: [SENTINEL; 3],
        stiffness: [SENTINEL; 9],
        dissipated: SENTINEL,
        regime: -1,
    }
}

/// Calls step and checks that a failing call wrote nothing.
fn step_fails(c: &jointlin_contact3d, state: &[f64; LEN], disp: &[f64; 3], code: i32) {
    let mut next = [SENTINEL; LEN];
    let mut out = sentinel_step();
    let rc = unsafe {
        jointlin_point3d_step(
            c,
            state.as_ptr(),
            disp.as_ptr(),
            next.as_mut_ptr(),
            &mut out,
        )
    };
    assert_eq!(rc, code, "{c:?} {disp:?}");
    assert_eq!(out, sentinel_step());
    assert!(next.iter().all(|&v| v == SENTINEL));
}

#[test]
fn step_rejects_null_non_finite_and_corrupt_inputs_without_writing() {
    let c = mindlin();
    let state = [0.0; LEN];
    let disp = [1e-4, -2e-4, 1e-3];
    let mut next = [SENTINEL; LEN];
    let mut out = sentinel_step();
    unsafe {
        let (s, d, n) = (state.as_ptr(), disp.as_ptr(), next.as_mut_ptr());
        assert_eq!(
            jointlin_point3d_step(null(), s, d, n, &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_point3d_step(&c, null(), d, n, &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_point3d_step(&c, s, null(), n, &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_point3d_step(&c, s, d, null_mut(), &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_point3d_step(&c, s, d, n, null_mut()),
            JOINTLIN_ERR_NULL
        );
        // Misaligned state pointer.
        let bytes = [0u8; 8 * (LEN + 1)];
        let odd = bytes.as_ptr().add(1).cast::<f64>();
        assert_eq!(
            jointlin_point3d_step(&c, odd, d, n, &mut out),
            JOINTLIN_ERR_OUT_OF_RANGE
        );
    }
    assert_eq!(out, sentinel_step());
    assert!(next.iter().all(|&v| v == SENTINEL));
    for bad in BAD {
        for i in 0..3 {
            let mut d = disp;
            d[i] = bad;
            step_fails(&c, &state, &d, JOINTLIN_ERR_NON_FINITE);
        }
        for i in [0, 1, 3, 4, 5, LEN - 1] {
            let mut s = state;
            s[i] = bad;
            step_fails(&c, &s, &disp, JOINTLIN_ERR_NON_FINITE);
        }
        for field in 0..4 {
            let mut cb = c;
            match field {
                0 => cb.mu = bad,
                1 => cb.k_t0 = bad,
                2 => cb.normal_stiffness = bad,
                _ => cb.r_star = bad,
            }
            step_fails(&cb, &state, &disp, JOINTLIN_ERR_NON_FINITE);
        }
    }
    // Out-of-range data and states: named codes.
    for cb in [
        jointlin_contact3d { mu: -0.1, ..c },
        jointlin_contact3d { k_t0: 0.0, ..c },
        jointlin_contact3d {
            normal_stiffness: -1.0,
            ..c
        },
        jointlin_contact3d { r_star: 0.0, ..c },
        jointlin_contact3d { cells: -1, ..c },
        jointlin_contact3d {
            cells: JOINTLIN_POINT3D_MAX_CELLS + 1,
            ..c
        },
        jointlin_contact3d {
            law: JOINTLIN_LAW_JENKINS,
            cells: 8,
            ..c
        },
        jointlin_contact3d { normal_law: 9, ..c },
    ] {
        step_fails(&cb, &state, &disp, JOINTLIN_ERR_OUT_OF_RANGE);
    }
    // A state written for 8 cells read by a 4-cell contact, and trailing garbage.
    let mut written = [0.0; LEN];
    let mut out = jointlin_step3d::default();
    let rc = unsafe {
        jointlin_point3d_step(
            &c,
            state.as_ptr(),
            disp.as_ptr(),
            written.as_mut_ptr(),
            &mut out,
        )
    };
    assert_eq!(rc, JOINTLIN_OK);
    step_fails(
        &jointlin_contact3d { cells: 4, ..c },
        &written,
        &disp,
        JOINTLIN_ERR_OUT_OF_RANGE,
    );
    let mut garbage = written;
    garbage[LEN - 1] = 1.0;
    step_fails(&c, &garbage, &disp, JOINTLIN_ERR_OUT_OF_RANGE);
    let mut negative = written;
    negative[4] = -1.0;
    step_fails(&c, &negative, &disp, JOINTLIN_ERR_OUT_OF_RANGE);
    // Displacements whose forces overflow: a named code, not ∞.
    step_fails(&c, &state, &[1.5e308, 0.0, 1e-3], JOINTLIN_ERR_OVERFLOW);
    step_fails(&c, &state, &[0.0, 0.0, 1e250], JOINTLIN_ERR_OVERFLOW);
}

#[test]
fn step_in_place_and_at_the_edges_of_contact() {
    let c = mindlin();
    let mut s = [0.0; LEN];
    let mut out = jointlin_step3d::default();
    for (disp, open) in [
        ([1e-4, 0.0, 1e-3], false),
        ([2e-4, 1e-4, 0.0], true),
        ([2e-4, 1e-4, -1.0], true),
        ([2e-4, 1e-4, 1e-200], false),
        ([3e-4, 1e-4, 1e-3], false),
    ] {
        let p = s.as_mut_ptr();
        let rc = unsafe { jointlin_point3d_step(&c, p, disp.as_ptr(), p, &mut out) };
        assert_eq!(rc, JOINTLIN_OK);
        assert!(out
            .force
            .iter()
            .chain(&out.stiffness)
            .all(|v| v.is_finite()));
        assert!(out.dissipated >= 0.0);
        assert_eq!(
            out.regime == jointlin::ffi::linearize::JOINTLIN_REGIME_OPEN,
            open
        );
        let t = out.force[0].hypot(out.force[1]);
        assert!(t <= 0.3 * out.force[2] * (1.0 + 1e-12));
    }
    assert_eq!(s[0], 8.0);
}

#[test]
fn linearize3d_rejects_null_and_bad_inputs_without_writing() {
    let c = mindlin();
    let keep = jointlin_linearization3d {
        k_star: [SENTINEL; 2],
        d_star: [SENTINEL; 2],
        energy_per_cycle: SENTINEL,
        regime: -1,
    };
    let mut out = keep;
    unsafe {
        assert_eq!(
            jointlin_linearize3d(null(), 1.0, 1e-4, 1e-4, 1.0, &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_linearize3d(&c, 1.0, 1e-4, 1e-4, 1.0, null_mut()),
            JOINTLIN_ERR_NULL
        );
        for bad in BAD {
            for args in [
                (bad, 1e-4, 1e-4, 1.0),
                (1.0, bad, 1e-4, 1.0),
                (1.0, 1e-4, bad, 1.0),
                (1.0, 1e-4, 1e-4, bad),
            ] {
                let rc = jointlin_linearize3d(&c, args.0, args.1, args.2, args.3, &mut out);
                assert_eq!(rc, JOINTLIN_ERR_NON_FINITE, "{args:?}");
            }
        }
        for args in [
            (1.0, -1e-4, 1e-4, 1.0),
            (1.0, 1e-4, 1e-4, 0.0),
            (1.0, 1e-4, 1e-4, -2.0),
        ] {
            let rc = jointlin_linearize3d(&c, args.0, args.1, args.2, args.3, &mut out);
            assert_eq!(rc, JOINTLIN_ERR_OUT_OF_RANGE, "{args:?}");
        }
        // d* not representable at a subnormal frequency.
        let rc = jointlin_linearize3d(&c, 1.0, 1e-3, 1e-3, 1e-320, &mut out);
        assert_eq!(rc, JOINTLIN_ERR_OVERFLOW);
    }
    assert_eq!(out, keep);
}

#[test]
fn linearize3d_phasors_rejects_null_and_bad_inputs_without_writing() {
    let c = mindlin();
    let keep = jointlin_linearization3d_matrix {
        k_star: [SENTINEL; 4],
        d_star: [SENTINEL; 4],
        semi_axes: [SENTINEL; 2],
        angle: SENTINEL,
        energy_per_cycle: SENTINEL,
        regime: -1,
    };
    let mut out = keep;
    let u = [1e-4, 2e-5, -3e-5, 5e-5];
    let tab = JOINTLIN_DESCRIBE_TABULATED;
    unsafe {
        assert_eq!(
            jointlin_linearize3d_phasors(null(), 1.0, u.as_ptr(), 1.0, tab, &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_linearize3d_phasors(&c, 1.0, null(), 1.0, tab, &mut out),
            JOINTLIN_ERR_NULL
        );
        assert_eq!(
            jointlin_linearize3d_phasors(&c, 1.0, u.as_ptr(), 1.0, tab, null_mut()),
            JOINTLIN_ERR_NULL
        );
        for bad in BAD {
            for k in 0..4 {
                let mut v = u;
                v[k] = bad;
                let rc = jointlin_linearize3d_phasors(&c, 1.0, v.as_ptr(), 1.0, tab, &mut out);
                assert_eq!(rc, JOINTLIN_ERR_NON_FINITE, "{v:?}");
            }
            let rc = jointlin_linearize3d_phasors(&c, bad, u.as_ptr(), 1.0, tab, &mut out);
            assert_eq!(rc, JOINTLIN_ERR_NON_FINITE);
            let rc = jointlin_linearize3d_phasors(&c, 1.0, u.as_ptr(), bad, tab, &mut out);
            assert_eq!(rc, JOINTLIN_ERR_NON_FINITE);
        }
        for (omega, method) in [(0.0, tab), (-1.0, tab), (1.0, 2), (1.0, -1)] {
            let rc = jointlin_linearize3d_phasors(&c, 1.0, u.as_ptr(), omega, method, &mut out);
            assert_eq!(rc, JOINTLIN_ERR_OUT_OF_RANGE, "{omega} {method}");
        }
    }
    assert_eq!(out, keep);
    // Both methods on the same path: symmetric matrices, the same energy within the
    // table's tolerance (8 cells: 8 × 2e-3 of μN times the perimeter at most).
    let mut both = [keep; 2];
    for (m, o) in [JOINTLIN_DESCRIBE_INTEGRATED, tab]
        .into_iter()
        .zip(&mut both)
    {
        let rc = unsafe { jointlin_linearize3d_phasors(&c, 1.0, u.as_ptr(), 1.0, m, o) };
        assert_eq!(rc, JOINTLIN_OK);
        assert_eq!(o.k_star[1], o.k_star[2]);
        assert_eq!(o.d_star[1], o.d_star[2]);
    }
    let perimeter = 2.0 * std::f64::consts::PI * both[0].semi_axes[0];
    assert!((both[0].energy_per_cycle - both[1].energy_per_cycle).abs() < 2e-3 * 0.3 * perimeter);
}
