//! Materials and bodies: `[materials]`, `[[bodies]]` (boxes, graded boxes, masses).

use serde::{Deserialize, Serialize};

/// Linear isotropic elastic material.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Young's modulus E (force/length²).
    #[serde(rename = "E")]
    pub e: f64,
    /// Poisson's ratio ν (−1 < ν < 0.5).
    pub nu: f64,
    /// Density ρ (mass/length³).
    pub rho: f64,
    /// Rayleigh mass-proportional damping α (1/time): D = αM + βK.
    #[serde(default)]
    pub rayleigh_alpha: f64,
    /// Rayleigh stiffness-proportional damping β (time).
    #[serde(default)]
    pub rayleigh_beta: f64,
}

/// Kind of body.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum BodyKind {
    /// Axis-aligned box meshed with hex8 elements: `origin`, `size`, `divisions`, `material`.
    Box,
    /// A lumped point mass (3 translational DOFs): `position`, `mass`.
    Mass,
}

/// One body. Boxes need origin/size/divisions/material; masses need position/mass.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub name: String,
    pub kind: BodyKind,
    /// Box corner with the smallest coordinates (length).
    pub origin: Option<[f64; 3]>,
    /// Box edge lengths (length).
    pub size: Option<[f64; 3]>,
    /// Elements per axis.
    pub divisions: Option<[usize; 3]>,
    /// Element sizes graded per axis (boxes; default equal elements). Example:
    /// `grading = { x = { ratio = 20.0, toward = "both" } }`.
    pub grading: Option<BoxGrading>,
    /// Material name (key of `[materials]`).
    pub material: Option<String>,
    /// Point-mass position (length).
    pub position: Option<[f64; 3]>,
    /// Point mass (mass).
    pub mass: Option<f64>,
}

/// Per-axis grading of a box; an axis left out has equal elements.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct BoxGrading {
    pub x: Option<AxisGrading>,
    pub y: Option<AxisGrading>,
    pub z: Option<AxisGrading>,
}

/// Element sizes along one axis in geometric progression.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AxisGrading {
    /// Largest / smallest element (≥ 1; 1 = equal elements).
    pub ratio: f64,
    /// Where the smallest elements are.
    pub toward: GradeToward,
}

/// End of an axis where a grading puts its smallest elements.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum GradeToward {
    /// The smallest coordinate.
    Min,
    /// The largest coordinate.
    Max,
    /// Both ends (the largest elements in the middle).
    Both,
}

impl BoxGrading {
    /// The three axes' gradings, equal elements where none is given.
    pub fn axes(&self) -> [crate::fe::grading::Grading; 3] {
        use crate::fe::grading::{Grading, Toward};
        [self.x, self.y, self.z].map(|g| match g {
            None => Grading::UNIFORM,
            Some(g) => Grading {
                ratio: g.ratio,
                toward: match g.toward {
                    GradeToward::Min => Toward::Min,
                    GradeToward::Max => Toward::Max,
                    GradeToward::Both => Toward::Both,
                },
            },
        })
    }
}
