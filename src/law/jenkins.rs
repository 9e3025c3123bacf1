//! Jenkins element: linear spring k_T0 in series with a Coulomb slider at μF_N.
//! Its virgin curve g(s) = min(k_T0 s, μF_N) has slip limit δ* = μF_N/k_T0.

/// Jenkins backbone of one contact point (force or stress form).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jenkins {
    /// μ|F_N| (> 0).
    pub friction_limit: f64,
    /// Spring stiffness k_T0 (> 0).
    pub k_t0: f64,
}

impl Jenkins {
    pub fn new(friction_limit: f64, k_t0: f64) -> Self {
        Self {
            friction_limit,
            k_t0,
        }
    }

    /// δ* = μF_N / k_T0: the spring's stretch when the slider starts.
    pub fn slip_limit(&self) -> f64 {
        self.friction_limit / self.k_t0
    }

    /// g(s) = min(k_T0 s, μF_N) (spring, then Coulomb (2.39)).
    pub fn force(&self, s: f64) -> f64 {
        (self.k_t0 * s).min(self.friction_limit)
    }

    /// k_T0 while the slider sticks, 0 while it slides.
    pub fn tangent(&self, s: f64) -> f64 {
        if s < self.slip_limit() {
            self.k_t0
        } else {
            0.0
        }
    }

    /// s = F/k_T0, capped at δ*.
    pub fn inverse(&self, force: f64) -> f64 {
        (force.max(0.0) / self.k_t0).min(self.slip_limit())
    }

    /// G(s) = ∫₀ˢ g: k_T0 s²/2, then μF_N δ*/2 + μF_N (s − δ*).
    pub fn work(&self, s: f64) -> f64 {
        let d = self.slip_limit();
        if s <= d {
            0.5 * self.k_t0 * s * s
        } else {
            self.friction_limit * (s - 0.5 * d)
        }
    }

    /// H(s) = 2G(s) − s g(s): 0 while sticking, μF_N (s − δ*) while sliding: the slider's work.
    pub fn iwan_dissipation(&self, s: f64) -> f64 {
        (self.friction_limit * (s - self.slip_limit())).max(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slider_dissipation_is_friction_times_slip() {
        let j = Jenkins::new(2.0, 100.0);
        assert_eq!(j.slip_limit(), 0.02);
        assert_eq!(j.force(0.01), 1.0);
        assert_eq!(j.force(1.0), 2.0);
        // 2G − s g at s = 0.05: 2·(2·(0.05 − 0.01)) − 0.05·2 = 0.16 − 0.1 = 0.06 = μF_N (s − δ*)
        assert!((j.iwan_dissipation(0.05) - 0.06).abs() < 1e-15);
        assert!((2.0 * j.work(0.05) - 0.05 * j.force(0.05) - 0.06).abs() < 1e-15);
    }
}
