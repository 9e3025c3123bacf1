//! Hertz normal contact of two curved elastic bodies (2.31–2.35) and the per-area
//! "stress form" that FE hosts use (pressure vs overclosure, Abaqus sign convention:
//! pressure positive in compression, overclosure positive = penetration).

use crate::error::Error;

/// Effective radius r* = (1/r₁ + 1/r₂)⁻¹ (2.31). A flat body has r = ∞.
pub fn effective_radius(r1: f64, r2: f64) -> f64 {
    1.0 / (1.0 / r1 + 1.0 / r2) // (2.31)
}

/// Effective modulus E* = ((1 − ν₁²)/E₁ + (1 − ν₂²)/E₂)⁻¹ (2.31).
pub fn effective_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2) // (2.31)
}

/// Hertz contact of two bodies with effective radius r* and modulus E*.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    pub r_star: f64,
    pub e_star: f64,
}

impl Hertz {
    pub fn new(r_star: f64, e_star: f64) -> Result<Self, Error> {
        if !(r_star.is_finite() && e_star.is_finite()) {
            return Err(Error::NonFinite("Hertz r* or E*"));
        }
        if r_star <= 0.0 || e_star <= 0.0 {
            return Err(Error::OutOfRange("Hertz r* and E* must be > 0"));
        }
        Ok(Self { r_star, e_star })
    }

    /// Contact radius r_A = (3|F_N| r*/(4E*))^{1/3} (2.32).
    pub fn contact_radius(&self, normal_force: f64) -> f64 {
        (3.0 * normal_force.abs() * self.r_star / (4.0 * self.e_star)).cbrt() // (2.32)
    }

    /// Peak pressure p_max = 3|F_N|/(2π r_A²) (2.33).
    pub fn peak_pressure(&self, normal_force: f64) -> f64 {
        let r_a = self.contact_radius(normal_force);
        if r_a == 0.0 {
            return 0.0;
        }
        3.0 * normal_force.abs() / (2.0 * std::f64::consts::PI * r_a * r_a) // (2.33)
    }

    /// Approach α_N = r_A²/r* = (9|F_N|²/(16 r* E*²))^{1/3} (2.34; the thesis prints 19 for 16).
    pub fn approach(&self, normal_force: f64) -> f64 {
        let r_a = self.contact_radius(normal_force);
        r_a * r_a / self.r_star // (2.34)
    }

    /// Normal stiffness k_N = dF_N/dα_N = 2 r_A E* = (6 r* E*² |F_N|)^{1/3} (2.35).
    pub fn normal_stiffness(&self, normal_force: f64) -> f64 {
        2.0 * self.contact_radius(normal_force) * self.e_star // (2.35)
    }

    /// Inverse of (2.34): F_N = (4/3) E* √r* α^{3/2} for an approach α ≥ 0, 0 when open.
    pub fn force(&self, approach: f64) -> f64 {
        if approach <= 0.0 {
            return 0.0;
        }
        4.0 / 3.0 * self.e_star * self.r_star.sqrt() * approach.powf(1.5) // (2.34) inverted
    }
}

/// Normal law in the stress form used per FE contact point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalLaw {
    /// p = k_N h for overclosure h > 0 (k_N: pressure per length, i.e. stiffness per area).
    Linear { stiffness_per_area: f64 },
    /// Hertz point contact (2.34) spread over the point's tributary area:
    /// p = F_N(h)/area with F_N = (4/3) E* √r* h^{3/2}.
    Hertz { hertz: Hertz, area: f64 },
}

/// Contact pressure and its derivative at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NormalResponse {
    /// Pressure p ≥ 0 (positive in compression).
    pub pressure: f64,
    /// dp/dh ≥ 0 (pressure per length).
    pub stiffness: f64,
    /// Whether the point is closed (h > 0).
    pub closed: bool,
}

impl NormalLaw {
    /// Pressure for the overclosure h (positive = penetration); open (zero pressure and
    /// stiffness) when h ≤ 0.
    pub fn response(&self, overclosure: f64) -> NormalResponse {
        if overclosure <= 0.0 || overclosure.is_nan() {
            return NormalResponse {
                pressure: 0.0,
                stiffness: 0.0,
                closed: false,
            };
        }
        match *self {
            NormalLaw::Linear { stiffness_per_area } => NormalResponse {
                pressure: stiffness_per_area * overclosure,
                stiffness: stiffness_per_area,
                closed: true,
            },
            NormalLaw::Hertz { hertz, area } => {
                let force = hertz.force(overclosure);
                // dF/dα = 2 E* √r* α^{1/2} = k_N (2.35)
                let k_n = 2.0 * hertz.e_star * (hertz.r_star * overclosure).sqrt();
                NormalResponse {
                    pressure: force / area,
                    stiffness: k_n / area,
                    closed: true,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn steel_ball_on_flat() -> Hertz {
        let e = effective_modulus(210_000.0, 0.3, 210_000.0, 0.3);
        Hertz::new(effective_radius(5.0, f64::INFINITY), e).unwrap()
    }

    #[test]
    fn approach_and_force_are_inverse() {
        let h = steel_ball_on_flat();
        for f in [1e-6, 1.0, 100.0, 1e5] {
            assert_relative_eq!(h.force(h.approach(f)), f, max_relative = 1e-12);
        }
    }

    #[test]
    fn stiffness_forms_of_2_35_agree() {
        let h = steel_ball_on_flat();
        let f: f64 = 50.0;
        let k = h.normal_stiffness(f);
        assert_relative_eq!(
            k,
            (6.0 * h.r_star * h.e_star.powi(2) * f).cbrt(),
            max_relative = 1e-13
        );
        assert_relative_eq!(k, 1.5 * f / h.approach(f), max_relative = 1e-13);
        // dF/dα by central differences (h = 1e-6 α: error ≈ 1e-12 relative).
        let a = h.approach(f);
        let d = 1e-6 * a;
        let fd = (h.force(a + d) - h.force(a - d)) / (2.0 * d);
        assert_relative_eq!(k, fd, max_relative = 1e-8);
    }

    #[test]
    fn stress_form_is_open_for_a_gap() {
        let law = NormalLaw::Linear {
            stiffness_per_area: 1e4,
        };
        assert!(!law.response(-1e-3).closed);
        assert_eq!(law.response(0.0).pressure, 0.0);
        let r = law.response(1e-3);
        assert_eq!((r.pressure, r.stiffness, r.closed), (10.0, 1e4, true));
        let hz = NormalLaw::Hertz {
            hertz: steel_ball_on_flat(),
            area: 2.0,
        };
        let r = hz.response(1e-3);
        assert_relative_eq!(
            r.pressure * 2.0,
            steel_ball_on_flat().force(1e-3),
            max_relative = 1e-15
        );
    }

    #[test]
    fn pressure_integrates_to_the_load() {
        // ∫ p_max √(1 − r²/r_A²) 2πr dr = (2/3) π r_A² p_max = |F_N| (2.33).
        let h = steel_ball_on_flat();
        let f = 20.0;
        let r_a = h.contact_radius(f);
        assert_relative_eq!(
            2.0 / 3.0 * std::f64::consts::PI * r_a * r_a * h.peak_pressure(f),
            f,
            max_relative = 1e-14
        );
    }
}
