//! Loads and supports: `[[preload]]`, `[[clamp]]`, `[[excitation]]`.

use serde::{Deserialize, Serialize};

/// Kind of preload.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum PreloadKind {
    /// Uniform pressure on a box face (force/length², positive in compression).
    Pressure,
    /// A point force at the node nearest `at` (bolt force replaced by point forces).
    Force,
}

/// Box face names (outward normal).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum FaceName {
    XMin,
    XMax,
    YMin,
    YMax,
    ZMin,
    ZMax,
}

/// A static preload of the preload step.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PreloadSpec {
    pub kind: PreloadKind,
    pub body: String,
    /// Face for `pressure`.
    pub face: Option<FaceName>,
    /// Pressure (force/length², positive pushes into the body).
    pub pressure: Option<f64>,
    /// Point for `force` (length): the body's nearest node.
    pub at: Option<[f64; 3]>,
    /// Force vector for `force` (force, global axes).
    pub force: Option<[f64; 3]>,
}

/// Fixed displacements (zero).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ClampSpec {
    pub body: String,
    /// Box face to clamp; omitted for a mass body (its node).
    pub face: Option<FaceName>,
    /// Which components x, y, z are held (default all).
    #[serde(default = "all_components")]
    pub components: [bool; 3],
}

fn all_components() -> [bool; 3] {
    [true; 3]
}

/// Kind of harmonic excitation.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ExcitationKind {
    /// Force amplitude (force) at the node nearest `at`.
    Point,
    /// Traction amplitude (force/length²) uniform on a box face along `direction`.
    Face,
}

/// Harmonic excitation F̂ cos(ωt + φ) along a direction.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ExcitationSpec {
    pub kind: ExcitationKind,
    pub body: String,
    pub at: Option<[f64; 3]>,
    pub face: Option<FaceName>,
    /// Direction (normalized on use).
    pub direction: [f64; 3],
    /// Amplitude: force (point) or traction (face).
    pub amplitude: f64,
    /// Phase φ in degrees.
    #[serde(default)]
    pub phase_deg: f64,
}
