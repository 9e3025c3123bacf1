//! `jointlin_point_step`: the stateful time-domain hysteresis point (thesis §2.3.3,
//! Fig. 2.16/2.17) for hosts that integrate in time themselves (not Abaqus).

use super::error::{boundary, FfiError, FfiResult, JOINTLIN_ERR_OVERFLOW};
use super::linearize::jointlin_contact;
use super::{all_finite, check_ptr, finite, load, load_finite, put, put_all};
use crate::hysteresis::{NoTangents, PointState, Tangents, STATE_LEN};
use crate::linearize::Contact;

/// Number of doubles in the state of one tangential direction of a point.
pub const JOINTLIN_POINT_STATE_LEN: usize = 23;
const _: () = assert!(JOINTLIN_POINT_STATE_LEN == STATE_LEN);

/// Result of one slip increment.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct jointlin_step {
    /// Tangential force (or stress) at the new slip; its sign is the slip's direction
    /// (positive stiffness convention).
    pub force: f64,
    /// dForce/dSlip for continued motion in the last direction (>= 0).
    pub tangent: f64,
    /// Energy dissipated during the increment (>= 0, force x length).
    pub dissipated: f64,
}

/// One step of `c`'s point from the stored state `slots` to `slip`, moving `tangents`
/// along: the new state and the step, checked representable; `None` for a contact that
/// carries no tangential force (open or frictionless: the caller writes zeros).
pub(super) fn step_checked(
    c: &Contact,
    slots: &[f64; STATE_LEN],
    slip: f64,
    tangents: &mut impl Tangents,
) -> FfiResult<Option<([f64; STATE_LEN], jointlin_step)>> {
    let Some(point) = c.point()? else {
        return Ok(None);
    };
    let st = PointState::read(slots, point.rule, 0.0)?;
    let (next, r) = point.step_with_tangents(&st, slip, tangents)?;
    let mut buf = [0.0; STATE_LEN];
    next.write(&mut buf);
    let step = jointlin_step {
        force: r.force,
        tangent: r.tangent,
        dissipated: r.dissipated,
    };
    if !(all_finite(&buf) && all_finite(&[step.force, step.tangent, step.dissipated])) {
        return Err(FfiError::new(
            JOINTLIN_ERR_OVERFLOW,
            "slip too large: the state is not representable",
        ));
    }
    Ok(Some((buf, step)))
}

/// Moves one tangential direction of a contact point from the state `state` to the slip
/// `slip` (length) and returns the force, tangent and dissipated energy, writing the new
/// state to `state_out`. Both state arrays hold JOINTLIN_POINT_STATE_LEN doubles; an
/// all-zero state is a virgin point at slip 0. `state_out` may equal `state`. The function
/// is pure (no hidden state), so trial steps (Newton iterations, Runge–Kutta stages) may be
/// evaluated and only accepted states kept.
///
/// An open contact (normal_force <= 0) or mu = 0 carries no tangential force: `out` is all
/// zeros and `state_out` is all zeros (history reset).
///
/// No pointer may be NULL. Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_NON_FINITE (NaN/Inf in
/// the contact, the state or `slip`), JOINTLIN_ERR_OUT_OF_RANGE (unknown codes, mu < 0,
/// k_t0 <= 0, a state written for another rule or corrupt). Outputs are written only on
/// JOINTLIN_OK.
///
/// # Safety
/// `contact` must point to a valid contact, `state` and `state_out` to
/// JOINTLIN_POINT_STATE_LEN doubles each, `out` to a writable jointlin_step.
#[no_mangle]
pub unsafe extern "C" fn jointlin_point_step(
    contact: *const jointlin_contact,
    state: *const f64,
    slip: f64,
    state_out: *mut f64,
    out: *mut jointlin_step,
) -> i32 {
    boundary("jointlin_point_step", || {
        // SAFETY: pointers checked by the helpers; sizes by contract.
        let c = unsafe { load(contact, "contact") }?.to_core()?;
        let slots: [f64; STATE_LEN] = unsafe { load_finite(state, STATE_LEN, "state") }?;
        check_ptr(state_out, "state_out")?;
        check_ptr(out, "out")?;
        finite(slip, "slip")?;
        let (new_state, step) =
            step_checked(&c, &slots, slip, &mut NoTangents)?.unwrap_or_default();
        // SAFETY: both checked non-NULL and aligned; sizes by contract.
        unsafe {
            put_all(state_out, &new_state);
            put(out, step);
        }
        Ok(())
    })
}
