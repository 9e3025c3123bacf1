//! Time-domain reference: the scene's model integrated in time with the library's stateful
//! hysteresis (UINTER, LINPER = 0, through the C API — never a second copy of a contact
//! law), until the motion is periodic, then per output the first harmonic and the peaks
//! and per contact point the energy dissipated per cycle (∮ F·dδ).
//!
//! - [`rk4`]: classical Runge–Kutta (thesis Appendix D, (D.2)) for small systems (lumped
//!   bodies, ODEs such as the Duffing oscillator); explicit, so the step is kept below the
//!   stability limit of the stiffest mode.
//! - [`newmark`]: implicit Newmark in HHT-α form (α = −0.05 by default), Newton
//!   iterations on the contact unknowns with tangents from UINTER; trial states are
//!   evaluated from the committed state and the state is committed once per accepted step.
//!   One UMFPACK factorization per step size (symbolic analysis reused), the contact
//!   points condensed (receptance G = B K̂₀⁻¹ Bᵀ), so a Newton iteration is an m × m
//!   dense solve.
//! - [`step_control`]: a step whose Newton iteration fails is cut into two half steps
//!   (down to 1/64), counted; the next step is tried at the full size again.
//! - [`periodic`]: cycle statistics (first harmonic, peaks, energy) and the steady-state
//!   test (cycle-to-cycle change, extrapolated to the distance from the periodic state).
//! - [`lumped`]: a lumped system (one- and three-direction joints, cubic springs) by RK4;
//!   [`lumped_sweep`] a lumped scene's sweep, [`mhb_reference`] from a given state (the
//!   reference of the lumped harmonic balance's tests).
//! - [`scene_run`]: a scene's sweep in the time domain (`jointlin run --time-domain`);
//!   [`tables`] writes its files.
//!
//! Excitation: f(t) = f_pre + s(t)·Re(f̂ e^{iωt}), s a smooth ramp (C², over
//! `ramp_cycles`) when starting from rest; u(t) = Re(û e^{iωt}) + … defines the phase of
//! the extracted first harmonic û = (2/N) Σ u(t_k) e^{−iωt_k} over the last cycle, the same
//! convention as the frequency-domain sweep.

pub mod contact;
pub mod contact_points3d;
pub mod lumped;
pub mod lumped_sweep;
pub mod lumped_tables;
pub mod mhb_reference;
pub mod newmark;
pub mod periodic;
pub mod rk4;
pub mod scene_run;
pub mod settings;
pub mod step_control;
pub mod tables;

pub use settings::{Integrator, Start, TimeDomainSpec, TimeSettings};

use nalgebra::Complex;
use thiserror::Error;

use crate::capi::CapiError;
use crate::mhb::MhbError;
use crate::solve::prepared::PrepareError;
use crate::solve::umfpack::UmfpackError;

pub type C64 = Complex<f64>;

/// Errors of a time-domain run.
#[derive(Debug, Error)]
pub enum TimeError {
    #[error(transparent)]
    Capi(#[from] CapiError),
    #[error(transparent)]
    Umfpack(#[from] UmfpackError),
    #[error(transparent)]
    Prepare(#[from] PrepareError),
    #[error("Newton did not converge at t = {t:.6e} (|Φ|/|r| = {residual:.3e} after {iterations} iterations)")]
    Newton {
        t: f64,
        residual: f64,
        iterations: usize,
    },
    #[error("the condensed Newton matrix is singular at t = {t:.6e}")]
    Singular { t: f64 },
    #[error("the solution is not finite at t = {t:.6e} (unstable step?)")]
    NonFinite { t: f64 },
    #[error("the lumped system: {0}")]
    Lumped(String),
    #[error(transparent)]
    Mhb(#[from] MhbError),
    #[error("time-domain settings: {0}")]
    Settings(String),
    #[error("the time-domain reference does not integrate cubic springs (the C API has no time-domain cubic spring); `jointlin validate` has the Duffing oscillator's own RK4 reference")]
    CubicSprings,
    #[error("the time-domain reference evaluates each contact point at its node; remove `area_samples` from the interfaces")]
    AreaSamples,
}

/// The dynamic state on the free DOFs.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    pub t: f64,
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    pub a: Vec<f64>,
}

/// C² ramp s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ on [0, 1], 1 after.
pub fn ramp(t: f64, length: f64) -> f64 {
    if length <= 0.0 || t >= length {
        return 1.0;
    }
    if t <= 0.0 {
        return 0.0;
    }
    let x = t / length;
    x * x * x * (10.0 - 15.0 * x + 6.0 * x * x)
}

/// The load f(t) = f_pre + s(t)·Re(f̂ e^{iωt}) on the free DOFs.
#[derive(Debug, Clone, Copy)]
pub struct Forcing<'a> {
    pub preload: &'a [f64],
    pub excitation: &'a [C64],
    /// ω (rad/time).
    pub omega: f64,
    /// Ramp length (time); 0 = none.
    pub ramp: f64,
}

impl Forcing<'_> {
    /// f(t) into `out`.
    pub fn at(&self, t: f64, out: &mut [f64]) {
        let s = ramp(t, self.ramp);
        let (sn, cs) = (self.omega * t).sin_cos();
        for ((o, p), e) in out.iter_mut().zip(self.preload).zip(self.excitation) {
            *o = p + s * (e.re * cs - e.im * sn);
        }
    }
}

/// One integrator bound to a model, a forcing and a step size.
pub trait Stepper {
    /// Step size h.
    fn h(&self) -> f64;
    /// Advances `st` to st.t + h and commits the contact points there; returns the
    /// Newton iterations used (0 for explicit steps).
    fn step(
        &mut self,
        st: &mut State,
        contacts: &mut contact::Contacts,
    ) -> Result<usize, TimeError>;
    /// Steps accepted with a loosened Newton tolerance (implicit integrators).
    fn loose_steps(&self) -> usize {
        0
    }
    /// Steps replaced by two half steps after a failed iteration (implicit integrators).
    fn cut_steps(&self) -> usize {
        0
    }
}

#[cfg(test)]
mod tests;
