//! Mindlin's tangential microslip law (2.44–2.49), ending in Coulomb sliding (2.39).
//!
//! With u = s/δ* the normalized slip from the last zero-force point:
//! g(s) = μF_N [1 − (1 − u)^{3/2}] for u ≤ 1 (2.49), g = μF_N beyond (2.39).

use super::series::{binomial_tail, one_minus_pow, SERIES_BELOW};

/// Mindlin backbone of one contact point. Fields are plain data so the struct can be built
/// for a force (N) or a stress (N/mm²) form alike.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mindlin {
    /// μ|F_N| (force, or μ p_N in stress form), > 0.
    pub friction_limit: f64,
    /// Full-stick tangential stiffness k_T0 (force/length, or stress/length), > 0.
    pub k_t0: f64,
}

impl Mindlin {
    pub fn new(friction_limit: f64, k_t0: f64) -> Self {
        Self {
            friction_limit,
            k_t0,
        }
    }

    /// k_T0 from Hertz–Mindlin geometry, k_T0 = 8 r_A G* (2.38), with the contact radius
    /// r_A from [`super::hertz::Hertz::contact_radius`] and G* from [`effective_shear_modulus`].
    pub fn k_t0_from_geometry(contact_radius: f64, g_star: f64) -> f64 {
        8.0 * contact_radius * g_star // (2.38)
    }

    /// Slip limit δ* = δ_T^max = 1.5 μ|F_N| / k_T0 (2.46 with 2.38).
    pub fn slip_limit(&self) -> f64 {
        1.5 * self.friction_limit / self.k_t0 // (2.46)
    }

    /// Normalized slip u = s/δ*.
    fn u(&self, s: f64) -> f64 {
        s / self.slip_limit()
    }

    /// |F_T| = μ|F_N| [1 − (1 − s/δ*)^{3/2}] (2.49); μ|F_N| for s ≥ δ* (2.39).
    pub fn force(&self, s: f64) -> f64 {
        self.friction_limit * one_minus_pow(1.5, self.u(s)) // (2.49)
    }

    /// k_T = k_T0 (1 − s/δ*)^{1/2} (2.48); 0 while sliding.
    pub fn tangent(&self, s: f64) -> f64 {
        let u = self.u(s);
        if u >= 1.0 {
            0.0
        } else {
            self.k_t0 * (1.0 - u).sqrt() // (2.48)
        }
    }

    /// s = δ* [1 − (1 − F/μF_N)^{2/3}] (2.45), the inverse of (2.49); δ* for F ≥ μF_N.
    pub fn inverse(&self, force: f64) -> f64 {
        let f = (force / self.friction_limit).clamp(0.0, 1.0);
        self.slip_limit() * one_minus_pow(2.0 / 3.0, f) // (2.45)
    }

    /// G(s) = ∫₀ˢ g = μF_N δ* [u − (2/5)(1 − (1 − u)^{5/2})] from (2.49); beyond δ*
    /// G(δ*) = 0.6 μF_N δ* plus μF_N (s − δ*).
    pub fn work(&self, s: f64) -> f64 {
        let d = self.slip_limit();
        let u = self.u(s);
        let scale = self.friction_limit * d;
        if u >= 1.0 {
            return scale * (0.6 + (u - 1.0));
        }
        if u < SERIES_BELOW {
            // u − 0.4(1 − Σ c_k u^k) with c_1 = −5/2 cancels the u: 0.4 Σ_{k≥2} c_k u^k.
            return scale * 0.4 * binomial_tail(2.5, u, 2);
        }
        scale * (u - 0.4 * one_minus_pow(2.5, u))
    }

    /// H(s) = 2G(s) − s g(s) = μF_N δ* (1 − v)³ (3v² + 9v + 3)/15 with v = (1 − u)^{1/2}
    /// (factored so that no digits cancel at small u); μF_N (s − 0.8 δ*) beyond δ*.
    pub fn iwan_dissipation(&self, s: f64) -> f64 {
        let d = self.slip_limit();
        let u = self.u(s);
        let scale = self.friction_limit * d;
        if u >= 1.0 {
            return scale * (u - 0.8);
        }
        let v = (1.0 - u).sqrt();
        let one_minus_v = u / (1.0 + v);
        scale * one_minus_v.powi(3) * (3.0 * v * v + 9.0 * v + 3.0) / 15.0
    }

    /// ρ(u) = [k_T0 s − g(s)] / μF_N = 1.5u − 1 + (1 − u)^{3/2} (u ≤ 1), 1.5u − 1 beyond:
    /// how far the backbone falls below the elastic line, in units of μF_N. ≥ 0.
    pub fn remainder(u: f64) -> f64 {
        if u >= 1.0 {
            1.5 * u - 1.0
        } else if u < SERIES_BELOW {
            binomial_tail(1.5, u, 2)
        } else {
            1.5 * u - 1.0 + (1.0 - u).powf(1.5)
        }
    }
}

/// G* = ((2 − ν₁)/G₁ + (2 − ν₂)/G₂)⁻¹ (2.37), shear moduli G_i and Poisson ratios ν_i.
pub fn effective_shear_modulus(g1: f64, nu1: f64, g2: f64, nu2: f64) -> f64 {
    1.0 / ((2.0 - nu1) / g1 + (2.0 - nu2) / g2) // (2.37)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    // The block of Appendix C: μ = 0.3, F_N = 2 N, k_T0 = 1282.7 N/mm.
    fn block() -> Mindlin {
        Mindlin::new(0.6, 1282.7)
    }

    #[test]
    fn slip_limit_is_one_and_a_half_mu_fn_over_k() {
        assert_relative_eq!(block().slip_limit(), 0.9 / 1282.7, max_relative = 1e-15);
    }

    #[test]
    fn force_reaches_the_friction_limit_at_the_slip_limit_and_stays() {
        let m = block();
        assert_relative_eq!(m.force(m.slip_limit()), 0.6, max_relative = 1e-15);
        assert_eq!(m.force(10.0 * m.slip_limit()), 0.6);
        assert_eq!(m.tangent(2.0 * m.slip_limit()), 0.0);
    }

    #[test]
    fn initial_tangent_is_k_t0_and_matches_finite_differences() {
        let m = block();
        assert_relative_eq!(m.tangent(0.0), 1282.7, max_relative = 1e-15);
        // Central differences, h = 1e-6 δ*: truncation O(h²) ≈ 1e-12 relative, rounding ≈ 1e-10.
        for frac in [0.1, 0.5, 0.9] {
            let s = frac * m.slip_limit();
            let h = 1e-6 * m.slip_limit();
            let fd = (m.force(s + h) - m.force(s - h)) / (2.0 * h);
            assert_relative_eq!(m.tangent(s), fd, max_relative = 1e-8);
        }
        // (2.48) second form: k_T0 (1 − F/μF_N)^{1/3}.
        let s = 0.3 * m.slip_limit();
        let alt = m.k_t0 * (1.0 - m.force(s) / m.friction_limit).cbrt();
        assert_relative_eq!(m.tangent(s), alt, max_relative = 1e-13);
    }

    #[test]
    fn inverse_inverts_force() {
        let m = block();
        for frac in [1e-12, 1e-6, 0.01, 0.5, 0.999] {
            let s = frac * m.slip_limit();
            assert_relative_eq!(m.inverse(m.force(s)), s, max_relative = 1e-9);
        }
    }

    #[test]
    fn work_and_dissipation_match_quadrature_of_the_force() {
        let m = block();
        // Composite Simpson with 20000 intervals on a smooth integrand: error < 1e-14 relative.
        for frac in [1e-3, 0.04, 0.06, 0.5, 1.0] {
            let s = frac * m.slip_limit();
            let n = 20000;
            let h = s / n as f64;
            let simpson = |f: &dyn Fn(f64) -> f64| {
                let mut acc = f(0.0) + f(s);
                for i in 1..n {
                    acc += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
                }
                acc * h / 3.0
            };
            assert_relative_eq!(m.work(s), simpson(&|t| m.force(t)), max_relative = 1e-9);
            // At s = δ* the integrand's √(1 − u) end spoils Simpson; checked exactly below.
            if frac < 1.0 {
                let iwan = simpson(&|t| m.force(t) - t * m.tangent(t));
                assert_relative_eq!(m.iwan_dissipation(s), iwan, max_relative = 1e-9);
            }
        }
        // H(δ*) = 2G(δ*) − δ* μF_N = (1.2 − 1) μF_N δ*.
        let d = m.slip_limit();
        assert_relative_eq!(m.iwan_dissipation(d), 0.2 * 0.6 * d, max_relative = 1e-14);
    }

    #[test]
    fn small_slip_limits_are_cancellation_free() {
        let m = block();
        let s = 1e-12 * m.slip_limit();
        // G ≈ k_T0 s²/2, H ≈ k_T0 s³ /(4 δ*) · (1/ … ) — check the leading terms.
        assert_relative_eq!(m.work(s), 0.5 * m.k_t0 * s * s, max_relative = 1e-9);
        let u: f64 = 1e-12;
        // H/(μF_N δ*) = 2P − uQ = (1−v)³(15)/15 + … ≈ (u/2)³·15/15 = u³/8·... leading 15(u/2)^3/15
        let lead = m.friction_limit * m.slip_limit() * (u / 2.0).powi(3);
        assert_relative_eq!(m.iwan_dissipation(s), lead, max_relative = 1e-9);
        assert_relative_eq!(Mindlin::remainder(u), 0.375 * u * u, max_relative = 1e-9);
    }

    #[test]
    fn remainder_is_continuous_at_series_switch_and_slip_limit() {
        let below = Mindlin::remainder(SERIES_BELOW * (1.0 - 1e-12));
        let above = Mindlin::remainder(SERIES_BELOW * (1.0 + 1e-12));
        assert_relative_eq!(below, above, max_relative = 1e-10);
        assert_relative_eq!(Mindlin::remainder(1.0 - 1e-14), 0.5, max_relative = 1e-9);
    }

    #[test]
    fn geometry_gives_the_same_slip_limit_as_2_46() {
        // δ* = 3μF_N/(16 r_A G*) must equal 1.5 μF_N / (8 r_A G*).
        let (r_a, g_star, mu_fn) = (0.05, 30_000.0, 0.6);
        let m = Mindlin::new(mu_fn, Mindlin::k_t0_from_geometry(r_a, g_star));
        assert_relative_eq!(
            m.slip_limit(),
            3.0 * mu_fn / (16.0 * r_a * g_star),
            max_relative = 1e-15
        );
    }
}

impl Mindlin {
    /// D(s) = G(s) − g(s)²/(2k_T0) = μF_N δ* (1 − v)³ (5v³ + 9v² + 12v + 4)/15, v = (1 − u)^{1/2}
    /// (from (2.49) with μF_N/k_T0 = δ*/1.5, factored to avoid cancellation);
    /// μF_N δ* (4/15 + u − 1) beyond δ*.
    pub fn elastic_split_dissipation(&self, s: f64) -> f64 {
        let u = self.u(s);
        let scale = self.friction_limit * self.slip_limit();
        if u >= 1.0 {
            return scale * (4.0 / 15.0 + (u - 1.0));
        }
        let v = (1.0 - u).sqrt();
        let one_minus_v = u / (1.0 + v);
        scale * one_minus_v.powi(3) * (((5.0 * v + 9.0) * v + 12.0) * v + 4.0) / 15.0
    }
}

#[cfg(test)]
mod split_tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn elastic_split_matches_its_definition() {
        let m = Mindlin::new(0.6, 1282.7);
        for frac in [0.2, 0.7, 1.0, 3.0] {
            let s = frac * m.slip_limit();
            let direct = m.work(s) - m.force(s).powi(2) / (2.0 * m.k_t0);
            assert_relative_eq!(m.elastic_split_dissipation(s), direct, max_relative = 1e-11);
        }
    }
}
