//! The stateful time-domain point (`jointlin_point_step`, thesis §2.3.3) through the
//! C API, with a per-thread step count.

use std::cell::Cell;

use jointlin::ffi::point::{jointlin_point_step, jointlin_step, JOINTLIN_POINT_STATE_LEN};

use super::linearize::{c_contact, Tangential};
use super::{check, CapiError};

thread_local! {
    static POINT_STEPS: Cell<u64> = const { Cell::new(0) };
}

/// Doubles in the state of one tangential direction of a time-domain point.
pub const POINT_STATE_LEN: usize = JOINTLIN_POINT_STATE_LEN;

/// `jointlin_point_step` output: force (sign of the slip), tangent dF/dslip for continued
/// motion (>= 0), energy dissipated in the increment.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointStep {
    pub force: f64,
    pub tangent: f64,
    pub dissipated: f64,
}

/// Moves one tangential direction of a point from `state` to `slip` (`jointlin_point_step`,
/// the stateful hysteresis of thesis §2.3.3); the new state goes to `state_out` (an
/// all-zero state is a virgin point at slip 0).
pub fn point_step(
    t: &Tangential,
    state: &[f64; POINT_STATE_LEN],
    slip: f64,
    state_out: &mut [f64; POINT_STATE_LEN],
) -> Result<PointStep, CapiError> {
    POINT_STEPS.with(|c| c.set(c.get() + 1));
    let contact = c_contact(t);
    let mut out = jointlin_step::default();
    // SAFETY: contact and out are valid locals; both state arrays hold
    // JOINTLIN_POINT_STATE_LEN doubles.
    let code = unsafe {
        jointlin_point_step(
            &contact,
            state.as_ptr(),
            slip,
            state_out.as_mut_ptr(),
            &mut out,
        )
    };
    check("jointlin_point_step", code)?;
    Ok(PointStep {
        force: out.force,
        tangent: out.tangent,
        dissipated: out.dissipated,
    })
}

/// `jointlin_point_step` calls made on this thread so far.
pub fn point_steps() -> u64 {
    POINT_STEPS.with(|c| c.get())
}
