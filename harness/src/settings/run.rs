//! The settings of one run together: what the solvers, the time domain and the reports
//! read of an input, whichever reader filled them (a scene's tables, a deck's steps and
//! the shim's configuration).

use super::studies::{FieldOutputSpec, LossStudySpec, TimeDomainSpec};
use super::study::{Effects, IterationSpec, OutputSpec, SweepSpec};
use super::units::Units;

/// Every setting of a run; a study varies these (the mode, the effects, the band) and
/// builds the model of its input with them.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSettings {
    /// The input's title (free text; plot titles and run.json; may be empty).
    pub title: String,
    pub units: Units,
    pub sweep: SweepSpec,
    pub iteration: IterationSpec,
    pub outputs: Vec<OutputSpec>,
    pub effects: Effects,
    pub loss_study: Option<LossStudySpec>,
    pub time_domain: Option<TimeDomainSpec>,
    pub field_output: Option<FieldOutputSpec>,
}

impl RunSettings {
    /// The sweep's frequencies (1/time): [`SweepSpec::frequencies`].
    pub fn frequencies(&self) -> Vec<f64> {
        self.sweep.frequencies()
    }

    /// These settings with the contact points as the thesis's model: both `[effects]`
    /// switches of the three-direction point off (`normal_load_variation`,
    /// `coupled_slip`), so each point or joint with `normal` is two independent
    /// tangential directions at its static normal force (the first-order rungs, and the
    /// linearization a backbone with points starts from).
    pub fn thesis_points(&self) -> RunSettings {
        let mut s = self.clone();
        s.effects.normal_load_variation = false;
        s.effects.coupled_slip = false;
        s
    }
}
