//! First-order linearization of the cubic spring F(x) = k·x + α·x³ ((4.1), [`CubicSpring`])
//! for the amplitude A of x = A sin ωt: harmonic balance (3.5–3.8) gives
//! b₁ = (1/π)∫ F(A sin θ) sin θ dθ = k·A + ¾·α·A³, so k* = b₁/A = k + ¾·α·A²; the spring is
//! elastic, its force–displacement "loop" encloses no area (3.12), so energy balance (3.14)
//! gives d* = 0 at every frequency.

use crate::error::{finite, Error};
use crate::law::CubicSpring;

/// The linearized cubic spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubicLinearization {
    /// Equivalent stiffness k* = k + ¾αA² (3.8) (force/length; negative for a softening
    /// spring beyond A² = −4k/(3α)).
    pub k_star: f64,
    /// Equivalent viscous damping d* = A_hys/(πωA²) = 0 (3.14).
    pub d_star: f64,
    /// Energy dissipated per cycle A_hys = 0 (force × length).
    pub energy_per_cycle: f64,
}

/// Linearizes `spring` for the amplitude A ≥ 0 (length). Errors: NonFinite (A),
/// OutOfRange (A < 0), Overflow (k* not representable).
pub fn linearize_cubic(spring: &CubicSpring, amplitude: f64) -> Result<CubicLinearization, Error> {
    let a = finite(amplitude, "amplitude")?;
    if a < 0.0 {
        return Err(Error::OutOfRange("amplitude must be >= 0"));
    }
    // (3.8) with b₁ = kA + ¾αA³. Left to right, α = 0 gives 0 even where A² overflows.
    let k_star = spring.k + 0.75 * spring.alpha * a * a;
    if !k_star.is_finite() {
        return Err(Error::Overflow("cubic k* = k + 3/4 alpha A^2"));
    }
    // (3.12), (3.14): no enclosed area, no equivalent damping.
    Ok(CubicLinearization {
        k_star,
        d_star: 0.0,
        energy_per_cycle: 0.0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Trapezoid samples per period: exact (to round-off) for trigonometric polynomials of
    /// degree < SAMPLES; F(A sin θ)·sin θ has degree 4.
    const SAMPLES: usize = 64;

    /// b₁/A and ∮F dx of F(A sin θ) by the trapezoid rule over one period (3.6, 3.12).
    fn numerical_balance(s: &CubicSpring, a: f64) -> (f64, f64) {
        let h = 2.0 * std::f64::consts::PI / SAMPLES as f64;
        let (mut b1, mut work) = (0.0, 0.0);
        for i in 0..SAMPLES {
            let th = i as f64 * h;
            let f = s.force(a * th.sin());
            b1 += f * th.sin() * h / std::f64::consts::PI;
            work += f * a * th.cos() * h; // dx = A cos θ dθ
        }
        (b1 / a, work)
    }

    #[test]
    fn closed_form_matches_numerical_harmonic_balance() {
        // Duffing (B.1): k = 20, α = 40; plus softening and zero-linear cases, A over 12
        // decades. Tolerance 1e-13 relative: the trapezoid sum is exact up to round-off
        // of 64 terms (measured ≤ 3e-15).
        for (k, alpha) in [(20.0, 40.0), (20.0, -40.0), (0.0, 1.0), (1e3, 1e-3)] {
            let s = CubicSpring::new(k, alpha).unwrap();
            for e in -6..=6 {
                let a = 0.3948 * 10f64.powi(e);
                let l = linearize_cubic(&s, a).unwrap();
                let (k_num, work) = numerical_balance(&s, a);
                let scale = k.abs() + 0.75 * alpha.abs() * a * a;
                assert!(
                    (l.k_star - k_num).abs() <= 1e-13 * scale,
                    "k={k} alpha={alpha} A={a}: {} vs {k_num}",
                    l.k_star
                );
                // Elastic: the loop has no area (3.12), so d* = 0 (3.14). The numerical
                // work over a period is round-off of terms up to F·A.
                assert!(work.abs() <= 1e-13 * scale * a * a, "work {work}");
                assert_eq!((l.d_star, l.energy_per_cycle), (0.0, 0.0));
            }
        }
    }

    #[test]
    fn duffing_point_and_limits() {
        let s = CubicSpring::new(20.0, 40.0).unwrap();
        // The thesis's amplitude 0.395 at ω = 10: k* = 20 + 30·0.395² (3.8).
        let l = linearize_cubic(&s, 0.395).unwrap();
        assert!((l.k_star - 24.680_75).abs() < 1e-12);
        // A → 0: the linear spring.
        assert_eq!(linearize_cubic(&s, 0.0).unwrap().k_star, 20.0);
    }

    #[test]
    fn hard_inputs_give_named_errors() {
        let s = CubicSpring::new(20.0, 40.0).unwrap();
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(matches!(linearize_cubic(&s, bad), Err(Error::NonFinite(_))));
            assert!(matches!(
                CubicSpring::new(bad, 1.0),
                Err(Error::NonFinite(_))
            ));
            assert!(matches!(
                CubicSpring::new(1.0, bad),
                Err(Error::NonFinite(_))
            ));
        }
        assert!(matches!(
            linearize_cubic(&s, -1e-300),
            Err(Error::OutOfRange(_))
        ));
        assert!(matches!(
            linearize_cubic(&s, 1e200),
            Err(Error::Overflow(_))
        ));
        let huge = CubicSpring::new(f64::MAX, f64::MAX).unwrap();
        assert!(matches!(
            linearize_cubic(&huge, 1.0),
            Err(Error::Overflow(_))
        ));
        // α = 0 stays linear even where A² overflows.
        let linear = CubicSpring::new(5.0, 0.0).unwrap();
        assert_eq!(linearize_cubic(&linear, 1e200).unwrap().k_star, 5.0);
    }
}
