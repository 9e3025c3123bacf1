//! Cubic (Duffing) spring: the restoring force of the thesis's Duffing oscillator (4.1),
//! F(x) = k·x + α·x³. Not a contact law: an elastic nonlinear spring (hardening for
//! α > 0, softening for α < 0) that FE hosts linearize like a contact point.

use crate::error::{finite, Error};

/// A spring F(x) = k·x + α·x³ (k force/length, α force/length³; any finite signs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubicSpring {
    /// Linear stiffness k (force/length).
    pub k: f64,
    /// Cubic coefficient α (force/length³).
    pub alpha: f64,
}

impl CubicSpring {
    /// The spring, or NonFinite for a NaN/±∞ coefficient.
    pub fn new(k: f64, alpha: f64) -> Result<Self, Error> {
        Ok(CubicSpring {
            k: finite(k, "cubic spring k")?,
            alpha: finite(alpha, "cubic spring alpha")?,
        })
    }

    /// Force (force units) at the elongation x (length): k·x + α·x³ (4.1).
    pub fn force(&self, x: f64) -> f64 {
        // (4.1)
        self.k * x + self.alpha * x * x * x
    }

    /// Tangent stiffness dF/dx = k + 3·α·x² of (4.1) (force/length) at the elongation x.
    pub fn tangent(&self, x: f64) -> f64 {
        self.k + 3.0 * self.alpha * x * x
    }

    /// Force and tangent at the elongation x (length). Errors: NonFinite (x), Overflow
    /// (force or tangent not representable).
    pub fn force_and_tangent(&self, x: f64) -> Result<(f64, f64), Error> {
        let x = finite(x, "elongation x")?;
        let (force, tangent) = (self.force(x), self.tangent(x));
        if !(force.is_finite() && tangent.is_finite()) {
            return Err(Error::Overflow("cubic spring force k x + alpha x^3"));
        }
        Ok((force, tangent))
    }
}
