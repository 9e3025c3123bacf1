//! What a run computes: `[sweep]`, `[iteration]`, `[[outputs]]`, `[effects]`.

use serde::{Deserialize, Serialize};

use crate::names::SchemeName;

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
/// Most modes the modal route keeps when `[sweep] modes` is not given (its band of
/// modes below a multiple of the sweep's top); also what the memory estimate counts then.
pub const MODAL_MAX_MODES: usize = 500;

#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Absent in a scene over a deck (the deck's step gives them); the validation
    /// requires them otherwise.
    #[serde(default)]
    pub f_min: f64,
    #[serde(default)]
    pub f_max: f64,
    #[serde(default)]
    pub count: usize,
    #[serde(default)]
    pub spacing: Spacing,
    /// Bias p of the points toward both ends (Abaqus's steady-state bias parameter):
    /// p = 1 even spacing, p > 1 denser near f_min and f_max ([`biased`]).
    #[serde(default = "unbiased", skip_serializing_if = "is_unbiased")]
    pub bias: f64,
    #[serde(default)]
    pub refine: Vec<BandSpec>,
    /// Order in which the frequencies are run; each frequency starts from the previous
    /// one's converged state, so multi-valued responses (Duffing) follow their branch.
    #[serde(default)]
    pub direction: Direction,
    /// How each frequency's linear part is solved: `direct` (a sparse factorization of
    /// the dynamic stiffness per frequency) or `modal` (the structure's modes with every
    /// joint stuck, plus the static residual flexibility of the omitted ones; first order,
    /// mode fast).
    #[serde(default)]
    pub method: SweepMethod,
    /// Modal route: the number of modes (default: every mode below 4 × `f_max`, × H in
    /// the harmonic balance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Modal route: add the omitted modes' static residual flexibility (default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual: Option<bool>,
    /// How the range and each band are divided: `range` (`count` points over the whole
    /// range) or `eigenfrequency` (Abaqus's INTERVAL=EIGENFREQUENCY: `count` points, ends
    /// included, from `f_min` to the first stuck eigenfrequency inside the range, between
    /// each two and from the last to `f_max`, biased toward the ends by `bias`).
    #[serde(default)]
    pub interval: Interval,
    /// Modal damping of the stuck modes (modal route only), summed where ranges overlap.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub modal_damping: Vec<ModalDampingSpec>,
}

/// How a frequency range is divided into points.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Interval {
    #[default]
    Range,
    Eigenfrequency,
}

/// Viscous modal damping of modes `first_mode`…`last_mode` (1-based, inclusive; absent:
/// every mode): the fraction of critical damping ζ_r = `ratio` + α/(2ω_r) + βω_r/2
/// (`alpha` in 1/time, `beta` in time; Rayleigh's form as Abaqus's `*MODAL DAMPING,
/// RAYLEIGH` states it per mode).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ModalDampingSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_mode: Option<usize>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub last_mode: Option<usize>,
    #[serde(default)]
    pub ratio: f64,
    #[serde(default)]
    pub alpha: f64,
    #[serde(default)]
    pub beta: f64,
}

impl ModalDampingSpec {
    /// ζ of mode `r` (1-based) with circular frequency ω_r (rad/time); 0 outside the range.
    pub fn ratio_of(&self, r: usize, omega_r: f64) -> f64 {
        let inside =
            self.first_mode.is_none_or(|a| r >= a) && self.last_mode.is_none_or(|b| r <= b);
        if !inside {
            return 0.0;
        }
        let mut z = self.ratio;
        if self.alpha != 0.0 {
            z += self.alpha / (2.0 * omega_r);
        }
        z + self.beta * omega_r / 2.0
    }
}

/// How the steady-state step solves its linear part.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum SweepMethod {
    #[default]
    Direct,
    Modal,
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

/// An extra band of frequencies, linearly spaced (with `bias`, denser toward its ends).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BandSpec {
    pub f_min: f64,
    pub f_max: f64,
    pub count: usize,
    #[serde(default = "unbiased", skip_serializing_if = "is_unbiased")]
    pub bias: f64,
}

fn unbiased() -> f64 {
    1.0
}

fn is_unbiased(p: &f64) -> bool {
    *p == 1.0
}

/// Position t ∈ [0, 1] of a point in its range after the bias p: with y = 2t − 1,
/// y' = sign(y)|y|^{1/p} (the spacing of Abaqus's steady-state bias parameter: p > 1
/// moves points toward both ends), t' = (y' + 1)/2; p = 1 leaves t unchanged.
pub fn biased(t: f64, p: f64) -> f64 {
    if p == 1.0 {
        return t;
    }
    let y = 2.0 * t - 1.0;
    (y.signum() * y.abs().powf(1.0 / p) + 1.0) / 2.0
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

impl Mode {
    /// The name a scene writes (`fast`, `thesis`, `harmonic_balance`).
    pub fn name(self) -> &'static str {
        match self {
            Mode::Fast => "fast",
            Mode::Thesis => "thesis",
            Mode::HarmonicBalance => "harmonic_balance",
        }
    }
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
    /// Harmonic balance only: each closed point's normal direction joins the balance and
    /// the normal force N(t) follows the normal law within the cycle (load variation,
    /// separation; slip limit μN(t)), through the library's three-direction point.
    pub normal_load_variation: bool,
    /// Harmonic balance only: a point's two tangential directions slip under one
    /// circular limit ‖t‖ ≤ μN (the library's three-direction point) instead of as two
    /// independent points.
    pub coupled_slip: bool,
}

impl Effects {
    /// These effects for a first-order (fast) sweep: the harmonic-balance-only effects
    /// off (the reference and field sweeps of a run use the thesis's point model).
    pub fn first_order(self) -> Self {
        Effects {
            normal_load_variation: false,
            coupled_slip: false,
            ..self
        }
    }
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
            normal_load_variation: false,
            coupled_slip: false,
        }
    }
}
