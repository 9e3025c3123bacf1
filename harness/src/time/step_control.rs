//! Step control for the implicit integrator: a step whose contact Newton iteration fails
//! (no convergence, a singular condensed matrix, a non-finite trial or a point the library
//! refuses at a diverged trial) is retried as two steps of half the size, recursively down
//! to h/2^[`MAX_CUTS`]; the next step is tried at the full size again, so the sampling of
//! the cycle (one sample per full step) is unchanged. Each level's K̂₀ = K + c a₀(h)M +
//! a₁(h)D + Bᵀ K_c0 B is factored once, when a step first needs it. A failed trial leaves
//! the committed state untouched (the points evaluate trials from it), so a retry starts
//! where the failed step did.

use std::cell::OnceCell;

use super::contact::Contacts;
use super::newmark::{add_blocks, effective_stiffness, Newmark, Setup};
use super::{State, Stepper, TimeError};
use crate::fe::csc::Csc;
use crate::solve::umfpack::{Numeric, Symbolic};

/// Halvings of a failing step: down to 1/64 of the step.
pub const MAX_CUTS: usize = 6;

/// One slot per level (step h/2^k), filled when a step first needs it. The caller owns
/// the matrices and then the factors (which borrow them), so the integrators of every
/// level can borrow both.
pub type PerLevel<T> = [OnceCell<T>; MAX_CUTS + 1];

/// Empty slots.
pub fn per_level<T>() -> PerLevel<T> {
    std::array::from_fn(|_| OnceCell::new())
}

/// Newmark (HHT-α) with step cutting.
pub struct ControlledNewmark<'a, 'n, 'f> {
    /// The full-size step's setup.
    setup: Setup<'a>,
    sym: &'n Symbolic<f64>,
    matrices: &'n PerLevel<Csc<f64>>,
    factors: &'f PerLevel<Numeric<'n, f64>>,
    steppers: Vec<Option<Newmark<'a, 'f>>>,
    /// Steps replaced by two half steps (at any level).
    pub cut_steps: usize,
}

impl<'a, 'n: 'f, 'f> ControlledNewmark<'a, 'n, 'f> {
    /// The integrator of `setup`, with the full-size level factored now.
    pub fn new(
        setup: Setup<'a>,
        sym: &'n Symbolic<f64>,
        (matrices, factors): (&'n PerLevel<Csc<f64>>, &'f PerLevel<Numeric<'n, f64>>),
    ) -> Result<Self, TimeError> {
        let mut c = ControlledNewmark {
            setup,
            sym,
            matrices,
            factors,
            steppers: (0..=MAX_CUTS).map(|_| None).collect(),
            cut_steps: 0,
        };
        c.level(0)?;
        Ok(c)
    }

    /// The integrator of level `k` (step h/2^k), built on first use.
    fn level(&mut self, k: usize) -> Result<&mut Newmark<'a, 'f>, TimeError> {
        if self.steppers[k].is_none() {
            let s = Setup {
                h: self.setup.h / (1u64 << k) as f64,
                ..self.setup.clone()
            };
            let (matrices, factors) = (self.matrices, self.factors);
            if matrices[k].get().is_none() {
                let mut khat = effective_stiffness(s.p, s.damping, s.h, s.scheme);
                add_blocks(s.p, &mut khat.values, &s.kc0);
                let _ = matrices[k].set(khat);
            }
            let matrix = matrices[k].get().expect("set above");
            if factors[k].get().is_none() {
                let _ = factors[k].set(self.sym.factor(matrix)?);
            }
            let factor = factors[k].get().expect("set above");
            self.steppers[k] = Some(Newmark::new(s, factor)?);
        }
        Ok(self.steppers[k].as_mut().expect("built above"))
    }

    /// One step of level `k`, cut in two halves where it fails.
    fn step_at(
        &mut self,
        k: usize,
        st: &mut State,
        contacts: &mut Contacts,
    ) -> Result<usize, TimeError> {
        match self.level(k)?.step(st, contacts) {
            Err(e) if k < MAX_CUTS && retried(&e) => {
                self.cut_steps += 1;
                let first = self.step_at(k + 1, st, contacts)?;
                Ok(first + self.step_at(k + 1, st, contacts)?)
            }
            other => other,
        }
    }
}

/// Failures of a step's iteration that a smaller step may not have.
fn retried(e: &TimeError) -> bool {
    matches!(
        e,
        TimeError::Newton { .. }
            | TimeError::Singular { .. }
            | TimeError::NonFinite { .. }
            | TimeError::Capi(_)
    )
}

impl Stepper for ControlledNewmark<'_, '_, '_> {
    fn h(&self) -> f64 {
        self.setup.h
    }

    fn loose_steps(&self) -> usize {
        self.steppers.iter().flatten().map(|s| s.loose_steps).sum()
    }

    fn cut_steps(&self) -> usize {
        self.cut_steps
    }

    fn step(&mut self, st: &mut State, contacts: &mut Contacts) -> Result<usize, TimeError> {
        self.step_at(0, st, contacts)
    }
}
