//! Contact laws: pure functions of one contact point, no state, no allocation.
//!
//! Units are the caller's and consistent (N, mm or N, m, …); forces may equally be
//! stresses and stiffnesses per unit area (the FE "stress form").
//!
//! * [`hertz`]: normal contact of two curved bodies (2.31–2.35) and the per-area
//!   stress form used by FE hosts.
//! * [`mindlin`]: tangential microslip backbone (2.44–2.49) ending in Coulomb sliding (2.39).
//! * [`jenkins`]: linear spring + Coulomb slider, the classical cross-check.
//! * [`cubic`]: the Duffing oscillator's cubic spring k·x + α·x³ (4.1), not a contact law.
//! * [`screw`]: preload of a screw from its tightening torque (VDI 2230), for hosts that
//!   replace a screw by point forces (thesis §5.4.1).
//! * [`Backbone`]: the virgin curve of either tangential law behind one interface, used by
//!   the hysteresis and the linearization.

pub mod cubic;
pub mod hertz;
pub mod jenkins;
pub mod mindlin;
pub mod screw;

mod series;

pub use cubic::CubicSpring;
pub use jenkins::Jenkins;
pub use mindlin::Mindlin;

use crate::error::Error;

/// Which tangential law a contact point follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TangentialLaw {
    /// Hertz–Mindlin microslip (2.49) followed by Coulomb sliding (2.39).
    Mindlin,
    /// Linear spring k_T0 in series with a Coulomb slider at μF_N.
    Jenkins,
}

/// The virgin tangential curve F = g(s) (s ≥ 0 the slip distance from the last
/// zero-force point, F ≥ 0 its magnitude) of one contact point, for either law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Backbone {
    Mindlin(Mindlin),
    Jenkins(Jenkins),
}

impl Backbone {
    /// Builds the backbone for a law from the friction limit μF_N (> 0) and the initial
    /// tangential stiffness k_T0 (> 0). Both must be finite.
    pub fn new(law: TangentialLaw, friction_limit: f64, k_t0: f64) -> Result<Self, Error> {
        if !friction_limit.is_finite() || !k_t0.is_finite() {
            return Err(Error::NonFinite("friction limit or k_T0"));
        }
        if friction_limit <= 0.0 || k_t0 <= 0.0 {
            return Err(Error::OutOfRange("friction limit and k_T0 must be > 0"));
        }
        Ok(match law {
            TangentialLaw::Mindlin => Backbone::Mindlin(Mindlin::new(friction_limit, k_t0)),
            TangentialLaw::Jenkins => Backbone::Jenkins(Jenkins::new(friction_limit, k_t0)),
        })
    }

    /// Friction limit μF_N (force).
    pub fn friction_limit(&self) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.friction_limit,
            Backbone::Jenkins(j) => j.friction_limit,
        }
    }

    /// Initial tangential stiffness k_T0 (force/length).
    pub fn k_t0(&self) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.k_t0,
            Backbone::Jenkins(j) => j.k_t0,
        }
    }

    /// Slip limit δ* (length): where the virgin curve reaches μF_N.
    pub fn slip_limit(&self) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.slip_limit(),
            Backbone::Jenkins(j) => j.slip_limit(),
        }
    }

    /// Force magnitude g(s) on the virgin curve, s ≥ 0.
    pub fn force(&self, s: f64) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.force(s),
            Backbone::Jenkins(j) => j.force(s),
        }
    }

    /// Tangent dg/ds, s ≥ 0.
    pub fn tangent(&self, s: f64) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.tangent(s),
            Backbone::Jenkins(j) => j.tangent(s),
        }
    }

    /// Inverse s = g⁻¹(F) for 0 ≤ F < μF_N; returns δ* for F ≥ μF_N.
    pub fn inverse(&self, force: f64) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.inverse(force),
            Backbone::Jenkins(j) => j.inverse(force),
        }
    }

    /// Work along the virgin curve, G(s) = ∫₀ˢ g, s ≥ 0.
    pub fn work(&self, s: f64) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.work(s),
            Backbone::Jenkins(j) => j.work(s),
        }
    }

    /// Energy dissipated along the virgin curve by the equivalent parallel-slider (Iwan)
    /// picture, H(s) = ∫₀ˢ (g − t g') dt = 2G(s) − s g(s) ≥ 0. Used for Masing branches.
    pub fn iwan_dissipation(&self, s: f64) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.iwan_dissipation(s),
            Backbone::Jenkins(j) => j.iwan_dissipation(s),
        }
    }
}

impl Backbone {
    /// Energy dissipated along the virgin curve when the elastic energy is taken as
    /// F²/(2k_T0) (the split that matches the thesis rule's elastic unloading):
    /// D(s) = G(s) − g(s)²/(2k_T0) ≥ 0. Half the thesis loop area, see `linearize`.
    pub fn elastic_split_dissipation(&self, s: f64) -> f64 {
        match self {
            Backbone::Mindlin(m) => m.elastic_split_dissipation(s),
            Backbone::Jenkins(j) => (j.friction_limit * (s - j.slip_limit())).max(0.0),
        }
    }
}

/// Normalized Mindlin force G(σ) = 1 − (1 − σ)^{3/2} (2.49 divided by μF_N), exact to rounding.
pub fn mindlin_normalized_force(sigma: f64) -> f64 {
    series::one_minus_pow(1.5, sigma)
}
