//! Settings of the iteration store: tolerances, update rule, pass bound, increment
//! numbering, restart file.

use std::path::PathBuf;

use super::StoreError;
use crate::iterate::{next_estimate, Scheme};

/// How the host numbers the increments of a re-run or final pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KincNumbering {
    /// KINC is the sweep increment number in every pass (a host that re-runs selected
    /// frequencies of the original sweep and keeps their numbers).
    #[default]
    Original,
    /// Every pass numbers its increments 1..m (a new Abaqus analysis over the m re-run
    /// frequencies): KINC = i means the i-th scheduled sweep increment, ascending.
    Sequential,
}

/// Settings of the iteration.
#[derive(Debug, Clone, PartialEq)]
pub struct StoreConfig {
    /// Amplitude estimate for the first increment of pass 1 (length, > 0).
    pub initial_amplitude: f64,
    /// Relative tolerance: converged when |a − a*| ≤ rtol·max(a, a*) + atol per direction.
    pub rtol: f64,
    /// Absolute tolerance (length, ≥ 0).
    pub atol: f64,
    /// Update rule for later passes; `Direct` is the thesis's "last computed amplitude".
    pub scheme: Scheme,
    /// Most iteration passes (pass 1 and re-runs); the final pass comes on top.
    pub max_passes: u32,
    /// KSTEP of the steady-state step that is iterated; 0 = every step.
    pub sweep_step: i32,
    /// Increment numbering of re-run passes.
    pub numbering: KincNumbering,
    /// Restart file, written at LOP 2 when LRESTART ≥ 1 and at LOP 3; read at LOP 4.
    pub restart_path: Option<PathBuf>,
}

/// Default relative tolerance on the amplitude (0.1 %: well below the 3–9 % model error
/// of the linearization itself, model.md §8).
pub const DEFAULT_RTOL: f64 = 1e-3;
/// Pairs of a point's (estimate, computed) history handed to [`crate::iterate::next_estimate`]. Between two
/// passes the *other* points' amplitudes change too, so the map a ↦ a*(a) of one point
/// drifts: older pairs (and brackets built from them) are stale and made the bracketing
/// secant stall on a coupled two-point sweep (tests/ffi_sweep.rs: no convergence in 15
/// passes with the full history, 5 passes + final with the last two). The full history is
/// kept (restart file, status).
pub const HISTORY_WINDOW: usize = 2;

/// Amplitudes below this fraction of a point's own largest recent amplitude are
/// indistinguishable from 0 for the log-space update rule.
pub const RELATIVE_FLOOR: f64 = 1e-12;

/// Default bound on iteration passes (the thesis's beam needed 5, Fig. 4.33).
pub const DEFAULT_MAX_PASSES: u32 = 20;

impl StoreConfig {
    /// Defaults around an initial amplitude estimate: rtol 1e-3, atol 0, secant, 20 passes,
    /// every step, original numbering, no restart file.
    pub fn new(initial_amplitude: f64) -> Self {
        Self {
            initial_amplitude,
            rtol: DEFAULT_RTOL,
            atol: 0.0,
            scheme: Scheme::Secant,
            max_passes: DEFAULT_MAX_PASSES,
            sweep_step: 0,
            numbering: KincNumbering::Original,
            restart_path: None,
        }
    }

    pub(super) fn validate(&self) -> Result<(), StoreError> {
        for (v, what) in [
            (self.initial_amplitude, "initial amplitude"),
            (self.rtol, "rtol"),
            (self.atol, "atol"),
        ] {
            if !v.is_finite() {
                return Err(StoreError::NonFinite(what));
            }
        }
        if self.initial_amplitude <= 0.0 {
            return Err(StoreError::OutOfRange("initial amplitude must be > 0"));
        }
        if !(0.0..1.0).contains(&self.rtol) || self.atol < 0.0 {
            return Err(StoreError::OutOfRange("need 0 <= rtol < 1 and atol >= 0"));
        }
        if self.max_passes == 0 {
            return Err(StoreError::OutOfRange("max_passes must be >= 1"));
        }
        if self.sweep_step < 0 {
            return Err(StoreError::OutOfRange("sweep_step must be >= 0"));
        }
        Ok(())
    }

    /// |a − a*| ≤ rtol·max(a, a*) + atol.
    pub(super) fn within(&self, a: f64, a_star: f64) -> bool {
        (a - a_star).abs() <= self.rtol * a.max(a_star) + self.atol
    }

    /// The next estimate from the recent (estimate, computed) pairs of one point and
    /// direction (non-empty), in the point's own scale: a point whose latest computed
    /// amplitude is exactly 0 did not move (no load, or a node at rest by symmetry) and
    /// gets 0 in every scheme, so zero load gives zero and converges (|0 − 0| ≤ tolerance);
    /// otherwise amplitudes fed to the log-space rule (ln 0 = −∞) are floored at
    /// [`RELATIVE_FLOOR`] times the largest computed amplitude of these pairs (or at atol when that
    /// is larger), not at a fraction of the user's initial guess.
    pub(super) fn next_from(&self, pairs: &[(f64, f64)]) -> f64 {
        let (_, last) = pairs[pairs.len() - 1];
        if last == 0.0 {
            return 0.0;
        }
        // The scale of what the analysis computed, not of the estimates: a first estimate
        // (the user's guess) far above the point's real amplitude must not floor it.
        let scale = pairs
            .iter()
            .fold(0.0f64, |m, &(_, computed)| m.max(computed));
        let floor = self.atol.max(RELATIVE_FLOOR * scale);
        let h: Vec<(f64, f64)> = pairs
            .iter()
            .map(|&(a, b)| (a.max(floor), b.max(floor)))
            .collect();
        let next = next_estimate(self.scheme, &h);
        if next.is_finite() {
            next
        } else {
            last
        }
    }
}
