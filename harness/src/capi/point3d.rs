//! The three-direction contact point (`jointlin_point3d_step`, `jointlin_linearize3d`;
//! docs/contact3d.md) through the C API, with a per-thread step count: a unilateral
//! normal law and two tangential directions under one circular slip limit
//! ‖t‖ ≤ μ·N.

use std::cell::Cell;

use jointlin::ffi::point3d::{
    jointlin_contact3d, jointlin_linearization3d, jointlin_linearization3d_matrix,
    jointlin_linearize3d, jointlin_linearize3d_phasors, jointlin_point3d_step, jointlin_step3d,
    JOINTLIN_DESCRIBE_INTEGRATED, JOINTLIN_DESCRIBE_TABULATED, JOINTLIN_NORMAL_LINEAR,
    JOINTLIN_POINT3D_STATE_LEN,
};

use nalgebra::Complex;

use super::props::law_code;
use super::{check, CapiError};
use crate::names::LawName;

thread_local! {
    static POINT3D_STEPS: Cell<u64> = const { Cell::new(0) };
    static PHASOR_CALLS: Cell<u64> = const { Cell::new(0) };
}

/// Doubles in the state of a three-direction point.
pub const POINT3D_STATE_LEN: usize = JOINTLIN_POINT3D_STATE_LEN;

/// A three-direction point in force form: Jenkins (one cell) or Mindlin–Masing
/// (`cells` parallel Jenkins cells, 0 = the library's default), friction coefficient μ,
/// full-stick tangential stiffness k_T0 (force/length, both directions) and a linear
/// unilateral normal law N = k_N·h for overclosure h > 0, else 0 (k_N force/length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact3 {
    pub law: LawName,
    pub cells: i32,
    pub mu: f64,
    pub k_t0: f64,
    pub k_n: f64,
}

/// Mindlin–Masing cells of a three-direction Mindlin point (docs/contact3d.md §2: energy
/// of the straight-path loop within 0.27 % of the continuous law; Jenkins has one cell).
pub const MINDLIN_CELLS: i32 = 128;

impl Contact3 {
    /// The point of law `law` with [`MINDLIN_CELLS`] cells for Mindlin (one for Jenkins),
    /// friction coefficient μ, tangential and normal stiffness (force/length, or per area
    /// in stress form).
    pub fn new(law: LawName, mu: f64, k_t0: f64, k_n: f64) -> Self {
        let cells = if law == LawName::Mindlin {
            MINDLIN_CELLS
        } else {
            0
        };
        Contact3 {
            law,
            cells,
            mu,
            k_t0,
            k_n,
        }
    }

    fn c(&self) -> jointlin_contact3d {
        jointlin_contact3d {
            law: law_code(self.law),
            cells: self.cells,
            mu: self.mu,
            k_t0: self.k_t0,
            normal_law: JOINTLIN_NORMAL_LINEAR,
            normal_stiffness: self.k_n,
            r_star: 0.0,
        }
    }
}

/// One step of a three-direction point: forces (t₁, t₂ with the sign of the tangential
/// displacement; N ≥ 0, compression), their derivatives for continued motion (row-major,
/// rows t₁, t₂, N; columns u₁, u₂, h), the energy dissipated in the step and the regime.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Step3 {
    pub force: [f64; 3],
    pub stiffness: [f64; 9],
    pub dissipated: f64,
    pub regime: i32,
}

/// Moves a point from `state` to `disp` = (u₁, u₂, h) (tangential relative displacements
/// and overclosure, length); the new state goes to `state_out` (all zeros: a virgin
/// point).
pub fn point3d_step(
    c: &Contact3,
    state: &[f64; POINT3D_STATE_LEN],
    disp: [f64; 3],
    state_out: &mut [f64; POINT3D_STATE_LEN],
) -> Result<Step3, CapiError> {
    POINT3D_STEPS.with(|n| n.set(n.get() + 1));
    let contact = c.c();
    let mut out = jointlin_step3d::default();
    // SAFETY: contact, disp and out are valid locals; both states hold
    // JOINTLIN_POINT3D_STATE_LEN doubles.
    let code = unsafe {
        jointlin_point3d_step(
            &contact,
            state.as_ptr(),
            disp.as_ptr(),
            state_out.as_mut_ptr(),
            &mut out,
        )
    };
    check("jointlin_point3d_step", code)?;
    Ok(Step3 {
        force: out.force,
        stiffness: out.stiffness,
        dissipated: out.dissipated,
        regime: out.regime,
    })
}

/// `jointlin_linearize3d`: k* and d* per tangential direction (force/length,
/// force·time/length) and the energy per cycle (force·length) of the point at the
/// constant normal force `normal` (force) on the path u = (a₁ cos ωt, a₂ sin ωt).
pub fn linearize3d(
    c: &Contact3,
    normal: f64,
    amplitude: [f64; 2],
    omega: f64,
) -> Result<jointlin_linearization3d, CapiError> {
    let contact = c.c();
    let mut out = jointlin_linearization3d::default();
    // SAFETY: contact and out are valid locals.
    let code = unsafe {
        jointlin_linearize3d(
            &contact,
            normal,
            amplitude[0],
            amplitude[1],
            omega,
            &mut out,
        )
    };
    check("jointlin_linearize3d", code)?;
    Ok(out)
}

/// `jointlin_linearize3d_phasors`: the point at the constant normal force `normal`
/// (force) moving with the complex tangential amplitude `u` (length): first harmonic of
/// the force t̂ = (K* + iωD*) û, K* and D* symmetric, row-major (force/length,
/// force·time/length), the path's semi-axes and the energy per cycle (force·length).
/// `tabulated`: the unit cell's table (microseconds) instead of its integration.
pub fn linearize3d_phasors(
    c: &Contact3,
    normal: f64,
    u: [Complex<f64>; 2],
    omega: f64,
    tabulated: bool,
) -> Result<jointlin_linearization3d_matrix, CapiError> {
    PHASOR_CALLS.with(|n| n.set(n.get() + 1));
    let contact = c.c();
    let u_hat = [u[0].re, u[0].im, u[1].re, u[1].im];
    let method = if tabulated {
        JOINTLIN_DESCRIBE_TABULATED
    } else {
        JOINTLIN_DESCRIBE_INTEGRATED
    };
    let mut out = jointlin_linearization3d_matrix::default();
    // SAFETY: contact, u_hat and out are valid locals.
    let code = unsafe {
        jointlin_linearize3d_phasors(&contact, normal, u_hat.as_ptr(), omega, method, &mut out)
    };
    check("jointlin_linearize3d_phasors", code)?;
    Ok(out)
}

/// `jointlin_linearize3d_phasors` calls made on this thread so far.
pub fn phasor_calls() -> u64 {
    PHASOR_CALLS.with(|n| n.get())
}

/// `jointlin_point3d_step` calls made on this thread so far.
pub fn point3d_steps() -> u64 {
    POINT3D_STEPS.with(|n| n.get())
}
