//! `jointlin_linearize_cubic`: the equivalent stiffness and damping of a cubic (Duffing)
//! spring F(x) = k·x + α·x³ (4.1) for one amplitude, by first-order harmonic balance (3.8)
//! and energy balance (3.14); `jointlin_cubic_force`: its force and tangent at one
//! elongation (for hosts that march it in time or by alternating frequency–time balance).

use super::error::boundary;
use super::{check_ptr, put};
use crate::law::CubicSpring;
use crate::linearize::cubic::linearize_cubic;

/// The linearized cubic spring.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct jointlin_cubic_linearization {
    /// Equivalent stiffness k* = k + 3/4 alpha A^2 (3.8) (force/length; negative for a
    /// softening spring, alpha < 0, beyond A^2 = -4k/(3 alpha)).
    pub k_star: f64,
    /// Equivalent viscous damping d* (3.14): 0, the spring is elastic.
    pub d_star: f64,
    /// Energy dissipated per cycle: 0 (force x length).
    pub energy_per_cycle: f64,
}

/// Linearizes the cubic spring F(x) = k_lin x + alpha x^3 (k_lin force/length, alpha
/// force/length^3, any finite signs) for the displacement amplitude A = `amplitude`
/// (length, A >= 0) of x = A sin(omega t): k* = k_lin + 3/4 alpha A^2 by first-order
/// harmonic balance (3.8), d* = 0 and no energy per cycle by energy balance (3.14), at
/// every frequency.
///
/// `out` must not be NULL. Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_NON_FINITE (any NaN/Inf
/// input), JOINTLIN_ERR_OUT_OF_RANGE (amplitude < 0, misaligned `out`),
/// JOINTLIN_ERR_OVERFLOW (k* not representable). `*out` is written only on JOINTLIN_OK.
///
/// # Safety
/// A non-NULL `out` must point to a valid, aligned, writable jointlin_cubic_linearization.
#[no_mangle]
pub unsafe extern "C" fn jointlin_linearize_cubic(
    k_lin: f64,
    alpha: f64,
    amplitude: f64,
    out: *mut jointlin_cubic_linearization,
) -> i32 {
    boundary("jointlin_linearize_cubic", || {
        check_ptr(out, "out")?;
        let spring = CubicSpring::new(k_lin, alpha)?;
        let l = linearize_cubic(&spring, amplitude)?;
        let value = jointlin_cubic_linearization {
            k_star: l.k_star,
            d_star: l.d_star,
            energy_per_cycle: l.energy_per_cycle,
        };
        // SAFETY: checked non-NULL and aligned above; writable by contract.
        unsafe { put(out, value) };
        Ok(())
    })
}

/// Force F = k_lin x + alpha x^3 (4.1) (force units) and tangent stiffness
/// dF/dx = k_lin + 3 alpha x^2 (force/length) of the cubic spring at the elongation `x`
/// (length, any finite sign).
///
/// `force` and `tangent` must not be NULL. Errors: JOINTLIN_ERR_NULL,
/// JOINTLIN_ERR_NON_FINITE (any NaN/Inf input), JOINTLIN_ERR_OUT_OF_RANGE (misaligned
/// pointer), JOINTLIN_ERR_OVERFLOW (force or tangent not representable). The outputs are
/// written only on JOINTLIN_OK.
///
/// # Safety
/// Non-NULL `force` and `tangent` must point to valid, aligned, writable doubles.
#[no_mangle]
pub unsafe extern "C" fn jointlin_cubic_force(
    k_lin: f64,
    alpha: f64,
    x: f64,
    force: *mut f64,
    tangent: *mut f64,
) -> i32 {
    boundary("jointlin_cubic_force", || {
        check_ptr(force, "force")?;
        check_ptr(tangent, "tangent")?;
        let (f, t) = CubicSpring::new(k_lin, alpha)?.force_and_tangent(x)?;
        // SAFETY: both checked non-NULL and aligned above; writable by contract.
        unsafe {
            put(force, f);
            put(tangent, t);
        }
        Ok(())
    })
}
