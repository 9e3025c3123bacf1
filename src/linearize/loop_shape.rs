//! The steady hysteresis loop of half-width A (the amplitude) for a backbone and rule.
//!
//! Write the loop's descending branch from its right tip as f_L(x) = F̂ − D(A − x), where
//! D(Δ) is the force drop after a reversal travelled Δ:
//! * thesis rule (model.md §4): D = k_T0 Δ up to F̂/k_T0 (phase 3), then F̂ + g(Δ − F̂/k_T0)
//!   (phases 1–2 in the other direction), F̂ fixed by the loop width F̂/k_T0 + g⁻¹(F̂) = 2A;
//! * Masing: D = 2 g(Δ/2), F̂ = g(A).
//!
//! Along x = A sin θ, with φ = θ + π/2 and y = sin(φ/2): Δ = 2A(1 − y²), and the backbone
//! argument of the virgin part is σ = s/δ* = σ_max − c y² (σ ≥ 1: Coulomb sliding).

use crate::hysteresis::Rule;
use crate::law::Backbone;

/// Geometry of one loop, everything the HBM and EBM need.
#[derive(Debug, Clone, Copy)]
pub struct LoopShape {
    pub amplitude: f64,
    /// Peak force F̂ at the loop tips.
    pub peak_force: f64,
    /// Virgin-curve argument at the far tip (θ = −π/2), in units of δ*.
    pub sigma_max: f64,
    /// σ = σ_max − c y²: c = 2A/δ* (thesis) or A/δ* (Masing).
    pub c: f64,
    /// c − σ_max, computed without cancellation: F̂/(k_T0 δ*) (thesis), 0 (Masing).
    pub c_minus_sigma_max: f64,
    /// Loop area A_hys = energy dissipated per cycle (closed form).
    pub area: f64,
}

impl LoopShape {
    pub fn new(b: &Backbone, rule: Rule, amplitude: f64) -> Self {
        let d = b.slip_limit();
        let (peak_force, sigma_max, c) = match rule {
            Rule::Thesis => {
                let f = thesis_peak_force(b, amplitude);
                let s_tot = 2.0 * amplitude - f / b.k_t0();
                (f, thesis_sigma_max(b, f, s_tot), 2.0 * amplitude / d)
            }
            Rule::Masing => (b.force(amplitude), amplitude / d, amplitude / d),
        };
        let (c_minus_sigma_max, area) = match rule {
            // A_hys = 2 D(s_tot): twice the elastic-split dissipation of one half cycle.
            Rule::Thesis => (
                peak_force / (b.k_t0() * d),
                2.0 * b.elastic_split_dissipation(sigma_max * d),
            ),
            // A_hys = 8G(A) − 4A g(A) = 4H(A).
            Rule::Masing => (0.0, 4.0 * b.iwan_dissipation(amplitude)),
        };
        Self {
            amplitude,
            peak_force,
            sigma_max,
            c,
            c_minus_sigma_max,
            area: area.max(0.0),
        }
    }

    /// Whether part of the loop is Coulomb sliding (σ_max > 1).
    pub fn slides(&self) -> bool {
        self.sigma_max > 1.0
    }

    /// Force drop D(Δ) after a reversal travelled Δ ∈ [0, 2A].
    pub fn drop(&self, b: &Backbone, rule: Rule, delta: f64) -> f64 {
        match rule {
            Rule::Thesis => {
                let elastic = self.peak_force / b.k_t0();
                if delta <= elastic {
                    b.k_t0() * delta
                } else {
                    self.peak_force + b.force(delta - elastic)
                }
            }
            Rule::Masing => 2.0 * b.force(0.5 * delta),
        }
    }

    /// Descending branch f_L(x) = F̂ − D(A − x), x ∈ [−A, A].
    pub fn descending(&self, b: &Backbone, rule: Rule, x: f64) -> f64 {
        self.peak_force - self.drop(b, rule, self.amplitude - x)
    }
}

/// σ_max = (2A − F̂/k_T0)/δ*; in Mindlin stick it equals g⁻¹(F̂)/δ*, evaluated that way to
/// avoid the cancellation in 2A − F̂/k_T0.
fn thesis_sigma_max(b: &Backbone, peak: f64, s_tot: f64) -> f64 {
    let d = b.slip_limit();
    match b {
        Backbone::Mindlin(m) if peak < m.friction_limit => b.inverse(peak) / d,
        _ => (s_tot / d).max(0.0),
    }
}

/// Peak force of the thesis loop of half-width A: F̂/k_T0 + g⁻¹(F̂) = 2A, F̂ ≤ μF_N.
///
/// Mindlin: with v = (1 − g⁻¹(F̂)/δ*)^{1/2} and e = 1 − v the width equation (2.45, 2.49)
/// becomes 4e − 3e² + (2/3)e³ = 2A/δ* (solved for e when small) or (2/3)v³ + v² = 5/3 − 2A/δ*
/// (solved for v near the sliding onset A = 5δ*/6); both by monotone Newton, then
/// F̂ = μF_N (1 − v³) = μF_N e(3 − 3e + e²).
pub fn thesis_peak_force(b: &Backbone, amplitude: f64) -> f64 {
    let limit = b.friction_limit();
    match b {
        Backbone::Jenkins(j) => (j.k_t0 * amplitude).min(limit),
        Backbone::Mindlin(m) => {
            let a2 = 2.0 * amplitude / m.slip_limit();
            if a2 >= 5.0 / 3.0 {
                return limit;
            }
            let e = if a2 < 5.0 / 6.0 {
                // ψ(e) concave increasing, start left of the root: iterates rise monotonically.
                let mut e = a2 / 4.0;
                for _ in 0..60 {
                    let psi = ((2.0 / 3.0 * e - 3.0) * e + 4.0) * e - a2;
                    let step = psi / (2.0 * (1.0 - e) * (2.0 - e));
                    e -= step;
                    if step.abs() <= 1e-16 * e {
                        break;
                    }
                }
                e
            } else {
                // φ(v) convex increasing, start right of the root: iterates fall monotonically.
                let rhs = 5.0 / 3.0 - a2;
                let mut v = rhs.sqrt();
                for _ in 0..60 {
                    let phi = (2.0 / 3.0 * v + 1.0) * v * v - rhs;
                    let step = phi / (2.0 * v * (1.0 + v));
                    if !step.is_finite() {
                        break;
                    }
                    v -= step;
                    if step.abs() <= 1e-16 * v {
                        break;
                    }
                }
                1.0 - v
            };
            limit * e * (3.0 + e * (e - 3.0))
        }
    }
}
