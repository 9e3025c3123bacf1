//! The stateful time-domain point (`jointlin_point_step`, thesis §2.3.3) through the
//! C API, with a per-thread step count.

use std::cell::Cell;

use jointlin::ffi::point::{jointlin_point_step, jointlin_step, JOINTLIN_POINT_STATE_LEN};
use jointlin::ffi::point_tangents::jointlin_point_step_derivatives;

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

/// [`point_step`] carrying derivatives with respect to `d_slip.len()` parameters
/// (`jointlin_point_step_derivatives`): `d_state` and `d_state_out` hold the state slots'
/// derivatives slot-major (POINT_STATE_LEN × columns), `d_force` receives the force's.
/// Counted as a step.
pub fn point_step_derivatives(
    t: &Tangential,
    state: (&[f64; POINT_STATE_LEN], &[f64]),
    slip: (f64, &[f64]),
    state_out: (&mut [f64; POINT_STATE_LEN], &mut [f64]),
    d_force: &mut [f64],
) -> Result<PointStep, CapiError> {
    let columns = slip.1.len();
    assert!(
        state.1.len() == POINT_STATE_LEN * columns
            && state_out.1.len() == POINT_STATE_LEN * columns
            && d_force.len() == columns,
        "derivative arrays sized for {columns} columns"
    );
    POINT_STEPS.with(|c| c.set(c.get() + 1));
    let contact = c_contact(t);
    let mut out = jointlin_step::default();
    // SAFETY: contact and out are valid locals; the state arrays hold
    // JOINTLIN_POINT_STATE_LEN doubles, the derivative arrays the sizes asserted above.
    let code = unsafe {
        jointlin_point_step_derivatives(
            &contact,
            state.0.as_ptr(),
            state.1.as_ptr(),
            slip.0,
            slip.1.as_ptr(),
            columns,
            state_out.0.as_mut_ptr(),
            state_out.1.as_mut_ptr(),
            &mut out,
            d_force.as_mut_ptr(),
        )
    };
    check("jointlin_point_step_derivatives", code)?;
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
