//! Screw preload from the tightening torque: the standard screw formula (VDI 2230
//! part 1, eq. R13 in the simplified form of Roloff/Matek),
//!
//!   T = F · (0.16·P + 0.58·d₂·μ_G + D_Km/2·μ_K),
//!
//! with thread pitch P, flank diameter d₂, thread friction μ_G, head (bearing) friction
//! μ_K and effective bearing diameter D_Km. 0.16·P ≈ P/(2π) is the thread's lead term,
//! 0.58·d₂ ≈ d₂/(2 cos 30°) the 60° flank term. Not a thesis equation: the thesis
//! (§5.4.1) replaces its screw by two point forces without stating how it got them.

use crate::error::{finite, Error};
use crate::wide::Wide;

/// Preload F (force) of a screw tightened to `torque` T (force·length); all lengths in
/// the same unit. Requires T ≥ 0, P > 0, d₂ > 0, D_Km ≥ 0, μ_G ≥ 0, μ_K ≥ 0. The lever
/// and the quotient are formed without intermediate overflow or underflow, so any
/// finite inputs give the correctly rounded F, or [`Error::Overflow`] when F exceeds the
/// largest double (T = 1, P = 5e-324, no friction: F = 1.25e324).
pub fn preload_from_torque(
    torque: f64,
    pitch: f64,
    d2: f64,
    mu_thread: f64,
    mu_head: f64,
    d_km: f64,
) -> Result<f64, Error> {
    finite(torque, "screw torque")?;
    finite(pitch, "thread pitch")?;
    finite(d2, "flank diameter d2")?;
    finite(mu_thread, "thread friction mu_G")?;
    finite(mu_head, "head friction mu_K")?;
    finite(d_km, "bearing diameter D_Km")?;
    if torque < 0.0 || pitch <= 0.0 || d2 <= 0.0 || d_km < 0.0 {
        return Err(Error::OutOfRange(
            "screw: torque >= 0, pitch > 0, d2 > 0, D_Km >= 0 required",
        ));
    }
    if mu_thread < 0.0 || mu_head < 0.0 {
        return Err(Error::OutOfRange(
            "screw: friction coefficients must be >= 0",
        ));
    }
    // VDI 2230 (R13), Roloff/Matek form; the lever is > 0 because P > 0.
    let w = Wide::new;
    let lever = Wide::sum_non_negative(&[
        w(pitch) * 0.16,
        w(d2) * 0.58 * mu_thread,
        w(d_km) * 0.5 * mu_head,
    ]);
    let preload = (w(torque) / lever).to_f64();
    if preload.is_infinite() {
        return Err(Error::Overflow(
            "screw preload T / (0.16 P + 0.58 d2 mu_G + D_Km/2 mu_K) beyond the largest double",
        ));
    }
    Ok(preload)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// M8 (P = 1.25, d₂ = 7.188), μ_G = μ_K = 0.12, D_Km = 11.6 mm (hex head, medium
    /// hole): the lever is 0.2 + 0.5003 + 0.696 = 1.3963 mm, so 25 N·m gives 17.90 kN
    /// (VDI 2230 tables list 17.8–18 kN for this case; the formula is exact arithmetic).
    #[test]
    fn m8_reference_value() {
        let f = preload_from_torque(25_000.0, 1.25, 7.188, 0.12, 0.12, 11.6).unwrap();
        approx::assert_relative_eq!(
            f,
            25_000.0 / (0.16 * 1.25 + 0.58 * 7.188 * 0.12 + 5.8 * 0.12),
            max_relative = 1e-15
        );
        assert!((f - 17_904.0).abs() < 5.0, "{f}");
        // Frictionless limit: only the lead term, F = T/(0.16 P).
        let f0 = preload_from_torque(1.0, 0.5, 2.675, 0.0, 0.0, 4.0).unwrap();
        approx::assert_relative_eq!(f0, 1.0 / 0.08, max_relative = 1e-15);
    }

    #[test]
    fn bad_inputs_are_named_errors() {
        assert!(matches!(
            preload_from_torque(f64::NAN, 0.5, 2.675, 0.1, 0.1, 4.0),
            Err(Error::NonFinite(_))
        ));
        assert!(matches!(
            preload_from_torque(1.0, 0.0, 2.675, 0.1, 0.1, 4.0),
            Err(Error::OutOfRange(_))
        ));
        assert!(matches!(
            preload_from_torque(1.0, 0.5, 2.675, -0.1, 0.1, 4.0),
            Err(Error::OutOfRange(_))
        ));
    }
}
