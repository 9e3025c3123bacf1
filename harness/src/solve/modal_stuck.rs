//! The modes of a scene's model with every closed joint stuck: after the static preload
//! step, each closed contact point holds its static normal stiffness and k_T0 in both
//! tangential directions (the sweep's linear base, thesis §4.3 with no microslip), open
//! points hold nothing. These are the resonances a sweep should cover.

use crate::fe::csc::Csc;
use crate::model::{Job, Problem};
use crate::settings::Effects;
use crate::solve::modal::ModalOptions;
use crate::solve::modal_band::{modes_below, BandModes};
use crate::solve::prepared::Prepared;
use crate::solve::static_step::StaticState;
use crate::solve::sweep::Setup;

/// How many modes [`stuck_modes`] looks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModeCount {
    /// Exactly this many (fewer if the model has fewer DOFs).
    Exactly(usize),
    /// Every mode below `factor` × the sweep's highest frequency, at least `min`, at
    /// most `max` (the Lanczos basis holds DOFs × (2·count + 1) numbers).
    Band { factor: f64, min: usize, max: usize },
}

impl ModeCount {
    /// The default of `jointlin modes`: the sweep's band and half as much again, at
    /// least 6 modes, at most 200.
    pub const DEFAULT: ModeCount = ModeCount::Band {
        factor: 1.5,
        min: 6,
        max: 200,
    };
}

/// A scene's model and its stuck modes.
pub struct StuckModes {
    pub problem: Problem,
    pub band: BandModes,
    /// The frequency limit searched up to (1/time); None for [`ModeCount::Exactly`].
    pub limit: Option<f64>,
}

/// K with every closed joint stuck (k_T0 tangential, static normal stiffness), on the
/// problem's pattern, after the static step `stat`, with the run's `effects`.
pub fn stuck_stiffness(
    p: &Problem,
    stat: &StaticState,
    effects: &Effects,
) -> Result<Csc<f64>, String> {
    let mut eff = *effects;
    eff.tangential_microslip = false;
    let setup = Setup::new(p, stat, &eff).map_err(|e| e.to_string())?;
    Ok(Csc {
        pattern: p.sys.pattern.clone(),
        values: setup.base.clone(),
    })
}

/// The stuck modes of a run's model (a scene, a deck or a [`Job`]), as many as `count`
/// asks.
pub fn stuck_modes(job: impl Into<Job>, count: ModeCount) -> Result<StuckModes, String> {
    let job: Job = job.into();
    let Prepared { problem, stat, .. } = Prepared::new(&job, &|_| {}).map_err(|e| e.to_string())?;
    let k = stuck_stiffness(&problem, &stat, &job.settings.effects)?;
    let m = &problem.sys.m;
    let opts = ModalOptions::default();
    let (limit, min, max) = match count {
        ModeCount::Exactly(n) => (None, n, n),
        ModeCount::Band { factor, min, max } => {
            let top = job.settings.frequencies().into_iter().fold(0.0, f64::max);
            (Some(factor * top), min, max)
        }
    };
    let band = modes_below(&k, m, limit.unwrap_or(f64::NAN), min, max, &opts)
        .map_err(|e| e.to_string())?;
    Ok(StuckModes {
        problem,
        band,
        limit,
    })
}
