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
use crate::time::mhb_reference::Steady;
use crate::time::periodic::{change, Cycle, SteadyTest};
use crate::time::rk4::rk4_step;

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
    let lin = &sys.linear;
    let n = lin.n();
    assert_eq!(S, 2 * n);
    let minv = lin
        .m
        .clone()
        .try_inverse()
        .ok_or(MhbError::Singular { omega })?;
    let mut states = vec![[0.0; POINT3D_STATE_LEN]; sys.elements.len()];
    let h = 2.0 * std::f64::consts::PI / omega / steps as f64;
    let mut x = [0.0; S];
    x[..n].copy_from_slice(x0);
    x[n..].copy_from_slice(v0);
    let mut dissipated = 0.0;
    let mut test = SteadyTest::default();
    let mut prev = None;
    let mut t = 0.0;
    for cycle in 1..=max_cycles {
        let mut cyc = Cycle::new(omega, steps, n, vec![dissipated]);
        for _ in 0..steps {
            let f = |tt: f64, y: &[f64; S]| -> [f64; S] {
                let Ok(fi) = internal(sys, &y[..n], &states) else {
                    return [f64::NAN; S];
                };
                let (sn, cs) = (omega * tt).sin_cos();
                let mut out = [0.0; S];
                let r: Vec<f64> = (0..n)
                    .map(|a| {
                        let mut r = lin.f0[a] + lin.f1[a].re * cs - lin.f1[a].im * sn - fi[a];
                        for b in 0..n {
                            r -= lin.k[(a, b)] * y[b] + lin.d[(a, b)] * y[n + b];
                        }
                        r
                    })
                    .collect();
                for a in 0..n {
                    out[a] = y[n + a];
                    out[n + a] = (0..n).map(|b| minv[(a, b)] * r[b]).sum();
                }
                out
            };
            x = rk4_step(&f, t, &x, h);
            t += h;
            if x.iter().any(|v| !v.is_finite()) {
                internal(sys, &x[..n], &states)?;
                return Err(MhbError::Continuation(format!(
                    "time integration not finite at t = {t:.6e}"
                )));
            }
            for (e, st) in sys.elements.iter().zip(states.iter_mut()) {
                let mut next = [0.0; POINT3D_STATE_LEN];
                let s = capi::point3d_step(&e.contact, st, disp(e, &x[..n]), &mut next)
                    .map_err(AftError::from)?;
                *st = next;
                dissipated += s.dissipated;
            }
            cyc.push(t, &x[..n]);
        }
        let stats = cyc.finish(&[dissipated]);
        if let Some(p) = &prev {
            let d = test.push(change(p, &stats));
            if d <= tol {
                return Ok(Steady {
                    amplitude: stats.outputs.iter().map(|o| o.amplitude).collect(),
                    half_range: stats.outputs.iter().map(|o| o.half_range()).collect(),
                    cycles: cycle,
                    energy: stats.energy,
                });
            }
        }
        prev = Some(stats);
    }
    Err(MhbError::Continuation(format!(
        "time integration not periodic to {tol:.1e} within {max_cycles} cycles"
    )))
}
