//! jointlin_linearize (and jointlin_point_step on the same contact) with arbitrary
//! contacts, amplitudes, frequencies, methods and NULLs. Properties: status never
//! JOINTLIN_ERR_PANIC; on JOINTLIN_OK every output finite, 0 <= k* <= k_T0, d*, eta,
//! energy >= 0, a known regime; on an error nothing written.

#![cfg_attr(not(feature = "replay"), no_main)]

#[path = "../src/common.rs"]
mod common;

use arbitrary::{Arbitrary, Unstructured};
use common::*;
use jointlin::ffi::linearize::*;
use jointlin::ffi::point::*;

#[derive(Debug, Arbitrary)]
struct Input {
    law: i32,
    rule: i32,
    mu: F,
    normal_force: F,
    k_t0: F,
    amplitude: Near,
    omega: F,
    method: Option<(u8, i32)>,
    null_contact: bool,
    null_out: bool,
    /// Slips for jointlin_point_step, relative to δ* = 1.5 μ F_N / k_T0.
    slips: Vec<Near>,
    state: Option<[F; 23]>,
}

fn run(data: &[u8]) {
    let Ok(input) = Input::arbitrary(&mut Unstructured::new(data)) else {
        return;
    };
    // Codes: mostly valid, sometimes anything.
    let code = |c: i32| {
        if (-2..4).contains(&c) {
            c.rem_euclid(2)
        } else {
            c
        }
    };
    let contact = jointlin_contact {
        law: code(input.law),
        rule: code(input.rule),
        mu: input.mu.get(),
        normal_force: input.normal_force.get(),
        k_t0: input.k_t0.get(),
    };
    let delta = 1.5 * contact.mu * contact.normal_force / contact.k_t0;
    let amplitude = input.amplitude.around(delta);
    let omega = input.omega.get();
    let method = input.method.map(|(k, p)| jointlin_method {
        kind: i32::from(k % 4),
        points: p,
    });
    if let Some(m) = method {
        // Up to 2^26 Simpson intervals is valid but takes seconds per call; cap the work.
        if m.kind == JOINTLIN_METHOD_SIMPSON && m.points > 1 << 14 {
            return;
        }
    }
    let sentinel = jointlin_linearization {
        k_star: -7.0,
        d_star: -7.0,
        eta: -7.0,
        energy_per_cycle: -7.0,
        peak_force: -7.0,
        slip_limit: -7.0,
        amplitude_ratio: -7.0,
        regime: -7,
    };
    let mut out = sentinel;
    let status = unsafe {
        jointlin_linearize(
            if input.null_contact {
                std::ptr::null()
            } else {
                &contact
            },
            amplitude,
            omega,
            method.as_ref().map_or(std::ptr::null(), |m| m as *const _),
            if input.null_out {
                std::ptr::null_mut()
            } else {
                &mut out
            },
        )
    };
    assert_status("jointlin_linearize", status);
    if status == 0 {
        let l = out;
        assert_finite(
            "linearization",
            &[
                l.k_star,
                l.d_star,
                l.eta,
                l.energy_per_cycle,
                l.peak_force,
                l.slip_limit,
                l.amplitude_ratio,
            ],
        );
        assert!(
            l.k_star >= 0.0 && l.k_star <= contact.k_t0 * (1.0 + 1e-12),
            "{contact:?} A={amplitude:e} {l:?}"
        );
        assert!(
            l.d_star >= 0.0 && l.eta >= 0.0 && l.energy_per_cycle >= 0.0,
            "{l:?}"
        );
        assert!((0..=3).contains(&l.regime), "{l:?}");
    } else {
        assert_eq!(out, sentinel, "written on error {status}");
    }

    // The time-domain point on the same contact.
    let mut state = [0.0f64; 23];
    if let Some(s) = input.state {
        for (x, f) in state.iter_mut().zip(s) {
            *x = f.get();
        }
    }
    for slip in input.slips.iter().take(64) {
        let s = slip.around(delta);
        let mut next = [-7.0f64; 23];
        let mut step = jointlin_step {
            force: -7.0,
            tangent: -7.0,
            dissipated: -7.0,
        };
        let status = unsafe {
            jointlin_point_step(&contact, state.as_ptr(), s, next.as_mut_ptr(), &mut step)
        };
        assert_status("jointlin_point_step", status);
        if status != 0 {
            assert!(next.iter().all(|&x| x == -7.0) && step.force == -7.0);
            break;
        }
        assert_finite("step", &[step.force, step.tangent, step.dissipated]);
        assert_finite("state", &next);
        assert!(step.tangent >= 0.0 && step.dissipated >= 0.0, "{step:?}");
        state = next;
    }
}

#[cfg(not(feature = "replay"))]
libfuzzer_sys::fuzz_target!(|data: &[u8]| run(data));

#[cfg(feature = "replay")]
fn main() {
    replay_main(run);
}
