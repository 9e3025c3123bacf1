//! `jointlin_point_step_derivatives`: the time-domain point's step with the derivatives
//! of its state carried along (the tangent-linear step of `crate::hysteresis`), so a host
//! differentiates a marched slip history exactly, e.g. the Jacobian of an alternating
//! frequency–time harmonic balance, instead of marching it once per perturbed input.

use super::error::{boundary, FfiError, JOINTLIN_ERR_OUT_OF_RANGE, JOINTLIN_ERR_OVERFLOW};
use super::linearize::jointlin_contact;
use super::point::{jointlin_step, step_checked};
use super::{all_finite, check_ptr, finite, finite_all, load, load_finite, put, put_all};
use crate::hysteresis::{Tangents, FORCE_SLOT, STATE_LEN};

/// Largest number of derivative columns one call takes.
pub const JOINTLIN_POINT_DERIVATIVE_COLUMNS_MAX: usize = 4096;

/// Derivative rows of the state's slots, `columns` each, slot-major.
struct Rows<'a> {
    d: &'a mut [f64],
    d_slip: &'a [f64],
}

impl Tangents for Rows<'_> {
    fn set(&mut self, dst: usize, terms: &[(usize, f64)], target: f64) {
        let n = self.d_slip.len();
        for c in 0..n {
            let value = terms
                .iter()
                .fold(target * self.d_slip[c], |acc, &(slot, k)| {
                    acc + k * self.d[slot * n + c]
                });
            self.d[dst * n + c] = value;
        }
    }
}

/// `jointlin_point_step` that also carries derivatives with respect to `columns`
/// parameters: `d_state` holds the derivatives of the state's slots (slot-major: slot i's
/// derivative with respect to parameter c at `d_state[i * columns + c]`,
/// JOINTLIN_POINT_STATE_LEN × columns doubles; zeros for a virgin point), `d_slip` those
/// of `slip` (`columns` doubles). Writes the new state and its derivatives (`state_out`,
/// `d_state_out`, same layouts) and the step (`out`) with the derivatives of its force
/// (`d_force`, `columns` doubles).
///
/// The derivatives are those of the branch the step takes (elastic line, virgin curve,
/// Masing branch, with its anchors — reversal points, the zero-force point, the
/// sliding point — moving with the slips they came from), exact except where a step
/// ends exactly on a branch change. Chained over a path they give the derivative of every
/// force on it with respect to the slips. The same states as `jointlin_point_step`;
/// `state_out` may equal `state` and `d_state_out` may equal `d_state`.
///
/// `columns` may be 0 (then the derivative pointers are not read and may be NULL).
/// Errors: those of `jointlin_point_step`, JOINTLIN_ERR_NON_FINITE for NaN/Inf in
/// `d_state` or `d_slip`, JOINTLIN_ERR_OUT_OF_RANGE for `columns` above
/// JOINTLIN_POINT_DERIVATIVE_COLUMNS_MAX, JOINTLIN_ERR_OVERFLOW where a derivative is not
/// representable. Outputs are written only on JOINTLIN_OK.
///
/// # Safety
/// As `jointlin_point_step`; with `columns` > 0, `d_state` and `d_state_out` point to
/// JOINTLIN_POINT_STATE_LEN × `columns` doubles, `d_slip` and `d_force` to `columns`.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn jointlin_point_step_derivatives(
    contact: *const jointlin_contact,
    state: *const f64,
    d_state: *const f64,
    slip: f64,
    d_slip: *const f64,
    columns: usize,
    state_out: *mut f64,
    d_state_out: *mut f64,
    out: *mut jointlin_step,
    d_force: *mut f64,
) -> i32 {
    boundary("jointlin_point_step_derivatives", || {
        // SAFETY: pointers checked by the helpers; sizes by contract.
        let c = unsafe { load(contact, "contact") }?.to_core()?;
        let slots: [f64; STATE_LEN] = unsafe { load_finite(state, STATE_LEN, "state") }?;
        check_ptr(state_out, "state_out")?;
        check_ptr(out, "out")?;
        finite(slip, "slip")?;
        if columns > JOINTLIN_POINT_DERIVATIVE_COLUMNS_MAX {
            return Err(FfiError::new(
                JOINTLIN_ERR_OUT_OF_RANGE,
                format!("columns = {columns} above {JOINTLIN_POINT_DERIVATIVE_COLUMNS_MAX}"),
            ));
        }
        let (mut d, ds) = if columns == 0 {
            (Vec::new(), Vec::new())
        } else {
            for (p, what) in [(d_state, "d_state"), (d_slip, "d_slip")] {
                check_ptr(p, what)?;
            }
            check_ptr(d_state_out, "d_state_out")?;
            check_ptr(d_force, "d_force")?;
            // SAFETY: non-NULL, aligned (checked); sizes by contract; copied at once.
            unsafe {
                (
                    std::slice::from_raw_parts(d_state, STATE_LEN * columns).to_vec(),
                    std::slice::from_raw_parts(d_slip, columns).to_vec(),
                )
            }
        };
        finite_all(&d, "d_state")?;
        finite_all(&ds, "d_slip")?;
        let mut rows = Rows {
            d: &mut d,
            d_slip: &ds,
        };
        let Some((new_state, step)) = step_checked(&c, &slots, slip, &mut rows)? else {
            write_open(state_out, out, columns, d_state_out, d_force);
            return Ok(());
        };
        if !all_finite(&d) {
            return Err(FfiError::new(
                JOINTLIN_ERR_OVERFLOW,
                "the derivatives are not representable",
            ));
        }
        // SAFETY: all checked non-NULL and aligned; sizes by contract.
        unsafe {
            put_all(state_out, &new_state);
            put(out, step);
            if columns > 0 {
                put_all(d_state_out, &d);
                put_all(
                    d_force,
                    &d[FORCE_SLOT * columns..(FORCE_SLOT + 1) * columns],
                );
            }
        }
        Ok(())
    })
}

/// The outputs of a contact that carries no tangential force: all zeros (history and
/// derivatives reset).
fn write_open(
    state_out: *mut f64,
    out: *mut jointlin_step,
    columns: usize,
    d_state_out: *mut f64,
    d_force: *mut f64,
) {
    // SAFETY: the caller checked every pointer non-NULL and aligned; sizes by contract.
    unsafe {
        put_all(state_out, &[0.0; STATE_LEN]);
        put(out, jointlin_step::default());
        if columns > 0 {
            put_all(d_state_out, &vec![0.0; STATE_LEN * columns]);
            put_all(d_force, &vec![0.0; columns]);
        }
    }
}
