//! Names shared by the inputs and the C-API layer: the contact laws, unloading rules and
//! iteration schemes a scene (or any other input) chooses and [`crate::capi`] maps onto
//! the library's constants. They live here, below both, so neither imports the other.

use serde::{Deserialize, Serialize};

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
