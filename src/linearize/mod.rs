//! Linearization of one contact point for a displacement amplitude A and angular
//! frequency ω: k* by harmonic balance ([`hbm`], (3.8) on the Ersatzfunktion (4.3)),
//! d* by energy balance ([`ebm`], (3.14)), loss factor, energy per cycle, peak force, regime.
//! [`cubic`]: the same two balances for the Duffing oscillator's cubic spring (closed form).

pub mod cubic;
pub mod ebm;
pub mod hbm;
pub mod loop_shape;
pub mod quadrature;

use crate::error::{finite, Error};
use crate::hysteresis::{Point, Rule};
use crate::law::{Backbone, TangentialLaw};
use crate::wide::Wide;
use loop_shape::LoopShape;
use std::f64::consts::PI;

/// Gauss points per panel of the default method: the smallest count whose worst relative
/// error in k* over A/δ* ∈ [1e-12, 1e6] stays below 1e-12 (measured in `tests`).
pub const DEFAULT_POINTS: usize = 8;

/// How the loop integrals are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Default: loop area in closed form; k* from closed-form pieces plus graded
    /// Gauss–Legendre (`points` per panel) on the Mindlin piece in singularity-free variables.
    Graded { points: usize },
    /// The thesis's composite Simpson rule with `intervals` (even) sub-intervals, for k*
    /// over θ and for the loop area over x (Fig. 4.11).
    Simpson { intervals: usize },
    /// Plain Gauss–Legendre with `points` ≥ 2 over θ and over x, no splitting at the kinks
    /// (one point samples only θ = 0, where sin θ = 0: k* would be 0 for every loop).
    Gauss { points: usize },
}

impl Default for Method {
    fn default() -> Self {
        Method::Graded {
            points: DEFAULT_POINTS,
        }
    }
}

impl Method {
    /// The method itself, or [`Error::OutOfRange`] for a point count it does not offer.
    pub fn validate(self) -> Result<Self, Error> {
        let ok = match self {
            Method::Graded { points } => (1..=quadrature::MAX_GAUSS_POINTS).contains(&points),
            Method::Gauss { points } => (2..=quadrature::MAX_GAUSS_POINTS).contains(&points),
            Method::Simpson { intervals } => {
                intervals >= 2 && intervals % 2 == 0 && intervals <= 1 << 26
            }
        };
        if ok {
            Ok(self)
        } else {
            Err(Error::OutOfRange("quadrature point count"))
        }
    }
}

/// Contact state of the linearized point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(i32)]
pub enum Regime {
    /// No tangential force can be carried: the gap is open (F_N ≤ 0) or μ = 0.
    Open = 0,
    /// No slip anywhere in the loop (A = 0, or a Jenkins slider below its limit).
    Stick = 1,
    /// Partial slip (Mindlin microslip), no Coulomb sliding.
    Microslip = 2,
    /// Part of each cycle is Coulomb sliding (2.39).
    Sliding = 3,
}

/// One contact point's tangential data in one direction. Forces may be stresses (and
/// k_T0 a stiffness per area) as long as the units are consistent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    pub law: TangentialLaw,
    pub rule: Rule,
    /// Friction coefficient μ ≥ 0.
    pub mu: f64,
    /// Normal force F_N (compression positive); F_N ≤ 0 is an open contact.
    pub normal_force: f64,
    /// Full-stick tangential stiffness k_T0 > 0.
    pub k_t0: f64,
}

impl Contact {
    /// Rejects NaN/±∞, μ < 0 and k_T0 ≤ 0.
    fn validate(&self) -> Result<(), Error> {
        finite(self.mu, "mu")?;
        finite(self.normal_force, "normal force")?;
        finite(self.k_t0, "k_T0")?;
        if self.mu < 0.0 {
            return Err(Error::OutOfRange("mu must be >= 0"));
        }
        if self.k_t0 <= 0.0 {
            return Err(Error::OutOfRange("k_T0 must be > 0"));
        }
        Ok(())
    }

    /// The point's backbone, or None when it carries no tangential force (open, μ = 0, or
    /// a friction limit so small that δ* underflows).
    pub fn point(&self) -> Result<Option<Point>, Error> {
        self.validate()?;
        let limit = self.mu * self.normal_force;
        if limit.is_infinite() || (limit / self.k_t0).is_infinite() {
            return Err(Error::Overflow("friction limit mu F_N or mu F_N / k_T0"));
        }
        if limit <= 0.0 || !(limit / self.k_t0).is_normal() {
            return Ok(None);
        }
        let backbone = Backbone::new(self.law, limit, self.k_t0)?;
        // μF_N/k_T0 may be a normal double while Mindlin's δ* = 1.5 μF_N/k_T0 is not (fuzz
        // finding: F_N = 1.5e308, μ = 1, k_T0 = 1 returned slip_limit = +inf at A = 0).
        if !backbone.slip_limit().is_finite() {
            return Err(Error::Overflow(
                "slip limit delta* (mu F_N / k_T0 too large)",
            ));
        }
        Ok(Some(Point::new(backbone, self.rule)))
    }
}

/// The linearized point: what a frequency-domain host needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linearization {
    /// Equivalent stiffness k* (3.8), 0 ≤ k* ≤ k_T0.
    pub k_star: f64,
    /// Equivalent viscous damping d* = A_hys/(π ω A²) (3.14), ≥ 0.
    pub d_star: f64,
    /// Loss factor η = A_hys/(π k* A²) (0 when nothing dissipates).
    pub eta: f64,
    /// Energy dissipated per cycle, A_hys ≥ 0 (force × length).
    pub energy_per_cycle: f64,
    /// Peak force of the loop F̂ ≤ μF_N.
    pub peak_force: f64,
    /// Slip limit δ* (0 when open).
    pub slip_limit: f64,
    /// A/δ* (0 when open).
    pub amplitude_ratio: f64,
    pub regime: Regime,
}

/// Below this A/δ* the loop is its small-amplitude limit to double precision: k* = k_T0,
/// F̂ = k_T0 A, A_hys = μF_N δ* (A/δ*)³/2 (Mindlin, both rules) or 0 (Jenkins); the
/// first corrections are relative O(A/δ*) < 1e-17 (k*/k_T0 = 1 − a/(3π) thesis rule,
/// 1 − a/4 Masing, model.md §5 limits). Evaluated from these forms, so that a subnormal or
/// underflowing A/δ* keeps its digits.
const SMALL_RATIO: f64 = 1e-17;

/// The loop in units of the point itself: μF_N = 1, δ* = 1 (k_T0 = 1.5 Mindlin, 1 Jenkins).
struct Normalized {
    /// k*/k_T0 ∈ [0, 1].
    kappa: Wide,
    /// A_hys/(μF_N δ*).
    alpha: Wide,
    /// F̂/μF_N.
    phi: Wide,
    regime: Regime,
}

/// Linearizes a contact point for amplitude A ≥ 0 (length) and angular frequency ω > 0
/// (rad per time unit).
///
/// The loop is evaluated for the point's own scale (μF_N = 1, δ* = 1) and scaled back with
/// products that cannot overflow or underflow on the way (`crate::wide::Wide`), so every output is the
/// correctly scaled double of the normalized result over the whole double range: a
/// subnormal δ* (k_T0 = f64::MAX) or A/δ* (F_N = 1e308, A = 1e-8), a friction limit of
/// 1e-165. An output that is itself beyond the largest double is
/// [`Error::Overflow`]; one below the smallest is 0 or subnormal.
pub fn linearize(
    contact: &Contact,
    amplitude: f64,
    omega: f64,
    method: Method,
) -> Result<Linearization, Error> {
    finite(amplitude, "amplitude")?;
    finite(omega, "omega")?;
    if amplitude < 0.0 {
        return Err(Error::OutOfRange("amplitude must be >= 0"));
    }
    if omega <= 0.0 {
        return Err(Error::OutOfRange("omega must be > 0"));
    }
    let method = method.validate()?;
    contact.validate()?;
    let (mu, f_n, k_t0) = (contact.mu, contact.normal_force, contact.k_t0);
    if (mu * f_n).is_infinite() {
        return Err(Error::Overflow("friction limit mu F_N"));
    }
    if mu == 0.0 || f_n <= 0.0 {
        return Ok(Linearization {
            k_star: 0.0,
            d_star: 0.0,
            eta: 0.0,
            energy_per_cycle: 0.0,
            peak_force: 0.0,
            slip_limit: 0.0,
            amplitude_ratio: 0.0,
            regime: Regime::Open,
        });
    }
    let k0_n = normalized_k_t0(contact.law);
    let limit = Wide::new(mu) * Wide::new(f_n);
    let delta = limit * k0_n / k_t0; // δ* = 1.5 μF_N/k_T0 (2.46), μF_N/k_T0 (Jenkins)
    let slip_limit = delta.to_f64();
    if slip_limit.is_infinite() {
        // Fuzz finding: F_N = 1.5e308, μ = 1, k_T0 = 1 returned slip_limit = +inf at A = 0.
        return Err(Error::Overflow(
            "slip limit delta* (mu F_N / k_T0 too large)",
        ));
    }
    if amplitude == 0.0 {
        return Ok(Linearization {
            k_star: k_t0,
            d_star: 0.0,
            eta: 0.0,
            energy_per_cycle: 0.0,
            peak_force: 0.0,
            slip_limit,
            amplitude_ratio: 0.0,
            regime: Regime::Stick,
        });
    }
    let ratio = Wide::new(amplitude) / delta;
    let amplitude_ratio = ratio.to_f64();
    // A/δ* overflows for a huge amplitude on a point with a tiny slip limit (found by
    // fuzz/jointlin_linearize: k_T0 = 1e300, A = 1e10 gave amplitude_ratio = +inf).
    if amplitude_ratio.is_infinite() {
        return Err(Error::Overflow(
            "A/delta* (amplitude far beyond the slip limit)",
        ));
    }
    let n = if amplitude_ratio < SMALL_RATIO {
        small_amplitude(contact.law, ratio)
    } else {
        normalized(contact.law, contact.rule, amplitude_ratio, method)?
    };
    let energy = limit * delta * n.alpha; // A_hys = μF_N δ* α
    let energy_per_cycle = energy.to_f64();
    if energy_per_cycle.is_infinite() {
        return Err(Error::Overflow("energy per cycle (mu F_N A too large)"));
    }
    let d_star = (energy / (Wide::new(PI) * omega * Wide::new(amplitude) * amplitude)).to_f64(); // (3.14)
    if d_star.is_infinite() {
        return Err(Error::Overflow(
            "d* = A_hys/(pi omega A^2) (omega too small)",
        ));
    }
    // η = A_hys/(π k* A²) = α/(π (k_T0 δ*/μF_N) κ a²), in the point's units.
    let eta = if n.alpha.is_zero() {
        0.0
    } else if n.kappa.is_zero() {
        return Err(Error::Overflow(
            "eta = A_hys/(pi k* A^2) with k* = 0 (too few quadrature points)",
        ));
    } else {
        (n.alpha / (n.kappa * (PI * k0_n) * ratio * ratio)).to_f64()
    };
    if eta.is_infinite() {
        return Err(Error::Overflow("eta = A_hys/(pi k* A^2)"));
    }
    Ok(Linearization {
        k_star: (n.kappa * k_t0).to_f64(),
        d_star,
        eta,
        energy_per_cycle,
        peak_force: (limit * n.phi).to_f64(),
        slip_limit,
        amplitude_ratio,
        regime: n.regime,
    })
}

/// k_T0 of the normalized backbone (μF_N = 1, δ* = 1): δ* = 1.5 μF_N/k_T0 (2.46) for
/// Mindlin, μF_N/k_T0 for Jenkins.
fn normalized_k_t0(law: TangentialLaw) -> f64 {
    match law {
        TangentialLaw::Mindlin => 1.5,
        TangentialLaw::Jenkins => 1.0,
    }
}

/// The loop of half-width a = A/δ* < [`SMALL_RATIO`] in the point's units (leading terms).
fn small_amplitude(law: TangentialLaw, ratio: Wide) -> Normalized {
    let phi = ratio * normalized_k_t0(law); // F̂ = k_T0 A
    match law {
        // A_hys/(μF_N δ*) = 4H(a) (Masing) or 2D(σ_max ≈ a) (thesis) → a³/2, from the
        // factored forms of `Mindlin::iwan_dissipation` and `elastic_split_dissipation`.
        TangentialLaw::Mindlin => Normalized {
            kappa: Wide::new(1.0),
            alpha: ratio * ratio * ratio * 0.5,
            phi,
            regime: Regime::Microslip,
        },
        TangentialLaw::Jenkins => Normalized {
            kappa: Wide::new(1.0),
            alpha: Wide::new(0.0),
            phi,
            regime: Regime::Stick,
        },
    }
}

/// The loop of half-width a = A/δ* ≥ [`SMALL_RATIO`] in the point's units, by `method`;
/// [`Error::Overflow`] where the loop area (≈ 4a) or the quadrature leaves the double range
/// (a beyond ≈ 4e307).
fn normalized(law: TangentialLaw, rule: Rule, a: f64, method: Method) -> Result<Normalized, Error> {
    let k0 = normalized_k_t0(law);
    let b = Backbone::new(law, 1.0, k0).expect("unit backbone is valid");
    let shape = LoopShape::new(&b, rule, a);
    let (sum, area) = match method {
        Method::Graded { points } => (
            hbm::in_phase_sum_graded(&b, rule, &shape, points),
            shape.area,
        ),
        Method::Simpson { intervals: n } => (
            hbm::in_phase_sum_by_rule(&b, rule, &shape, true, n),
            ebm::area_by_rule(&b, rule, &shape, true, n),
        ),
        Method::Gauss { points: n } => (
            hbm::in_phase_sum_by_rule(&b, rule, &shape, false, n),
            ebm::area_by_rule(&b, rule, &shape, false, n),
        ),
    };
    if !sum.is_finite() || !area.is_finite() {
        return Err(Error::Overflow(
            "loop area or in-phase sum (A/delta* beyond about 4e307)",
        ));
    }
    let kappa = match method {
        Method::Graded { .. } if shape.slides() && a >= hbm::TANGENT_FORM_FROM => {
            hbm::stiffness_ratio_sliding(&b, rule, a)
        }
        _ => Wide::new((hbm::k_star_from_sum(sum, a) / k0).clamp(0.0, 1.0)),
    };
    let area = area.max(0.0);
    let regime = if shape.slides() {
        Regime::Sliding
    } else if area == 0.0 || law == TangentialLaw::Jenkins {
        Regime::Stick
    } else {
        Regime::Microslip
    };
    Ok(Normalized {
        kappa,
        alpha: Wide::new(area),
        phi: Wide::new(shape.peak_force),
        regime,
    })
}

#[cfg(test)]
mod tests;
