//! `jointlin_point_step_derivatives` against central differences of `jointlin_point_step`
//! marched over the same slip paths: every force of a path of 400 steps (several
//! reversals, sliding, inner loops), both laws and both unloading rules, from a virgin
//! point and with several derivative columns at once.
//!
//! Run: `cargo test --release --test point_derivatives`.

use jointlin::ffi::error::{JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_OUT_OF_RANGE, JOINTLIN_OK};
use jointlin::ffi::linearize::*;
use jointlin::ffi::point::*;
use jointlin::ffi::point_tangents::*;

const N: usize = JOINTLIN_POINT_STATE_LEN;

fn contact(law: i32, rule: i32) -> jointlin_contact {
    jointlin_contact {
        law,
        rule,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1000.0,
    }
}

/// Slip limit δ* = 1.5 μF_N / k_T0 (2.46).
const DELTA_STAR: f64 = 1.5 * 0.3 * 2.0 / 1000.0;

/// A path with a drifting mean, two harmonics and a decaying inner loop, in units of δ*;
/// from step 200 on it repeats with period 25 (a sampled periodic slip with a mean, as a
/// harmonic balance marches: loops close exactly at earlier samples).
fn path(k: usize, amplitude: f64) -> f64 {
    if k >= 200 {
        let t = std::f64::consts::TAU * ((k - 200) % 25) as f64 / 25.0;
        return DELTA_STAR * amplitude * (0.1 + t.cos() + 0.3 * t.sin() + 0.2 * (2.0 * t).cos());
    }
    let t = k as f64 * 0.07;
    DELTA_STAR * (amplitude * (t.sin() + 0.35 * (3.1 * t + 0.4).cos()) + 0.05 * t.sin().powi(2))
}

/// The direction the parameters move the path in (column c).
fn direction(k: usize, c: usize) -> f64 {
    let k = if k >= 200 { 200 + (k - 200) % 25 } else { k };
    DELTA_STAR * ((0.13 * (k as f64) * (c + 1) as f64 + c as f64).cos())
}

/// Forces along the path δ_k + p·direction(k, 0).
fn forces(c: &jointlin_contact, amplitude: f64, p: f64) -> Vec<f64> {
    let mut state = [0.0; N];
    (0..400)
        .map(|k| {
            let mut step = jointlin_step::default();
            let mut next = [0.0; N];
            let slip = path(k, amplitude) + p * direction(k, 0);
            let code = unsafe {
                jointlin_point_step(c, state.as_ptr(), slip, next.as_mut_ptr(), &mut step)
            };
            assert_eq!(code, JOINTLIN_OK);
            state = next;
            step.force
        })
        .collect()
}

/// d(force_k)/dp for `columns` directions, marched with the derivative step.
fn derivatives(c: &jointlin_contact, amplitude: f64, columns: usize) -> Vec<Vec<f64>> {
    let mut state = [0.0; N];
    let mut d_state = vec![0.0; N * columns];
    (0..400)
        .map(|k| {
            let d_slip: Vec<f64> = (0..columns).map(|col| direction(k, col)).collect();
            let (mut next, mut d_next) = ([0.0; N], vec![0.0; N * columns]);
            let (mut step, mut d_force) = (jointlin_step::default(), vec![0.0; columns]);
            let code = unsafe {
                jointlin_point_step_derivatives(
                    c,
                    state.as_ptr(),
                    d_state.as_ptr(),
                    path(k, amplitude),
                    d_slip.as_ptr(),
                    columns,
                    next.as_mut_ptr(),
                    d_next.as_mut_ptr(),
                    &mut step,
                    d_force.as_mut_ptr(),
                )
            };
            assert_eq!(code, JOINTLIN_OK);
            (state, d_state) = (next, d_next);
            d_force
        })
        .collect()
}

#[test]
fn equal_central_differences_of_the_marched_path() {
    for (law, rule, name) in [
        (
            JOINTLIN_LAW_MINDLIN,
            JOINTLIN_RULE_THESIS,
            "Mindlin, thesis",
        ),
        (
            JOINTLIN_LAW_MINDLIN,
            JOINTLIN_RULE_MASING,
            "Mindlin, Masing",
        ),
        (
            JOINTLIN_LAW_JENKINS,
            JOINTLIN_RULE_THESIS,
            "Jenkins, thesis",
        ),
        (
            JOINTLIN_LAW_JENKINS,
            JOINTLIN_RULE_MASING,
            "Jenkins, Masing",
        ),
    ] {
        let c = contact(law, rule);
        // From microslip (a tenth of δ*) to gross sliding (three times δ*).
        for amplitude in [0.1, 0.6, 3.0] {
            let h = 1e-6;
            let (plus, minus) = (forces(&c, amplitude, h), forces(&c, amplitude, -h));
            let tl = derivatives(&c, amplitude, 3);
            let scale = 0.3 * 2.0;
            let mut worst = (0.0f64, 0);
            for k in 0..400 {
                let fd = (plus[k] - minus[k]) / (2.0 * h);
                let err = (tl[k][0] - fd).abs() / scale;
                if err > worst.0 {
                    worst = (err, k);
                }
            }
            // Central differences: truncation ~h² and round-off ~1e-16/h of μF_N.
            assert!(
                worst.0 < 1e-7,
                "{name}, A = {amplitude} δ*: derivative off by {:.2e} μF_N at step {} \
                 (derivative {:.6e}, differences {:.6e})",
                worst.0,
                worst.1,
                tl[worst.1][0],
                (plus[worst.1] - minus[worst.1]) / (2.0 * h)
            );
            // One column at a time gives the same as three together.
            let single = derivatives(&c, amplitude, 1);
            assert!((0..400).all(|k| single[k][0] == tl[k][0]), "{name}");
        }
    }
}

#[test]
fn bad_derivative_inputs_are_named_errors() {
    let c = contact(JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_MASING);
    let state = [0.0; N];
    let (mut next, mut step) = ([0.0; N], jointlin_step::default());
    let d_state = [f64::NAN; N];
    let (d_slip, mut d_next, mut d_force) = ([1.0], [7.0; N], [7.0]);
    let code = unsafe {
        jointlin_point_step_derivatives(
            &c,
            state.as_ptr(),
            d_state.as_ptr(),
            1e-4,
            d_slip.as_ptr(),
            1,
            next.as_mut_ptr(),
            d_next.as_mut_ptr(),
            &mut step,
            d_force.as_mut_ptr(),
        )
    };
    assert_eq!(code, JOINTLIN_ERR_NON_FINITE);
    assert_eq!(
        (d_next, d_force),
        ([7.0; N], [7.0]),
        "nothing written on error"
    );
    let code = unsafe {
        jointlin_point_step_derivatives(
            &c,
            state.as_ptr(),
            std::ptr::null(),
            1e-4,
            std::ptr::null(),
            JOINTLIN_POINT_DERIVATIVE_COLUMNS_MAX + 1,
            next.as_mut_ptr(),
            std::ptr::null_mut(),
            &mut step,
            std::ptr::null_mut(),
        )
    };
    assert_eq!(code, JOINTLIN_ERR_OUT_OF_RANGE);
    // No columns: the plain step, derivative pointers unread.
    let code = unsafe {
        jointlin_point_step_derivatives(
            &c,
            state.as_ptr(),
            std::ptr::null(),
            1e-4,
            std::ptr::null(),
            0,
            next.as_mut_ptr(),
            std::ptr::null_mut(),
            &mut step,
            std::ptr::null_mut(),
        )
    };
    assert_eq!(code, JOINTLIN_OK);
    let mut plain = jointlin_step::default();
    let mut plain_next = [0.0; N];
    unsafe {
        jointlin_point_step(
            &c,
            state.as_ptr(),
            1e-4,
            plain_next.as_mut_ptr(),
            &mut plain,
        )
    };
    assert_eq!((step, next), (plain, plain_next));
}

/// Slips from 1e-300 to 1e300 of the slip limit, and an open contact: finite outputs or
/// JOINTLIN_ERR_OVERFLOW, never a NaN; the open contact writes zeros everywhere.
#[test]
fn extreme_slips_and_open_contacts() {
    use jointlin::ffi::error::JOINTLIN_ERR_OVERFLOW;
    let step = |c: &jointlin_contact, slip: f64| {
        let (state, d_state, d_slip) = ([0.0; N], [0.5; N], [1.0]);
        let (mut next, mut d_next, mut out, mut d_force) =
            ([7.0; N], [7.0; N], jointlin_step::default(), [7.0]);
        let code = unsafe {
            jointlin_point_step_derivatives(
                c,
                state.as_ptr(),
                d_state.as_ptr(),
                slip,
                d_slip.as_ptr(),
                1,
                next.as_mut_ptr(),
                d_next.as_mut_ptr(),
                &mut out,
                d_force.as_mut_ptr(),
            )
        };
        (code, next, d_next, out, d_force)
    };
    for (law, rule) in [
        (JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS),
        (JOINTLIN_LAW_JENKINS, JOINTLIN_RULE_MASING),
    ] {
        let c = contact(law, rule);
        for e in [-300, -100, -1, 0, 1, 100, 300] {
            for sign in [1.0, -1.0] {
                let slip = sign * DELTA_STAR * 10f64.powi(e);
                let (code, next, d_next, out, d_force) = step(&c, slip);
                match code {
                    JOINTLIN_OK => {
                        let all = next.iter().chain(&d_next).chain(&d_force);
                        assert!(all.clone().all(|v| v.is_finite()), "{slip:e}");
                        assert!(out.force.is_finite() && out.force.abs() <= 0.3 * 2.0);
                    }
                    JOINTLIN_ERR_OVERFLOW => assert_eq!(d_force, [7.0], "nothing written"),
                    other => panic!("{slip:e}: status {other}"),
                }
            }
        }
        let open = jointlin_contact {
            normal_force: 0.0,
            ..c
        };
        let (code, next, d_next, out, d_force) = step(&open, 1e-3);
        assert_eq!(code, JOINTLIN_OK);
        assert_eq!((next, d_next, d_force), ([0.0; N], [0.0; N], [0.0]));
        assert_eq!(out, jointlin_step::default());
    }
}
