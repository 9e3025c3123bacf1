//! The one frequency loop of the sweeps: order, progress, failure isolation and the rows
//! of [`SweepResult`]. A [`FrequencySolver`] (fast, harmonic balance) solves one
//! frequency from its own warm start (prediction, continuation); the driver records what
//! it gives: a solved row, a singular frequency, or a failure that fails that frequency
//! only (status `failed`, the message in run.json), after which the solver restarts cold.
//! A solver that finds a frequency singular prepares its own next start.

use super::posteriori::Verdict;
use super::{Options, PointFreq, SweepError, SweepResult, C64};
use crate::model::Problem;

/// A frequency's status in the results.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// Consistent to the tolerance, and the independent check passed.
    Converged,
    /// A response that is not consistent (or failed its check): reported as such.
    NotConverged,
    /// The dynamic stiffness is singular there (an undamped resonance): no response.
    Singular,
    /// A library call or a solve failed there: no response, with the reason.
    Failed(String),
}

impl Status {
    /// The status column's word.
    pub fn name(&self) -> &'static str {
        match self {
            Status::Converged => "converged",
            Status::NotConverged => "not_converged",
            Status::Singular => "singular",
            Status::Failed(_) => "failed",
        }
    }

    /// Whether a response was computed (converged or not).
    pub fn has_response(&self) -> bool {
        matches!(self, Status::Converged | Status::NotConverged)
    }
}

/// One frequency's response.
#[derive(Debug, Clone, Default)]
pub struct Row {
    /// Complex first-harmonic amplitude of every output (length).
    pub outputs: Vec<C64>,
    /// Harmonic balance: `[output][h]`, h = 0..H.
    pub harmonics: Option<Vec<Vec<C64>>>,
    /// Power dissipated in the joints (force·length/time).
    pub power: f64,
    /// Per contact point, when per-point results are kept.
    pub points: Option<Vec<PointFreq>>,
    /// Contact iterations (fast) or Newton iterations (harmonic balance).
    pub iterations: usize,
    pub converged: bool,
    /// The independent check of a converged solution.
    pub check: Option<Verdict>,
    /// The displacement amplitude of every free DOF (length), when kept.
    pub field: Option<Vec<C64>>,
}

/// What a solver gives for one frequency.
#[derive(Debug, Clone)]
pub enum Outcome {
    Solved(Row),
    /// Singular dynamic stiffness: no response (the solver has reset its start).
    Singular,
}

/// A per-frequency solver of the steady state.
pub trait FrequencySolver {
    /// Solves frequency `f` (1/time), adding its costs to `res.timings` and counters.
    fn solve(&mut self, f: f64, res: &mut SweepResult) -> Result<Outcome, SweepError>;
    /// The next frequency starts cold (after a failed one).
    fn restart(&mut self);
    /// Harmonics per output row (H + 1) when the solver reports them, else `None`.
    fn harmonics(&self) -> Option<usize> {
        None
    }
}

/// Shape of the rows: outputs, and contact points when per-point results are kept.
#[derive(Debug, Clone, Copy)]
pub struct Shape {
    pub outputs: usize,
    pub points: Option<usize>,
}

impl Shape {
    /// The rows of a sweep of `p` with `opts`.
    pub fn of(p: &Problem, opts: &Options) -> Self {
        Shape {
            outputs: p.outputs.len(),
            points: opts.point_results.then_some(p.contacts.len()),
        }
    }
}

/// Runs `solver` over `freqs` in the given order into a result listing them so.
pub fn drive(
    solver: &mut dyn FrequencySolver,
    freqs: &[f64],
    shape: Shape,
    progress: &dyn Fn(&str, usize, usize),
    res: &mut SweepResult,
) {
    res.freqs = freqs.to_vec();
    for (fi, &f) in freqs.iter().enumerate() {
        progress("frequency", fi + 1, freqs.len());
        match solver.solve(f, res) {
            Ok(Outcome::Solved(row)) => res.push_row(f, row),
            Ok(Outcome::Singular) => {
                res.push_singular(shape.outputs, shape.points);
                push_empty_harmonics(solver, shape, res);
            }
            Err(e) => {
                res.push_failed(&e, shape.outputs, shape.points);
                push_empty_harmonics(solver, shape, res);
                solver.restart();
            }
        }
    }
}

fn push_empty_harmonics(solver: &dyn FrequencySolver, shape: Shape, res: &mut SweepResult) {
    if let Some(n) = solver.harmonics() {
        res.harmonics
            .push(vec![vec![C64::new(0.0, 0.0); n]; shape.outputs]);
    }
}

impl SweepResult {
    /// The next frequency is singular: a row of zeros, not converged.
    pub(crate) fn push_singular(&mut self, nout: usize, points: Option<usize>) {
        self.push_no_response(nout, points, true, None);
    }

    /// Why frequency `i` failed, if it did.
    pub fn failure(&self, i: usize) -> Option<&str> {
        self.failed.get(i).and_then(|m| m.as_deref())
    }

    /// The next frequency failed with `e`: a row of zeros (`points` contact points when
    /// per-point results are kept), not converged.
    pub(crate) fn push_failed(&mut self, e: &SweepError, nout: usize, points: Option<usize>) {
        self.push_no_response(nout, points, false, Some(e.to_string()));
    }

    /// Whether frequency `i` was singular (no response computed there).
    pub fn is_singular(&self, i: usize) -> bool {
        self.singular.get(i).copied().unwrap_or(false)
    }

    /// A row of zeros standing for "no response computed", not converged.
    fn push_no_response(
        &mut self,
        nout: usize,
        points: Option<usize>,
        singular: bool,
        failed: Option<String>,
    ) {
        self.outputs.push(vec![C64::new(0.0, 0.0); nout]);
        self.power.push(0.0);
        if let Some(n) = points {
            self.points.push(vec![PointFreq::default(); n]);
        }
        self.iterations.push(0);
        self.converged.push(false);
        self.singular.push(singular);
        self.failed.push(failed);
        self.checks.push(None);
    }

    /// Appends the solved frequency `f`.
    pub(crate) fn push_row(&mut self, f: f64, row: Row) {
        self.outputs.push(row.outputs);
        if let Some(h) = row.harmonics {
            self.harmonics.push(h);
        }
        self.power.push(row.power);
        if let Some(p) = row.points {
            self.points.push(p);
        }
        self.iterations.push(row.iterations);
        self.converged.push(row.converged);
        self.singular.push(false);
        self.failed.push(None);
        self.checks.push(row.check);
        if let Some(x) = row.field {
            self.fields.push((f, x));
        }
    }

    /// The status of frequency `i`.
    pub fn status(&self, i: usize) -> Status {
        if let Some(m) = self.failure(i) {
            Status::Failed(m.to_string())
        } else if self.is_singular(i) {
            Status::Singular
        } else if self.converged.get(i).copied().unwrap_or(false) {
            Status::Converged
        } else {
            Status::NotConverged
        }
    }
}
