//! Time-domain reference for the lumped systems with three-direction contact points
//! ([`crate::mhb::contact3d`]): RK4 ([`crate::time::rk4::rk4_step`], thesis (D.2)) on
//! the first-order form, every stage asking the library's point
//! (`jointlin_point3d_step`) for its forces at the stage's displacements from the
//! committed state, the state committed once per accepted step, as
//! [`super::mhb_reference`] does with the one-direction point; periodic steady state by
//! the harness's cycle test ([`crate::time::periodic`]).

use crate::mhb::contact3d::{step, States, System3, VIRGIN};
use crate::mhb::{AftError, MhbError};
use crate::time::mhb_reference::{Run, Steady};

/// Internal force vector of the points at `y` from their committed `states` (a trial:
/// the states are not changed): +F₁, +F₂ along the tangential rows, −N along the normal
/// row ([`crate::mhb::contact3d::Element3::add_internal`]).
fn internal(sys: &System3, y: &[f64], states: &[States]) -> Result<Vec<f64>, MhbError> {
    let mut out = vec![0.0; sys.linear.n()];
    let mut scratch = VIRGIN;
    for (e, st) in sys.elements.iter().zip(states) {
        let (force, _) = step(&e.contact, e.coupled, st, e.displacement(y), &mut scratch)
            .map_err(AftError::from)?;
        e.add_internal(force, &mut out);
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
    if !sys.linear.elements.is_empty() {
        return Err(MhbError::Continuation(
            "the three-direction reference integrates points only: the system has 1D elements"
                .into(),
        ));
    }
    let mut states = vec![VIRGIN; sys.elements.len()];
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
                let mut next = VIRGIN;
                let (_, d) = step(&e.contact, e.coupled, st, e.displacement(y), &mut next)
                    .map_err(AftError::from)?;
                *st = next;
                dissipated += d;
            }
            Ok(dissipated)
        },
    )
}
