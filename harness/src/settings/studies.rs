//! The study tables of a scene: `[loss_study]` (read by the loss study),
//! `[time_domain]` (the time-domain reference's settings, resolved by
//! `time::TimeSettings`) and `[field_output]` (the displacement fields `jointlin run`
//! writes for ParaView). Settings of the studies that read them.

use serde::{Deserialize, Serialize};

/// The `[loss_study]` table of a scene.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LossStudySpec {
    /// Named output whose amplitude is set (e.g. the sonotrode's blade-side end face).
    pub output: String,
    /// Target amplitudes of the output (length), ascending.
    pub amplitudes: Vec<f64>,
    /// Screw whose torque the study varies (a `[[screws]]` name).
    pub screw: String,
    /// Torques (force·length), one curve each.
    pub torques: Vec<f64>,
    /// Fraction of the structure in the model (0.5 for a half model): the reported
    /// power is the model's divided by it.
    #[serde(default = "one")]
    pub model_share: f64,
    /// Name of the reported power unit and its size in scene power units
    /// (force·length/time): "W" and 1e-3 for N·mm/s.
    pub power_unit: String,
    pub power_factor: f64,
    /// Name of the reported amplitude unit and the scene lengths per reported unit
    /// ("µm" and 1e-3 for mm).
    pub amplitude_unit: String,
    pub amplitude_factor: f64,
    /// Measured (or published) points to compare with: torque, amplitude (scene units),
    /// power (reported unit). Without `calibration`, the first one is the target of
    /// `jointlin loss --calibrate`.
    #[serde(default)]
    pub reference: Vec<ReferencePoint>,
    /// What `jointlin loss --calibrate` fits, and to which reference points.
    #[serde(default)]
    pub calibration: Option<CalibrationSpec>,
}

/// Contact parameters fitted to reference points: one factor per parameter on every
/// interface, as many parameters as points (a square system).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CalibrationSpec {
    pub parameters: Vec<CalibratedParameter>,
    /// Indices into `reference` (0 = the first point).
    pub points: Vec<usize>,
}

/// A contact parameter a calibration may scale.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum CalibratedParameter {
    /// The tangential stiffness per area `k_t0_per_area`.
    KT0,
    /// The friction coefficient `mu`.
    Mu,
}

impl CalibratedParameter {
    /// The scene key it scales.
    pub fn key(self) -> &'static str {
        match self {
            CalibratedParameter::KT0 => "k_t0_per_area",
            CalibratedParameter::Mu => "mu",
        }
    }
}

fn one() -> f64 {
    1.0
}

/// A published power-loss level.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ReferencePoint {
    pub torque: f64,
    pub amplitude: f64,
    pub power: f64,
    /// Where the number comes from.
    #[serde(default)]
    pub note: String,
    /// The deviation the source reports for its own model there (percent), if any.
    #[serde(default)]
    pub source_deviation_percent: Option<f64>,
}

/// Which integrator.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    /// RK4 for up to `time::settings::AUTO_RK4_MAX_DOFS` (12) free DOFs, else Newmark.
    #[default]
    Auto,
    Rk4,
    Newmark,
}

/// Initial state.
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum Start {
    /// The static preload state at rest; the excitation is ramped in.
    #[default]
    Rest,
    /// The steady state of the linear model with every closed point stuck (k_T0),
    /// excitation at full amplitude from t = 0 (shortens the settling of lightly damped
    /// FE models).
    Linear,
}

/// Periods run at least and at most per frequency when `[time_domain]` does not say.
pub const DEFAULT_MIN_CYCLES: usize = 3;
pub const DEFAULT_MAX_CYCLES: usize = 2000;
/// Time steps per forcing period: at least 8 (the periodicity test's harmonics), at
/// most 2^20 (beyond any accuracy the steps could buy; bounds each period's work).
pub const MIN_STEPS_PER_CYCLE: usize = 8;
pub const MAX_STEPS_PER_CYCLE: usize = 1 << 20;

/// The scene's `[time_domain]` table (all keys optional).
#[derive(Debug, Clone, Copy, Deserialize, Serialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct TimeDomainSpec {
    #[serde(default)]
    pub integrator: Integrator,
    pub steps_per_cycle: Option<usize>,
    pub ramp_cycles: Option<f64>,
    #[serde(default)]
    pub start: Start,
    pub tolerance: Option<f64>,
    pub min_cycles: Option<usize>,
    pub max_cycles: Option<usize>,
    /// HHT-α of the implicit integrator, in [−1/3, 0].
    pub alpha: Option<f64>,
}

/// The `[field_output]` table: displacement fields (`field_<frequency>.vtu`) that
/// `jointlin run` writes for ParaView, each solved once more at its frequency in fast
/// mode (first order) with the run's static state.
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FieldOutputSpec {
    /// At the `peaks` highest resonance peaks (local maxima over the sweep) of the first
    /// `[[outputs]]` amplitude, converged frequencies only.
    #[serde(default)]
    pub peaks: usize,
    /// And at these frequencies (1/time).
    #[serde(default)]
    pub frequencies: Vec<f64>,
}
