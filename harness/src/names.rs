//! Names shared by the inputs and the C-API layer: the contact laws, unloading rules and
//! iteration schemes a scene (or any other input) chooses and [`crate::capi`] maps onto
//! the library's constants, and [`ContactLaw`], an interface's law as every input gives
//! it. They live here, below both, so neither imports the other.

use serde::{Deserialize, Serialize};

/// Highest frequency any input may ask for (1/time): (2πf)² of a higher one overflows.
pub const MAX_FREQUENCY: f64 = 1e150;

/// Tangential contact law.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum LawName {
    /// Hertz–Mindlin microslip (2.49) then Coulomb sliding.
    Mindlin,
    /// Linear spring k_T0 in series with a Coulomb slider.
    Jenkins,
}

/// Unloading rule of the hysteresis loop.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum RuleName {
    /// The thesis's rule: elastic unloading with k_T0, then Mindlin loading (model.md §4).
    #[default]
    Thesis,
    /// Masing (Mindlin–Deresiewicz).
    Masing,
}

/// Normal contact law of an interface (stress form: pressure vs overclosure).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum NormalLawName {
    /// p = k_N·h for overclosure h > 0: `normal_stiffness_per_area` (force/length³).
    Linear,
    /// Hertz (2.34) per point: `hertz_radius` r* (length) and `hertz_e_star` E*
    /// (force/length², (2.31)), spread over the point's tributary area.
    Hertz,
}

/// Amplitude update rule of the thesis mode (the library's, through its iteration
/// store). The fast mode iterates all points at once with Anderson acceleration.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum SchemeName {
    /// a ← a*.
    Direct,
    /// a ← (a + a*)/2 (Fig. 4.14).
    Relaxation,
    /// Secant on ln a with bracketing (library default).
    #[default]
    Secant,
}

/// The contact law of an interface in stress form (per unit area), as a scene's
/// `[[interfaces]]` and a deck's USER surface interaction give it and the model builds
/// its contact points from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    pub law: LawName,
    pub rule: RuleName,
    /// Friction coefficient μ ≥ 0.
    pub mu: f64,
    /// Full-stick tangential stiffness per area k_T0/A (force/length³).
    pub k_t0_per_area: f64,
    pub normal_law: NormalLawName,
    /// Linear normal stiffness per area (force/length³), for [`NormalLawName::Linear`].
    pub normal_stiffness_per_area: Option<f64>,
    /// Hertz effective radius r* (length), for [`NormalLawName::Hertz`].
    pub hertz_radius: Option<f64>,
    /// Hertz effective modulus E* (force/length², (2.31)), for [`NormalLawName::Hertz`].
    pub hertz_e_star: Option<f64>,
}
