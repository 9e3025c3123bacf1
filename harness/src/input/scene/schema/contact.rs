//! Contact and joining: `[[interfaces]]`, `[[ties]]`, `[[screws]]`.

use serde::{Deserialize, Serialize};

use super::*;
use crate::names::ContactLaw;

/// A contact interface between two bodies: the z-max face of the first touches the
/// z-min face of the second (coincident nodes), or `ground` and a `mass` body.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    pub name: String,
    /// `[lower, upper]` body names; `"ground"` may be the lower one of a mass body.
    pub between: [String; 2],
    pub law: LawName,
    #[serde(default)]
    pub rule: RuleName,
    /// Friction coefficient μ ≥ 0.
    pub mu: f64,
    /// Full-stick tangential stiffness per area k_T0/A (force/length³).
    pub k_t0_per_area: f64,
    pub normal_law: NormalLawName,
    /// Linear normal stiffness per area (force/length³), for `normal_law = "linear"`;
    /// also the constant normal stiffness when `normal_contact_nonlinearity = false`.
    pub normal_stiffness_per_area: Option<f64>,
    /// Hertz effective radius r* (length), for `normal_law = "hertz"`.
    pub hertz_radius: Option<f64>,
    /// Hertz effective modulus E* (force/length²), for `normal_law = "hertz"`.
    pub hertz_e_star: Option<f64>,
    /// Contact area (length²) of a ground–mass interface (box interfaces use the
    /// nodes' tributary areas).
    pub area: Option<f64>,
    /// Initial normal gap g₀ ≥ 0 (length) between the coincident faces: the normal law
    /// sees the overclosure h = −δ_n − g₀, so the faces touch only once the preload has
    /// closed g₀ (a slot wider than the part it holds).
    #[serde(default)]
    pub initial_gap: f64,
    /// Regions taken out of the contact face: element faces of the lower body whose
    /// centre lies inside one of these boxes carry no contact (a relieved face).
    #[serde(default)]
    pub exclude: Vec<RegionSpec>,
    /// Sub-grid sampling of each point's tributary area (box interfaces): s × s samples
    /// per quarter element face, overclosure interpolated from the face's nodes, the
    /// point's law averaged over them (`model::subgrid`; the friction law's samples are
    /// split further where the static patch edge crosses them). Absent: the law at the node
    /// alone, over its whole area (the thesis's node-based contact).
    #[serde(default)]
    pub area_samples: Option<usize>,
}

impl InterfaceSpec {
    /// The interface's contact law (stress form).
    pub fn contact_law(&self) -> ContactLaw {
        ContactLaw {
            law: self.law,
            rule: self.rule,
            mu: self.mu,
            k_t0_per_area: self.k_t0_per_area,
            normal_law: self.normal_law,
            normal_stiffness_per_area: self.normal_stiffness_per_area,
            hertz_radius: self.hertz_radius,
            hertz_e_star: self.hertz_e_star,
        }
    }
}

/// An axis-aligned region `min ≤ x ≤ max` (length).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RegionSpec {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl RegionSpec {
    /// Whether `p` lies inside (boundary included).
    pub fn contains(&self, p: [f64; 3]) -> bool {
        (0..3).all(|a| p[a] >= self.min[a] && p[a] <= self.max[a])
    }
}

/// Two boxes tied where they touch: their coincident boundary nodes move as one (the
/// meshes must conform there).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TieSpec {
    pub between: [String; 2],
}

/// One end of a screw: the body it loads and a point on the screw axis there (length).
/// Without `bearing` or `thread` the force acts at the body's node nearest `at`.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ScrewEnd {
    /// The body, or several tied boxes the ring or the thread crosses.
    pub body: BodyNames,
    pub at: [f64; 3],
    /// Inner and outer diameter of a bearing ring (length): the force as a uniform
    /// pressure on the body's element faces in the plane through `at` normal to the
    /// axis, between these radii (a head or a nut on its bearing face).
    #[serde(default)]
    pub bearing: Option<[f64; 2]>,
    /// An engaged thread: the force as a uniform force per volume in the cylinder of
    /// this diameter around the axis, from `at` over `length` towards the other end
    /// (a screw in a threaded hole).
    #[serde(default)]
    pub thread: Option<ThreadSpec>,
}

/// One body's name or several.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(untagged)]
pub enum BodyNames {
    One(String),
    Many(Vec<String>),
}

impl BodyNames {
    /// The names, in the scene's order.
    pub fn names(&self) -> Vec<&str> {
        match self {
            BodyNames::One(n) => vec![n.as_str()],
            BodyNames::Many(v) => v.iter().map(String::as_str).collect(),
        }
    }
}

/// The engaged part of a thread (length).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ThreadSpec {
    pub diameter: f64,
    pub length: f64,
}

/// A screw tightened to `torque`, replaced in the preload step by two equal and
/// opposite forces: on the head side along `direction` (towards the nut side) and on
/// the nut (thread) side against it, each at a node, over a bearing ring or over the
/// engaged thread ([`ScrewEnd`]). Preload from the torque by the standard screw formula
/// F = T / (0.16·P + 0.58·d₂·μ_G + D_Km/2·μ_K) (VDI 2230).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ScrewSpec {
    pub name: String,
    /// Tightening torque T (force·length).
    pub torque: f64,
    /// Thread pitch P (length).
    pub pitch: f64,
    /// Flank (pitch) diameter d₂ (length).
    pub d2: f64,
    /// Thread friction coefficient μ_G.
    pub mu_thread: f64,
    /// Head (bearing) friction coefficient μ_K.
    pub mu_head: f64,
    /// Effective friction diameter of the head bearing D_Km (length).
    pub d_km: f64,
    /// Share of the screw in the model (0.5 for a screw cut by a symmetry plane).
    #[serde(default = "one")]
    pub share: f64,
    pub head: ScrewEnd,
    pub nut: ScrewEnd,
    /// Screw axis from the head towards the nut (normalized on use).
    pub direction: [f64; 3],
}

fn one() -> f64 {
    1.0
}
