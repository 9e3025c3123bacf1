//! Time-domain reference for the lumped systems with three-direction contact points
//! ([`crate::mhb::contact3d`]): RK4 ([`crate::time::rk4::rk4_step`], thesis (D.2)) on
//! the first-order form, every stage asking the library's point
//! (`jointlin_point3d_step`) for its forces at the stage's displacements from the
//! committed state, the state committed once per accepted step, as
//! [`super::mhb_reference`] does with the one-direction point; periodic steady state by
//! the harness's cycle test ([`crate::time::periodic`]).

use crate::capi::{self, POINT3D_STATE_LEN};
use crate::mhb::contact3d::{Element3, System3};
use crate::mhb::{AftError, MhbError};
use crate::time::mhb_reference::{Run, Steady};

/// The point's displacement (u₁, u₂, h) at the system displacements `y`.
fn disp(e: &Element3, y: &[f64]) -> [f64; 3] {
    [y[e.dofs[0]], y[e.dofs[1]], e.gap - y[e.dofs[2]]]
}

/// Internal force vector of the points at `y` from their committed `states` (a trial:
/// the states are not changed): +F₁, +F₂ on t₁, t₂ and −N on n.
fn internal(
    sys: &System3,
    y: &[f64],
    states: &[[f64; POINT3D_STATE_LEN]],
) -> Result<Vec<f64>, MhbError> {
    let mut out = vec![0.0; sys.linear.n()];
    let mut scratch = [0.0; POINT3D_STATE_LEN];
    for (e, st) in sys.elements.iter().zip(states) {
        let s =
            capi::point3d_step(&e.contact, st, disp(e, y), &mut scratch).map_err(AftError::from)?;
        out[e.dofs[0]] += s.force[0];
        out[e.dofs[1]] += s.force[1];
        out[e.dofs[2]] -= s.force[2];
    }
    Ok(out)
}

/// Integrates from x(0) = x0, v(0) = v0 (virgin points) with `steps` RK4 steps per
/// period until the cycle change test is below `tol` (S = 2n state size); amplitudes are
/// the first harmonics of every DOF over the last cycle, energy the points' dissipation
/// in it.
pub fn steady3<const S: usize>(
    sys: &System3,
    omega: f64,
    x0: &[f64],
    v0: &[f64],
    steps: usize,
    tol: f64,
    max_cycles: usize,
) -> Result<Steady, MhbError> {
    let mut states = vec![[0.0; POINT3D_STATE_LEN]; sys.elements.len()];
    let run = Run {
        sys: &sys.linear,
        omega,
        steps,
        tol,
        max_cycles,
    };
    run.settle::<S, _>(
        x0,
        v0,
        &mut states,
        |y, states| internal(sys, y, states),
        |y, states| {
            let mut dissipated = 0.0;
            for (e, st) in sys.elements.iter().zip(states.iter_mut()) {
                let mut next = [0.0; POINT3D_STATE_LEN];
                let s = capi::point3d_step(&e.contact, st, disp(e, y), &mut next)
                    .map_err(AftError::from)?;
                *st = next;
                dissipated += s.dissipated;
            }
            Ok(dissipated)
        },
    )
}
