//! Time-domain settings: the optional `[time_domain]` table of a scene and its resolved
//! form.
//!
//! ```toml
//! [time_domain]
//! integrator = "auto"      # "rk4", "newmark" or "auto" (RK4 up to 12 free DOFs);
//!                          # lumped scenes: RK4 ("newmark" is refused at this key)
//! steps_per_cycle = 256    # per forcing period (RK4 raises it to its stability limit)
//! ramp_cycles = 2.0        # C² ramp of the excitation when starting from rest
//! start = "rest"           # "rest" (static state, ramp) or "linear" (stuck linear steady state)
//! tolerance = 1e-5         # periodic when the estimated distance to the periodic state < this
//! min_cycles = 3
//! max_cycles = 2000
//! alpha = -0.05            # HHT-α of "newmark", in [−1/3, 0] (CalculiX's and Abaqus's
//!                          # *DYNAMIC default): < 0 damps the mesh's and the contact
//!                          # penalties' highest frequencies, 0 is average acceleration
//! ```

use serde::Serialize;

pub use crate::settings::{Integrator, Start, TimeDomainSpec};
use crate::settings::{
    DEFAULT_MAX_CYCLES, DEFAULT_MIN_CYCLES, MAX_STEPS_PER_CYCLE, MIN_STEPS_PER_CYCLE,
};

/// HHT-α by default: CalculiX's and Abaqus/Standard's *DYNAMIC default.
pub const DEFAULT_ALPHA: f64 = -0.05;

/// Largest model (free DOFs) for which `auto` picks RK4.
pub const AUTO_RK4_MAX_DOFS: usize = 12;

/// Resolved settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TimeSettings {
    pub integrator: Integrator,
    /// Steps per forcing period (the step is T/N, so cycles end on steps).
    pub steps_per_cycle: usize,
    /// Ramp length in periods (start = rest only).
    pub ramp_cycles: f64,
    pub start: Start,
    /// Steady when the estimated distance to the periodic state (relative, of the output
    /// first harmonics and the total joint energy per cycle) is below this; 0 = run
    /// exactly `max_cycles` (a fixed settling length).
    pub tolerance: f64,
    pub min_cycles: usize,
    pub max_cycles: usize,
    /// Newton: ‖Φ‖∞ ≤ this × max|r| (contact unknowns).
    pub newton_tolerance: f64,
    /// HHT-α of the implicit integrator (0: average acceleration). Without numerical
    /// damping, the stiff normal penalties' modes, excited at every stick–slip
    /// transition, ring on forever and a sliding FE scene never becomes periodic.
    pub alpha: f64,
}

impl Default for TimeSettings {
    fn default() -> Self {
        TimeSettings {
            integrator: Integrator::Auto,
            steps_per_cycle: 256,
            ramp_cycles: 2.0,
            start: Start::Rest,
            tolerance: 1e-5,
            min_cycles: DEFAULT_MIN_CYCLES,
            max_cycles: DEFAULT_MAX_CYCLES,
            newton_tolerance: 1e-10,
            alpha: DEFAULT_ALPHA,
        }
    }
}

impl TimeSettings {
    /// Defaults overridden by a scene table.
    pub fn from_spec(spec: Option<&TimeDomainSpec>) -> Result<Self, String> {
        let mut s = TimeSettings::default();
        let Some(t) = spec else {
            return Ok(s);
        };
        s.integrator = t.integrator;
        s.start = t.start;
        if let Some(n) = t.steps_per_cycle {
            s.steps_per_cycle = n;
        }
        if let Some(r) = t.ramp_cycles {
            s.ramp_cycles = r;
        }
        if let Some(v) = t.tolerance {
            s.tolerance = v;
        }
        if let Some(v) = t.min_cycles {
            s.min_cycles = v;
        }
        if let Some(v) = t.max_cycles {
            s.max_cycles = v;
        }
        if let Some(v) = t.alpha {
            s.alpha = v;
        }
        s.check()?;
        Ok(s)
    }

    /// Range checks.
    pub fn check(&self) -> Result<(), String> {
        if !(MIN_STEPS_PER_CYCLE..=MAX_STEPS_PER_CYCLE).contains(&self.steps_per_cycle) {
            return Err(format!(
                "time_domain.steps_per_cycle must be in {MIN_STEPS_PER_CYCLE}..={MAX_STEPS_PER_CYCLE}, got {}",
                self.steps_per_cycle
            ));
        }
        if !(self.ramp_cycles.is_finite() && self.ramp_cycles >= 0.0) {
            return Err(format!(
                "time_domain.ramp_cycles must be ≥ 0, got {}",
                self.ramp_cycles
            ));
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0 && self.tolerance < 1.0) {
            return Err(format!(
                "time_domain.tolerance must be in [0, 1), got {}",
                self.tolerance
            ));
        }
        if !(-1.0 / 3.0..=0.0).contains(&self.alpha) {
            return Err(format!(
                "time_domain.alpha (HHT) must be in [-1/3, 0], got {}",
                self.alpha
            ));
        }
        if self.max_cycles < 2 || self.min_cycles > self.max_cycles {
            return Err(format!(
                "time_domain: need 2 ≤ max_cycles and min_cycles ≤ max_cycles, got {} and {}",
                self.max_cycles, self.min_cycles
            ));
        }
        Ok(())
    }
}
