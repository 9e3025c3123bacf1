//! The describing function for a tangential motion given as two complex amplitudes, the
//! form a frequency-domain host has (docs/contact3d.md §4): u(t) = Re(û e^{iωt}),
//! û = (û₁, û₂). The path is an ellipse; in its principal axes it is
//! (A₁ cos(ωt + θ₀), A₂ sin(ωt + θ₀)), where [`describe_with`] gives per axis
//! cⱼ = k*ⱼ + iωd*ⱼ. Back in the host's axes the first harmonic of the force is
//! t̂ = (K* + iω D*) û with K* = R diag(k*) Rᵀ and D* = R diag(d*) Rᵀ (R the rotation to
//! the principal axes), two symmetric 2 × 2 matrices.

use super::describing::{describe_with, Method};
use super::Contact3d;
use crate::error::{finite, Error};
use crate::iterate::Complex64;
use crate::linearize::Regime;

/// A minor axis below this share of the major one is evaluated at it: a path that thin
/// is a line for the major direction (its harmonics change by O(share²)), and the minor
/// direction's coefficient takes its thin-path limit instead of 0 (the stiffness a
/// slipping point offers sideways). The forces change by O(share) of μN at most.
pub const THIN_PATH: f64 = 1e-6;

/// The linearized point for a complex tangential amplitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DescribingMatrix {
    /// K*, symmetric, row-major (force/length).
    pub k_star: [[f64; 2]; 2],
    /// D*, symmetric, row-major (force·time/length).
    pub d_star: [[f64; 2]; 2],
    /// Semi-axes A₁ ≥ A₂ ≥ 0 of the path (length).
    pub semi_axes: [f64; 2],
    /// Angle of the major axis from direction 1, in (−π/2, π/2] (rad).
    pub angle: f64,
    /// Energy dissipated per cycle (force × length).
    pub energy_per_cycle: f64,
    pub regime: Regime,
}

/// The ellipse of u(t) = Re(û e^{iωt}): semi-axes A₁ ≥ A₂ (length) and the major axis's
/// angle φ from direction 1. From M = Re(û ûᴴ) (eigenvalues A₁², A₂²), with A₂ from
/// det M = Im(û₁ ū₂)² so that thin paths keep their minor axis to full precision; the
/// phasors are scaled by their largest modulus first (no overflow for any finite input).
pub fn ellipse(u: [Complex64; 2]) -> ([f64; 2], f64) {
    let scale = u[0].norm().max(u[1].norm());
    if scale == 0.0 || !scale.is_finite() {
        return ([scale; 2], 0.0);
    }
    let (p, q) = (u[0] / scale, u[1] / scale);
    let (m11, m22) = (p.norm_sqr(), q.norm_sqr());
    let cross = p * q.conj();
    let m12 = cross.re;
    let half_diff = 0.5 * (m11 - m22);
    let major2 = 0.5 * (m11 + m22) + half_diff.hypot(m12);
    let major = major2.sqrt();
    let minor = (cross.im.abs() / major).min(major);
    let angle = 0.5 * (2.0 * m12).atan2(m11 - m22);
    ([major * scale, minor * scale], angle)
}

/// Describes the point moving with the complex tangential amplitude `u` (length; finite)
/// at the constant normal force `normal_force` and ω > 0, by `method`.
pub fn describe_phasors(
    contact: &Contact3d,
    normal_force: f64,
    u: [Complex64; 2],
    omega: f64,
    method: Method,
) -> Result<DescribingMatrix, Error> {
    for c in u {
        finite(c.re, "amplitude")?;
        finite(c.im, "amplitude")?;
    }
    let (axes, angle) = ellipse(u);
    if !axes[0].is_finite() {
        return Err(Error::Overflow("amplitude"));
    }
    let minor = axes[1].max(THIN_PATH * axes[0]);
    let d = describe_with(contact, normal_force, [axes[0], minor], omega, method)?;
    let (s, c) = angle.sin_cos();
    let rotate = |v: [f64; 2]| {
        let off = (v[0] - v[1]) * c * s;
        [
            [v[0] * c * c + v[1] * s * s, off],
            [off, v[0] * s * s + v[1] * c * c],
        ]
    };
    Ok(DescribingMatrix {
        k_star: rotate(d.k_star),
        d_star: rotate(d.d_star),
        semi_axes: axes,
        angle,
        energy_per_cycle: d.energy_per_cycle,
        regime: d.regime,
    })
}
