//! The TOML schema of a scene, as deserialized (before validation).
//!
//! Units are the scene's own and must be consistent; `[units]` states them and every
//! quantity below says which dimension it has. Example (N, mm, s, t):
//! E in N/mm², ρ in t/mm³, pressure in N/mm², stiffness per area in N/mm³,
//! frequency in 1/s = Hz. Every table rejects unknown keys (typos are errors).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::names::{LawName, NormalLawName, RuleName, SchemeName};

mod bodies;
mod contact;
mod loads;
mod lumped;

pub use bodies::*;
pub use contact::*;
pub use loads::*;
pub use lumped::*;

pub use crate::settings::*;

/// The whole scene file.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Free text, echoed in run.json and plot titles.
    #[serde(default)]
    pub title: String,
    /// A deck (`.inp`, path relative to the scene) that provides the model: mesh,
    /// materials, sets, contact, loads and the sweep (see `model_file`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<String>,
    pub units: Units,
    /// Materials by name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub materials: BTreeMap<String, MaterialSpec>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<BodySpec>,
    /// Models given by their matrices (M, K, D from any FE code, a DOF list naming the
    /// rows by point and direction); their points are named `<name>.<point>`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub matrices: Vec<MatricesSpec>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub interfaces: Vec<InterfaceSpec>,
    /// Boxes that move as one where they touch (coincident nodes merged).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ties: Vec<TieSpec>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub preload: Vec<PreloadSpec>,
    /// Screws replaced by two opposite forces from their tightening torque (at nodes,
    /// over a bearing ring or over the engaged thread).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub screws: Vec<ScrewSpec>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub clamp: Vec<ClampSpec>,
    /// Grounded springs and dashpots on lumped (`mass`) bodies.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub springs: Vec<SpringSpec>,
    /// Discrete contact elements between mass bodies or to the ground (lumped models;
    /// read by `jointlin backbone`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointSpec>,
    #[serde(default)]
    pub excitation: Vec<ExcitationSpec>,
    /// Required unless `model` gives it (validation names it missing).
    #[serde(default)]
    pub sweep: SweepSpec,
    #[serde(default)]
    pub iteration: IterationSpec,
    #[serde(default)]
    pub outputs: Vec<OutputSpec>,
    #[serde(default)]
    pub effects: Effects,
    /// Joint power loss against the amplitude of an output at resonance
    /// (`jointlin loss`); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loss_study: Option<LossStudySpec>,
    /// Settings of the time-domain reference (`jointlin run --time-domain`); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_domain: Option<TimeDomainSpec>,
    /// Displacement fields for ParaView at the sweep's peaks or named frequencies
    /// (`jointlin run`); optional.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field_output: Option<FieldOutputSpec>,
}

impl SceneFile {
    /// A lumped system rather than an FE model: `[[matrices]]`, `[[joints]]`, or springs
    /// `between` two bodies (run by the lumped sweep, `jointlin backbone`, the lumped
    /// modes).
    pub fn is_lumped(&self) -> bool {
        !self.matrices.is_empty()
            || !self.joints.is_empty()
            || self.springs.iter().any(|sp| sp.between.is_some())
    }
}
