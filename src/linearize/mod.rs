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
use loop_shape::LoopShape;

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
    /// Plain Gauss–Legendre with `points` over θ and over x, no splitting at the kinks.
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
    fn validate(self) -> Result<Self, Error> {
        let ok = match self {
            Method::Graded { points } | Method::Gauss { points } => {
                (1..=quadrature::MAX_GAUSS_POINTS).contains(&points)
            }
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
    /// The point's backbone, or None when it carries no tangential force (open, μ = 0, or
    /// a friction limit so small that δ* underflows).
    pub fn point(&self) -> Result<Option<Point>, Error> {
        finite(self.mu, "mu")?;
        finite(self.normal_force, "normal force")?;
        finite(self.k_t0, "k_T0")?;
        if self.mu < 0.0 {
            return Err(Error::OutOfRange("mu must be >= 0"));
        }
        if self.k_t0 <= 0.0 {
            return Err(Error::OutOfRange("k_T0 must be > 0"));
        }
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

/// Linearizes a contact point for amplitude A ≥ 0 (length) and angular frequency ω > 0
/// (rad per time unit).
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
    match contact.point()? {
        None => Ok(Linearization {
            k_star: 0.0,
            d_star: 0.0,
            eta: 0.0,
            energy_per_cycle: 0.0,
            peak_force: 0.0,
            slip_limit: 0.0,
            amplitude_ratio: 0.0,
            regime: Regime::Open,
        }),
        Some(point) => linearize_point(&point, amplitude, omega, method),
    }
}

/// As [`linearize`] for a point with a backbone (the checks on A, ω and the method are the
/// caller's).
pub fn linearize_point(
    point: &Point,
    amplitude: f64,
    omega: f64,
    method: Method,
) -> Result<Linearization, Error> {
    let b = &point.backbone;
    let delta_star = b.slip_limit();
    let k0 = b.k_t0();
    // Zero or subnormal A (round-off in a welded joint): the stick limit, where F/A
    // would have lost its digits (k* came out 641 for k_T0 = 1e5 at A = 1e-320).
    if amplitude < f64::MIN_POSITIVE {
        return Ok(Linearization {
            k_star: k0,
            d_star: 0.0,
            eta: 0.0,
            energy_per_cycle: 0.0,
            peak_force: 0.0,
            slip_limit: delta_star,
            amplitude_ratio: 0.0,
            regime: Regime::Stick,
        });
    }
    let shape = LoopShape::new(b, point.rule, amplitude);
    let (sum, area) = match method {
        Method::Graded { points } => (
            hbm::in_phase_sum_graded(b, point.rule, &shape, points),
            shape.area,
        ),
        Method::Simpson { intervals: n } => (
            hbm::in_phase_sum_by_rule(b, point.rule, &shape, true, n),
            ebm::area_by_rule(b, point.rule, &shape, true, n),
        ),
        Method::Gauss { points: n } => (
            hbm::in_phase_sum_by_rule(b, point.rule, &shape, false, n),
            ebm::area_by_rule(b, point.rule, &shape, false, n),
        ),
    };
    let k_star = hbm::k_star_from_sum(sum, amplitude).clamp(0.0, k0);
    let area = area.max(0.0);
    let d_star = ebm::viscous_damping(area, amplitude, omega);
    let eta = if area == 0.0 {
        0.0
    } else {
        ebm::loss_factor(area, amplitude, k_star)
    };
    if !d_star.is_finite() || !eta.is_finite() || !k_star.is_finite() {
        return Err(Error::Overflow("d* or eta (amplitude or omega too small)"));
    }
    // A/δ* overflows for a huge amplitude on a point with a tiny slip limit (found by
    // fuzz/jointlin_linearize: k_T0 = 1e300, A = 1e10 gave amplitude_ratio = +inf).
    let amplitude_ratio = amplitude / delta_star;
    if !amplitude_ratio.is_finite() {
        return Err(Error::Overflow(
            "A/delta* (amplitude far beyond the slip limit)",
        ));
    }
    let regime = if shape.slides() {
        Regime::Sliding
    } else if area == 0.0 || matches!(b, Backbone::Jenkins(_)) {
        Regime::Stick
    } else {
        Regime::Microslip
    };
    Ok(Linearization {
        k_star,
        d_star,
        eta,
        energy_per_cycle: area,
        peak_force: shape.peak_force,
        slip_limit: delta_star,
        amplitude_ratio,
        regime,
    })
}

#[cfg(test)]
mod tests;
