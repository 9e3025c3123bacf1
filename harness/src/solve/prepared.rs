//! An FE job made ready for its steps, as the run, the loss study, the time domain, the
//! stuck modes (`modes`, `check`, the benches' probes) and the validation's coarse beams
//! start (the backbone, the reduction and the export take a built problem and preload it
//! with their own flags; the column bench always with the nonlinear normal contact): the
//! problem built
//! (`Job::build`) and its static preload step solved (`static_step::solve`, the normal
//! contact nonlinear where the job's `[effects] normal_contact_nonlinearity` says so),
//! with what each cost.

use std::time::Instant;

use thiserror::Error;

use super::static_step::{self, StaticError, StaticState};
use crate::model::{BuildError, Job, Problem};

/// Errors preparing a job: its build or its static step.
#[derive(Debug, Error)]
pub enum PrepareError {
    #[error("building the model: {0}")]
    Build(#[from] BuildError),
    #[error("static preload step: {0}")]
    Static(#[from] StaticError),
}

/// A job's problem after its static preload step.
#[derive(Debug)]
pub struct Prepared {
    pub problem: Problem,
    /// The preloaded state every dynamic step linearizes about.
    pub stat: StaticState,
    /// Wall seconds of the build and of the static step.
    pub build_seconds: f64,
    pub static_seconds: f64,
}

impl Prepared {
    /// Builds `job`'s problem and solves its static step; `progress` is told each
    /// step's name as it starts ("building the model", "static preload step").
    pub fn new(job: &Job, progress: &dyn Fn(&str)) -> Result<Prepared, PrepareError> {
        let t = Instant::now();
        progress("building the model");
        let problem = job.build()?;
        let build_seconds = t.elapsed().as_secs_f64();
        let t = Instant::now();
        progress("static preload step");
        let nonlinear = job.settings.effects.normal_contact_nonlinearity;
        let stat = static_step::solve(&problem, nonlinear)?;
        Ok(Prepared {
            problem,
            stat,
            build_seconds,
            static_seconds: t.elapsed().as_secs_f64(),
        })
    }
}
