//! Lumped and reduced models: `[[matrices]]`, `[[joints]]`, `[[springs]]`.

use serde::{Deserialize, Serialize};

use super::*;

/// A model given by its matrices (`[[matrices]]`, read by `input::matrices`): Matrix
/// Market files (paths relative to the scene) in the scene's units, and the DOF list.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MatricesSpec {
    /// Prefix of its points: `<name>.<point>` in joints, springs, clamps, loads, outputs.
    pub name: String,
    /// M (mass).
    pub mass: String,
    /// K (force/length).
    pub stiffness: String,
    /// D (force·time/length), optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<String>,
    /// The DOF list: a CSV file of `point,direction` rows, or the rows inline.
    pub dofs: DofsSpec,
}

/// A DOF list: a file, or its rows inline (`["tip,x", "tip,y", "modal,1"]`).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(untagged)]
pub enum DofsSpec {
    File(String),
    Inline(Vec<String>),
}

/// A discrete contact element (`[[joints]]`) between two mass bodies or `[[matrices]]`
/// points (or one and `"ground"`), force form (not per area): one tangential direction
/// at a fixed normal force, or with `normal` a three-direction point (docs/contact3d.md):
/// a linear unilateral normal law N = max(0, −k_N·g), g the displacement of the second
/// end relative to the first along `normal`, zero where the bodies start (touching), and
/// two tangential directions, `direction` and normal × direction.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    pub name: String,
    pub between: [String; 2],
    /// Tangential direction (a coordinate axis); with `normal` the first tangential axis.
    pub direction: [f64; 3],
    pub law: LawName,
    #[serde(default)]
    pub rule: RuleName,
    /// Friction coefficient μ > 0.
    pub mu: f64,
    /// Normal force F_N > 0 (force). Without `normal` required; with it the force the
    /// joint carries where the bodies start (a preload inside the joint), else the
    /// static step's normal force.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_force: Option<f64>,
    /// Tangential stiffness k_T0 > 0 (force/length).
    pub k_t0: f64,
    /// Normal direction (a coordinate axis, pointing from the first end of `between` to
    /// the second: the gap opens when the second end moves along it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<[f64; 3]>,
    /// Normal stiffness k_N > 0 (force/length), with `normal`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal_stiffness: Option<f64>,
}

/// A spring and dashpot on a mass body (grounded) or `between` two bodies along a
/// direction: force
/// k·x + α·x³ + c·ẋ for the elongation x along it (the Duffing oscillator (4.1) with
/// α ≠ 0).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    /// The mass body the spring grounds (or `between`).
    #[serde(default)]
    pub body: String,
    /// Two mass bodies, or a mass body and `"ground"`, the spring connects (instead of
    /// `body`; read by `jointlin backbone`).
    #[serde(default)]
    pub between: Option<[String; 2]>,
    /// Direction (normalized on use).
    pub direction: [f64; 3],
    /// Linear stiffness k (force/length).
    pub stiffness: f64,
    /// Cubic coefficient α (force/length³; < 0 softening). Linearized per frequency by the
    /// library (k* = k + ¾αA², (3.8)) for the spring's amplitude A, iterated to
    /// consistency like a contact point.
    #[serde(default)]
    pub cubic: f64,
    /// Viscous damping c (force·time/length).
    #[serde(default)]
    pub damping: f64,
}
