//! `jointlin_screw_preload`: the preload of a screw from its tightening torque (VDI 2230),
//! for hosts that replace the screw by point forces in a static step (thesis §5.4.1).

use super::error::boundary;
use super::{check_ptr, put};
use crate::law::screw::preload_from_torque;

/// Writes to `*preload` the axial force F (force) of a screw tightened to `torque` T
/// (force x length): F = T / (0.16 P + 0.58 d2 mu_thread + d_km/2 mu_head) (VDI 2230,
/// R13). Lengths in one unit: thread pitch `pitch` P > 0, flank diameter `d2` > 0,
/// effective head bearing diameter `d_km` >= 0; friction coefficients >= 0; T >= 0.
///
/// On JOINTLIN_OK the preload is finite and >= 0 for any finite inputs: the lever and the
/// quotient are formed without intermediate overflow or underflow (P = 5e-324 or
/// d2 mu_thread = 1e400 keep their value); a preload beyond DBL_MAX is
/// JOINTLIN_ERR_OVERFLOW, never Inf or NaN.
///
/// Errors: JOINTLIN_ERR_NULL (`preload` NULL), JOINTLIN_ERR_NON_FINITE,
/// JOINTLIN_ERR_OUT_OF_RANGE, JOINTLIN_ERR_OVERFLOW. `*preload` is written only on
/// JOINTLIN_OK.
///
/// # Safety
/// `preload` must be NULL or point to a writable double.
#[no_mangle]
pub unsafe extern "C" fn jointlin_screw_preload(
    torque: f64,
    pitch: f64,
    d2: f64,
    mu_thread: f64,
    mu_head: f64,
    d_km: f64,
    preload: *mut f64,
) -> i32 {
    boundary("jointlin_screw_preload", || {
        check_ptr(preload, "preload")?;
        let f = preload_from_torque(torque, pitch, d2, mu_thread, mu_head, d_km)?;
        // SAFETY: checked non-NULL and aligned; writable by contract.
        unsafe { put(preload, f) };
        Ok(())
    })
}
