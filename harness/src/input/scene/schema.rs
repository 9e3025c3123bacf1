//! The TOML schema of a scene, as deserialized (before validation).
//!
//! Units are the scene's own and must be consistent; `[units]` states them and every
//! quantity below says which dimension it has. Example (N, mm, s, t):
//! E in N/mm², ρ in t/mm³, pressure in N/mm², stiffness per area in N/mm³,
//! frequency in 1/s = Hz. Every table rejects unknown keys (typos are errors).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::names::{LawName, NormalLawName, RuleName, SchemeName};

use super::studies::{FieldOutputSpec, LossStudySpec, TimeDomainSpec};

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
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialSpec>,
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// Models given by their matrices (M, K, D from any FE code, a DOF list naming the
    /// rows by point and direction); their points are named `<name>.<point>`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub matrices: Vec<MatricesSpec>,
    #[serde(default)]
    pub interfaces: Vec<InterfaceSpec>,
    /// Boxes that move as one where they touch (coincident nodes merged).
    #[serde(default)]
    pub ties: Vec<TieSpec>,
    #[serde(default)]
    pub preload: Vec<PreloadSpec>,
    /// Screws replaced by two point forces from their tightening torque.
    #[serde(default)]
    pub screws: Vec<ScrewSpec>,
    #[serde(default)]
    pub clamp: Vec<ClampSpec>,
    /// Grounded springs and dashpots on lumped (`mass`) bodies.
    #[serde(default)]
    pub springs: Vec<SpringSpec>,
    /// Discrete contact elements between mass bodies or to the ground (lumped models;
    /// read by `jointlin backbone`).
    #[serde(default)]
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

/// The scene's unit system, stated (names only; the numbers must be consistent with
/// them: mass = force·time²/length).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Units {
    pub length: String,
    pub force: String,
    pub time: String,
    pub mass: String,
}

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

/// A body and a point on it (length): the body's nearest node.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BodyPoint {
    pub body: String,
    pub at: [f64; 3],
}

/// A screw tightened to `torque`, replaced in the preload step by two equal and
/// opposite point forces: on the head side along `direction` (towards the nut side)
/// and on the nut (thread) side against it. Preload from the torque by the standard
/// screw formula F = T / (0.16·P + 0.58·d₂·μ_G + D_Km/2·μ_K) (VDI 2230).
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
    pub head: BodyPoint,
    pub nut: BodyPoint,
    /// Screw axis from the head towards the nut (normalized on use).
    pub direction: [f64; 3],
}

fn one() -> f64 {
    1.0
}

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

/// A discrete contact element (`[[joints]]`): one tangential direction between two mass
/// bodies (or a mass body and `"ground"`), force form (not per area).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    pub name: String,
    pub between: [String; 2],
    /// Tangential direction (a coordinate axis).
    pub direction: [f64; 3],
    pub law: LawName,
    #[serde(default)]
    pub rule: RuleName,
    /// Friction coefficient μ > 0.
    pub mu: f64,
    /// Normal force F_N > 0 (force).
    pub normal_force: f64,
    /// Tangential stiffness k_T0 > 0 (force/length).
    pub k_t0: f64,
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

/// Frequency spacing of the sweep.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Spacing {
    #[default]
    Linear,
    Log,
}

/// The frequencies of the steady-state step (1/time, Hz for seconds): `count` points
/// from `f_min` to `f_max`, plus the points of any `refine` bands (e.g. around
/// resonances), merged in ascending order. The default (count 0) stands for "absent".
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    pub f_min: f64,
    pub f_max: f64,
    pub count: usize,
    #[serde(default)]
    pub spacing: Spacing,
    #[serde(default)]
    pub refine: Vec<BandSpec>,
    /// Order in which the frequencies are run; each frequency starts from the previous
    /// one's converged state, so multi-valued responses (Duffing) follow their branch.
    #[serde(default)]
    pub direction: Direction,
}

/// Sweep direction.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Ascending frequencies.
    #[default]
    Up,
    /// Descending frequencies.
    Down,
    /// Ascending, then a second sweep descending (results_down.csv).
    UpDown,
}

/// An extra band of frequencies, linearly spaced.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BandSpec {
    pub f_min: f64,
    pub f_max: f64,
    pub count: usize,
}

/// Iteration mode of the steady-state step.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Mode {
    /// One factorization per frequency, contact iterations on the condensed system.
    #[default]
    Fast,
    /// The thesis's multi-pass UEXTERNALDB scheme (§4.3.2).
    Thesis,
    /// Multi-harmonic balance (`harmonics`, `samples`): the contact loops marched in time
    /// through the C API, the linear part condensed onto the contacts per harmonic.
    HarmonicBalance,
}

/// Amplitude-consistency iteration.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct IterationSpec {
    #[serde(default)]
    pub mode: Mode,
    /// Relative amplitude tolerance |a − a*| ≤ tol·max(a*, floor).
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    #[serde(default)]
    pub scheme: SchemeName,
    /// Most passes (thesis) or contact iterations per frequency (fast).
    #[serde(default = "default_max_passes")]
    pub max_passes: usize,
    /// Amplitude estimate (length) of the first frequency increment.
    #[serde(default = "default_initial_amplitude")]
    pub initial_amplitude: f64,
    /// Harmonic balance: harmonics H (zeroth included besides); required by that mode.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub harmonics: Option<usize>,
    /// Harmonic balance: samples N per period (default 16(H + 1) rounded up to a power
    /// of two, at least 64).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub samples: Option<usize>,
}

fn default_tolerance() -> f64 {
    1e-3
}
fn default_max_passes() -> usize {
    50
}
fn default_initial_amplitude() -> f64 {
    1e-9
}

impl Default for IterationSpec {
    fn default() -> Self {
        IterationSpec {
            mode: Mode::default(),
            tolerance: default_tolerance(),
            scheme: SchemeName::default(),
            max_passes: default_max_passes(),
            initial_amplitude: default_initial_amplitude(),
            harmonics: None,
            samples: None,
        }
    }
}

/// A named output: the displacement of the body's node nearest `at` along `direction`.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    pub name: String,
    pub body: String,
    /// Point (length); ignored for a mass body.
    pub at: Option<[f64; 3]>,
    pub direction: [f64; 3],
}

/// Physics and output switches: the engine runs only what is on.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(deny_unknown_fields, default)]
pub struct Effects {
    /// Static step with the library's normal law by Newton (open points stay open);
    /// off: constant normal springs, one linear static solve, no open/close.
    pub normal_contact_nonlinearity: bool,
    /// Tangential k* from the library's linearization; off: constant k_T0 and no
    /// linearization calls at all.
    pub tangential_microslip: bool,
    /// Coulomb sliding allowed; off: the amplitude handed to the linearization is
    /// capped at the slip limit δ* (and the cap is counted in the run log).
    pub macroslip: bool,
    /// Equivalent contact damping d* in the dynamic stiffness; off: d* = 0.
    pub contact_damping: bool,
    /// Rayleigh damping of the materials and the springs' dashpots; off: none.
    pub material_damping: bool,
    /// points.csv: per point and frequency amplitude, k*, d*, energy, A/δ*.
    pub point_energy_output: bool,
    /// Regime (stick/microslip/sliding) per point and frequency, stick_slip.csv/svg.
    pub stick_slip_map: bool,
}

impl Default for Effects {
    fn default() -> Self {
        Effects {
            normal_contact_nonlinearity: true,
            tangential_microslip: true,
            macroslip: true,
            contact_damping: true,
            material_damping: true,
            point_energy_output: false,
            stick_slip_map: false,
        }
    }
}
