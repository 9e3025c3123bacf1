//! Time-domain reference for the lumped systems of [`crate::mhb`] (with or without
//! three-direction points) from a given state:
//! [`super::lumped::settle`] (RK4, thesis (D.2), the library's points through the C API,
//! committed once per step) from x(0) = x0, v(0) = v0 with virgin elements, the full
//! excitation at once, until the harness's cycle test ([`crate::time::periodic`]) finds
//! the motion periodic.

use super::lumped::{settle, Integration, LumpedState};
use crate::mhb::contact3d::System3;
use crate::mhb::{MhbError, System};

/// Steady periodic response measured over the last cycle.
#[derive(Debug, Clone)]
pub struct Steady {
    /// First-harmonic amplitude per DOF.
    pub amplitude: Vec<f64>,
    /// Half the peak-to-peak range per DOF.
    pub half_range: Vec<f64>,
    pub cycles: usize,
    /// Energy dissipated per cycle by the elements.
    pub energy: f64,
    /// Per three-direction point: the fraction of the last cycle's steps at which it
    /// carries no normal force (open).
    pub open_fraction: Vec<f64>,
}

/// Integrates `sys` (one-direction elements) from x(0) = x0, v(0) = v0 with `steps` RK4
/// steps per period until the cycle change test is below `tol`.
pub fn steady(
    sys: &System,
    omega: f64,
    x0: &[f64],
    v0: &[f64],
    steps: usize,
    tol: f64,
    max_cycles: usize,
) -> Result<Steady, MhbError> {
    let with_points = System3 {
        linear: sys.clone(),
        elements: Vec::new(),
    };
    steady3(&with_points, omega, x0, v0, steps, tol, max_cycles)
}

/// [`steady`] of a system with three-direction points (`jointlin_point3d_step`, virgin
/// at x0) and one-direction elements.
pub fn steady3(
    sys: &System3,
    omega: f64,
    x0: &[f64],
    v0: &[f64],
    steps: usize,
    tol: f64,
    max_cycles: usize,
) -> Result<Steady, MhbError> {
    let mut st = LumpedState::virgin(sys, x0, v0);
    let run = Integration {
        omega,
        steps,
        ramp_cycles: 0.0,
        tolerance: tol,
        min_cycles: 0,
        max_cycles,
    };
    let s = settle(sys, &mut st, &run, &[])?;
    if !s.steady {
        return Err(MhbError::Continuation(format!(
            "time integration not periodic to {tol:.1e} within {max_cycles} cycles"
        )));
    }
    // Per step the elements' samples: one-direction elements, then the points.
    let first_point = sys.linear.elements.len();
    let open_fraction = (0..sys.elements.len())
        .map(|p| {
            let open = s
                .loops
                .iter()
                .filter(|step| step[first_point + p].force[2] <= 0.0);
            open.count() as f64 / s.loops.len().max(1) as f64
        })
        .collect();
    Ok(Steady {
        amplitude: s.last.outputs.iter().map(|o| o.amplitude).collect(),
        half_range: s.last.outputs.iter().map(|o| o.half_range()).collect(),
        cycles: s.cycles,
        energy: s.last.energy,
        open_fraction,
    })
}
