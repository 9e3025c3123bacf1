//! Linearization of one tangential direction (`jointlin_linearize`, (3.14)), the cubic
//! spring's equivalent stiffness and force, and the screw preload, through the C API.

use std::ptr;

use jointlin::ffi::cubic::{
    jointlin_cubic_force, jointlin_cubic_linearization, jointlin_linearize_cubic,
};
use jointlin::ffi::linearize::{
    jointlin_contact, jointlin_linearization, jointlin_linearize, jointlin_method,
};
use jointlin::ffi::screw::jointlin_screw_preload;

use super::props::{law_code, rule_code};
use super::{check, count, CapiError, QUADRATURE};
use crate::names::{LawName, RuleName};

/// One point's tangential data for [`linearize`] (stress form: normal "force" = pressure,
/// k_T0 per area; results are then per area too).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    pub law: LawName,
    pub rule: RuleName,
    pub mu: f64,
    /// Normal pressure (or force), positive in compression.
    pub normal: f64,
    pub k_t0: f64,
}

/// `jointlin_linearize` output.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Linearized {
    pub k_star: f64,
    pub d_star: f64,
    pub eta: f64,
    pub energy_per_cycle: f64,
    pub slip_limit: f64,
    pub amplitude_ratio: f64,
    pub regime: i32,
}

/// Preload (force) of a screw tightened to `torque` (force·length) by the library's
/// screw formula (VDI 2230); lengths in one unit.
pub fn screw_preload(
    torque: f64,
    pitch: f64,
    d2: f64,
    mu_thread: f64,
    mu_head: f64,
    d_km: f64,
) -> Result<f64, CapiError> {
    let mut f = 0.0;
    // SAFETY: f is a valid local.
    let code =
        unsafe { jointlin_screw_preload(torque, pitch, d2, mu_thread, mu_head, d_km, &mut f) };
    check("jointlin_screw_preload", code)?;
    Ok(f)
}

/// The C description of a point's tangential law.
pub(super) fn c_contact(t: &Tangential) -> jointlin_contact {
    jointlin_contact {
        law: law_code(t.law),
        rule: rule_code(t.rule),
        mu: t.mu,
        normal_force: t.normal,
        k_t0: t.k_t0,
    }
}

/// k*, d*, η, energy per cycle, δ*, A/δ*, regime of one point for amplitude A (length)
/// at ω (rad/time), default quadrature.
pub fn linearize(t: &Tangential, amplitude: f64, omega: f64) -> Result<Linearized, CapiError> {
    count(|c| c.linearize += 1);
    let contact = c_contact(t);
    let mut out = jointlin_linearization {
        k_star: 0.0,
        d_star: 0.0,
        eta: 0.0,
        energy_per_cycle: 0.0,
        peak_force: 0.0,
        slip_limit: 0.0,
        amplitude_ratio: 0.0,
        regime: 0,
    };
    let method = QUADRATURE.with(|c| c.get()).map(|q| {
        let (kind, points) = q.code();
        jointlin_method { kind, points }
    });
    let mptr = method
        .as_ref()
        .map_or(ptr::null(), |m| m as *const jointlin_method);
    // SAFETY: contact and out are valid locals; method NULL = default, else a local.
    let code = unsafe { jointlin_linearize(&contact, amplitude, omega, mptr, &mut out) };
    check("jointlin_linearize", code)?;
    Ok(Linearized {
        k_star: out.k_star,
        d_star: out.d_star,
        eta: out.eta,
        energy_per_cycle: out.energy_per_cycle,
        slip_limit: out.slip_limit,
        amplitude_ratio: out.amplitude_ratio,
        regime: out.regime,
    })
}

/// k* (force/length) of the cubic spring F(x) = k·x + α·x³ for the amplitude A (length)
/// by first-order harmonic balance (`jointlin_linearize_cubic`, thesis (3.8)); its d* is 0.
pub fn linearize_cubic(k: f64, alpha: f64, amplitude: f64) -> Result<f64, CapiError> {
    count(|c| c.linearize_cubic += 1);
    let mut out = jointlin_cubic_linearization {
        k_star: 0.0,
        d_star: 0.0,
        energy_per_cycle: 0.0,
    };
    // SAFETY: out is a writable local.
    let code = unsafe { jointlin_linearize_cubic(k, alpha, amplitude, &mut out) };
    check("jointlin_linearize_cubic", code)?;
    Ok(out.k_star)
}

/// Force (force units) and tangent (force/length) of the cubic spring F = k·x + α·x³ at
/// the elongation x, through `jointlin_cubic_force`.
pub fn cubic_force(k: f64, alpha: f64, x: f64) -> Result<(f64, f64), CapiError> {
    let (mut force, mut tangent) = (0.0, 0.0);
    // SAFETY: both are writable locals.
    let code = unsafe { jointlin_cubic_force(k, alpha, x, &mut force, &mut tangent) };
    check("jointlin_cubic_force", code)?;
    Ok((force, tangent))
}
