//! The stateful time-domain contact point in one tangential direction: slip in → force,
//! tangent, dissipated energy, new state (model.md §4; thesis §2.3.3, Fig. 2.16/2.17).
//!
//! Two unloading rules:
//! * [`Rule::Thesis`]: after a reversal, elastic unloading with k_T0 until the force changes
//!   sign, then virgin (Mindlin) loading from that zero-force point (thesis phases 1–3);
//!   an excursion past zero force that spans less than a quarter of the branch before it
//!   keeps a fading memory of that branch, so closed loops move continuously with the
//!   motion (`thesis` module docs; model.md §4 "Shallow excursions").
//! * [`Rule::Masing`]: Mindlin–Deresiewicz / Masing branches F = F_r ± 2g(|δ − δ_r|/2)
//!   with the usual memory rules (a branch that reaches an earlier reversal point rejoins
//!   the branch it interrupted).
//!
//! The two tangential directions of an FE point are independent points (Fig. 4.26).
//! A state is plain data and [`Point::step`] is pure, so hosts can evaluate trial states
//! (Newton iterations, Runge–Kutta stages) and commit only accepted ones.
//!
//! [`Point::step_with_tangents`] also carries derivatives of the state's continuous slots
//! with respect to any parameters the slips depend on (the tangent-linear step): every
//! assignment of a continuous slot in the rules is mirrored by a [`Tangents::set`] with
//! its exact derivative on the branch taken, so a host differentiates a whole marched
//! path (e.g. a harmonic-balance Jacobian) without finite differences.

mod masing;
mod thesis;

pub use masing::{MasingState, MAX_REVERSALS};
pub use thesis::ThesisState;

use crate::error::{finite, Error};
use crate::law::Backbone;

/// Unloading rule of the hysteresis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// Elastic unloading with k_T0 until the force changes sign (the thesis's rule).
    Thesis,
    /// Masing's rule (Mindlin–Deresiewicz).
    Masing,
}

/// One tangential direction of one contact point: its backbone and unloading rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    pub backbone: Backbone,
    pub rule: Rule,
}

/// History of one direction. Starts virgin at slip 0 ([`PointState::virgin`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PointState {
    Thesis(ThesisState),
    Masing(MasingState),
}

/// Result of one slip increment.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepResult {
    /// Tangential force (or stress) at the new slip, sign = direction.
    pub force: f64,
    /// dF/dδ for continued motion in the last direction (≥ 0).
    pub tangent: f64,
    /// Energy dissipated during the increment (≥ 0, force × length).
    pub dissipated: f64,
}

/// Slots of the stored state every rule shares: the slip and the force.
pub const SLIP_SLOT: usize = 1;
pub const FORCE_SLOT: usize = 2;

/// Number of f64 slots a [`PointState`] occupies when stored (e.g. in Abaqus STATEV).
pub const STATE_LEN: usize = 5 + 3 * MAX_REVERSALS;

/// Derivatives of a stored state's slots (the layout of [`PointState::write`]) with
/// respect to some parameters, updated along with the state by a step.
pub trait Tangents {
    /// d(slot `dst`) = Σ coefficient · d(slot) over `terms` (values before this
    /// assignment) + `target` · d(new slip). Slots never assigned keep their derivatives;
    /// discrete slots (tags, directions, counts) are never assigned.
    fn set(&mut self, dst: usize, terms: &[(usize, f64)], target: f64);
}

/// No derivatives: the plain step.
pub struct NoTangents;

impl Tangents for NoTangents {
    #[inline(always)]
    fn set(&mut self, _dst: usize, _terms: &[(usize, f64)], _target: f64) {}
}

impl PointState {
    /// A point that has never slipped, at slip `origin` with zero force.
    pub fn virgin(rule: Rule, origin: f64) -> Self {
        match rule {
            Rule::Thesis => PointState::Thesis(ThesisState::virgin(origin)),
            Rule::Masing => PointState::Masing(MasingState::virgin(origin)),
        }
    }

    /// Current slip δ.
    pub fn slip(&self) -> f64 {
        match self {
            PointState::Thesis(s) => s.slip,
            PointState::Masing(s) => s.slip,
        }
    }

    /// Current force.
    pub fn force(&self) -> f64 {
        match self {
            PointState::Thesis(s) => s.force,
            PointState::Masing(s) => s.force,
        }
    }

    /// Writes the state into `out[..STATE_LEN]`; slot 0 holds the rule tag (1 thesis, 2 masing).
    pub fn write(&self, out: &mut [f64; STATE_LEN]) {
        *out = [0.0; STATE_LEN];
        match self {
            PointState::Thesis(s) => {
                out[0] = 1.0;
                s.write(&mut out[1..]);
            }
            PointState::Masing(s) => {
                out[0] = 2.0;
                s.write(&mut out[1..]);
            }
        }
    }

    /// Reads a state written by [`PointState::write`]. An all-zero block (fresh STATEV) is a
    /// virgin state of `rule` at slip `origin`. Corrupt blocks give an error, never a panic.
    pub fn read(slots: &[f64; STATE_LEN], rule: Rule, origin: f64) -> Result<Self, Error> {
        if slots.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFinite("stored hysteresis state"));
        }
        let tag = slots[0];
        if tag == 0.0 {
            Ok(Self::virgin(rule, origin))
        } else if tag == 1.0 && rule == Rule::Thesis {
            Ok(PointState::Thesis(ThesisState::read(&slots[1..])?))
        } else if tag == 2.0 && rule == Rule::Masing {
            Ok(PointState::Masing(MasingState::read(&slots[1..])?))
        } else {
            Err(Error::OutOfRange(
                "stored hysteresis state belongs to another rule",
            ))
        }
    }
}

impl Point {
    pub fn new(backbone: Backbone, rule: Rule) -> Self {
        Self { backbone, rule }
    }

    /// Moves the point from `state` to slip `slip_new`; returns the new state and the force,
    /// tangent and energy dissipated on the way. Pure: `state` is not changed.
    pub fn step(
        &self,
        state: &PointState,
        slip_new: f64,
    ) -> Result<(PointState, StepResult), Error> {
        self.step_with_tangents(state, slip_new, &mut NoTangents)
    }

    /// [`Point::step`] that also moves the derivatives `tangents` of the state's slots
    /// along (the derivative of the new force is that of slot [`FORCE_SLOT`]).
    pub fn step_with_tangents(
        &self,
        state: &PointState,
        slip_new: f64,
        tangents: &mut impl Tangents,
    ) -> Result<(PointState, StepResult), Error> {
        finite(slip_new, "slip")?;
        match (state, self.rule) {
            (PointState::Thesis(s), Rule::Thesis) => {
                let mut next = *s;
                let r = next.advance(&self.backbone, slip_new, tangents);
                Ok((PointState::Thesis(next), r))
            }
            (PointState::Masing(s), Rule::Masing) => {
                let mut next = *s;
                let r = next.advance(&self.backbone, slip_new, tangents);
                Ok((PointState::Masing(next), r))
            }
            _ => Err(Error::OutOfRange("state belongs to another unloading rule")),
        }
    }
}

/// Sign of a motion or force: +1, −1, or 0 for zero.
pub(crate) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod fading_tests;
