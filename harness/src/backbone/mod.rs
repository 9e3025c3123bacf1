//! Backbones: natural frequency and damping ratio of one mode of a lumped system
//! ([`crate::mhb::System`]: M, K, D, contact elements between DOFs or to ground) as
//! functions of its modal amplitude q.
//!
//! The modal amplitude is that of the first harmonic: x̂₁ = q ψ with ψᴴMψ = 1, so for
//! the linear mode x(t) = q φ cos ωt with φᵀMφ = 1.
//!
//! - [`first_order`]: the thesis's linearization (k*, d* through `jointlin_linearize`)
//!   in a complex eigenvalue problem, made consistent with the mode's own amplitudes.
//! - [`epmc`]: the extended periodic motion concept (Krack 2015) at H harmonics with
//!   the alternating frequency–time forces of [`crate::mhb::aft`], followed in
//!   amplitude through turning points.
//! - [`fe`]: an FE scene reduced onto its contact points' tangential relative
//!   displacements, one joint per point and direction, as such a system.
//! - [`ringdown`]: a free decay integrated in time through the C API, the reference
//!   the backbones are checked against.

pub mod degenerate;
pub mod epmc;
pub mod fe;
pub mod first_order;
pub mod modes;
pub mod report;
pub mod ringdown;

#[cfg(test)]
mod tests;

use crate::capi::CapiError;
use crate::mhb::MhbError;
pub use modes::C64;

/// One point of a backbone.
#[derive(Debug, Clone)]
pub struct BackbonePoint {
    /// q (length·mass^½ in the scene's units: x̂₁ = q ψ, ψᴴMψ = 1).
    pub modal_amplitude: f64,
    /// Natural frequency (rad/time).
    pub omega: f64,
    /// Modal damping ratio (1).
    pub damping_ratio: f64,
    /// First harmonic of the motion per DOF (length), x(t) = Re(x̂ e^{iωt}).
    pub shape: Vec<C64>,
    /// First-harmonic relative-displacement amplitude of each element (length).
    pub element_amplitudes: Vec<f64>,
    /// Energy dissipated per cycle by each element (force·length).
    pub energy_per_cycle: Vec<f64>,
    /// Per three-direction point: its smallest and largest normal force over the
    /// cycle (force; empty without points).
    pub normal_range: Vec<(f64, f64)>,
}

/// Errors of a backbone computation.
#[derive(Debug, thiserror::Error)]
pub enum BackboneError {
    #[error(transparent)]
    Capi(#[from] CapiError),
    #[error(transparent)]
    Modes(#[from] modes::ModeError),
    #[error(transparent)]
    Mhb(#[from] MhbError),
    #[error("mode {mode} does not exist ({count} oscillatory modes)")]
    NoMode { mode: usize, count: usize },
    #[error("no contact moves in this mode")]
    NoContact,
    #[error("modal amplitude {0:e} is not positive and finite")]
    Amplitude(f64),
    #[error("no oscillatory mode at modal amplitude {modal_amplitude:.6e} (overdamped)")]
    Overdamped { modal_amplitude: f64 },
    #[error("amplitudes not consistent at modal amplitude {modal_amplitude:.6e} (relative mismatch {mismatch:.3e} after {iterations} steps of {method})")]
    NotConsistent {
        modal_amplitude: f64,
        mismatch: f64,
        iterations: usize,
        /// The iteration that stalled.
        method: &'static str,
    },
    #[error("the mode nears critical damping (damping ratio {damping_ratio:.3} at modal amplitude {last:.6e}): its joints slide through and past it no oscillatory mode remains; {cause}")]
    CriticalDamping {
        /// The last solved point's modal amplitude and damping ratio.
        last: f64,
        damping_ratio: f64,
        /// Why the next amplitude failed.
        cause: Box<BackboneError>,
    },
    #[error("EPMC: Newton did not converge at modal amplitude {modal_amplitude:.6e} (|R| = {residual:.3e})")]
    NotConverged { modal_amplitude: f64, residual: f64 },
    #[error("EPMC: the continuation stopped at modal amplitude {modal_amplitude:.6e}: {reason}")]
    PathStopped {
        modal_amplitude: f64,
        reason: String,
    },
}

/// `count` amplitudes from `from` to `to`, equally spaced in log.
pub fn log_space(from: f64, to: f64, count: usize) -> Vec<f64> {
    if count <= 1 {
        return vec![from];
    }
    let (a, b) = (from.ln(), to.ln());
    (0..count)
        .map(|i| (a + (b - a) * i as f64 / (count - 1) as f64).exp())
        .collect()
}
