//! Time-domain reference for the lumped systems of [`crate::mhb`]: the harness's RK4
//! ([`crate::time::rk4::rk4_step`], thesis (D.2)) on the first-order form, every stage
//! asking the library's point (`jointlin_point_step`) for the force at the stage's slip
//! from the committed state, the state committed once per accepted step (as
//! [`crate::time::rk4::SceneRk4`] does for scenes); periodic steady state detected by the
//! harness's cycle test ([`crate::time::periodic`]).

use crate::capi::{self, POINT_STATE_LEN};
use crate::time::periodic::{change, Cycle, SteadyTest};
use crate::time::rk4::rk4_step;

use crate::mhb::{AftError, Law, MhbError, System};

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
}

/// Integrates from x(0) = x0, v(0) = v0 with `steps` RK4 steps per period until the cycle
/// change test is below `tol` (S = 2n state size).
pub fn steady<const S: usize>(
    sys: &System,
    omega: f64,
    x0: &[f64],
    v0: &[f64],
    steps: usize,
    tol: f64,
    max_cycles: usize,
) -> Result<Steady, MhbError> {
    let mut states = vec![[0.0; POINT_STATE_LEN]; sys.elements.len()];
    let run = Run {
        sys,
        omega,
        steps,
        tol,
        max_cycles,
    };
    run.settle::<S, _>(
        x0,
        v0,
        &mut states,
        |y, states| {
            let fe = element_forces(sys, y, states)?;
            let mut out = vec![0.0; sys.n()];
            for (e, fv) in sys.elements.iter().zip(&fe) {
                out[e.i] += fv;
                if let Some(j) = e.j {
                    out[j] -= fv;
                }
            }
            Ok(out)
        },
        |y, states| {
            let mut dissipated = 0.0;
            for (e, st) in sys.elements.iter().zip(states.iter_mut()) {
                if let Law::Point(tg) = e.law {
                    let d = y[e.i] - e.j.map_or(0.0, |j| y[j]);
                    let mut next = [0.0; POINT_STATE_LEN];
                    let s = capi::point_step(&tg, st, d, &mut next).map_err(AftError::from)?;
                    *st = next;
                    dissipated += s.dissipated;
                }
            }
            Ok(dissipated)
        },
    )
}

/// One time-domain reference run: the linear system (M, D, K, loads) of `sys`, the
/// frequency, RK4 steps per period and the periodicity test.
pub struct Run<'a> {
    pub sys: &'a System,
    pub omega: f64,
    pub steps: usize,
    pub tol: f64,
    pub max_cycles: usize,
}

impl Run<'_> {
    /// RK4 on M ẍ + D ẋ + K x + g(x) = f₀ + Re(f̂ e^{iωt}) from x(0) = x0, v(0) = v0 until
    /// the cycle change test is below the tolerance (S = 2n state size). `internal(y,
    /// states)` gives the nonlinear elements' internal forces g at displacements y from
    /// their committed `states` (a trial: the states are not changed); `commit(y,
    /// states)` moves them to the accepted y and returns the energy dissipated in the
    /// step.
    pub fn settle<const S: usize, St>(
        &self,
        x0: &[f64],
        v0: &[f64],
        states: &mut [St],
        internal: impl Fn(&[f64], &[St]) -> Result<Vec<f64>, MhbError>,
        commit: impl Fn(&[f64], &mut [St]) -> Result<f64, MhbError>,
    ) -> Result<Steady, MhbError> {
        let (sys, omega) = (self.sys, self.omega);
        let n = sys.n();
        assert_eq!(S, 2 * n);
        let minv = sys
            .m
            .clone()
            .try_inverse()
            .ok_or(MhbError::Singular { omega })?;
        let h = 2.0 * std::f64::consts::PI / omega / self.steps as f64;
        let mut x = [0.0; S];
        x[..n].copy_from_slice(x0);
        x[n..].copy_from_slice(v0);
        let mut dissipated = 0.0;
        let mut test = SteadyTest::default();
        let mut prev = None;
        let mut t = 0.0;
        for cycle in 1..=self.max_cycles {
            let mut cyc = Cycle::new(omega, self.steps, n, vec![dissipated]);
            for _ in 0..self.steps {
                let f = |tt: f64, y: &[f64; S]| -> [f64; S] {
                    let mut out = [0.0; S];
                    let Ok(g) = internal(&y[..n], states) else {
                        return [f64::NAN; S];
                    };
                    let (sn, cs) = (omega * tt).sin_cos();
                    let mut r = vec![0.0; n];
                    for a in 0..n {
                        r[a] = sys.f0[a] + sys.f1[a].re * cs - sys.f1[a].im * sn;
                        for b in 0..n {
                            r[a] -= sys.k[(a, b)] * y[b] + sys.d[(a, b)] * y[n + b];
                        }
                        r[a] -= g[a];
                    }
                    for a in 0..n {
                        out[a] = y[n + a];
                        out[n + a] = (0..n).map(|b| minv[(a, b)] * r[b]).sum();
                    }
                    out
                };
                x = rk4_step(&f, t, &x, h);
                t += h;
                if x.iter().any(|v| !v.is_finite()) {
                    // A failed library call or an unstable step: the call's error if any.
                    internal(&x[..n], states)?;
                    return Err(MhbError::Continuation(format!(
                        "time integration not finite at t = {t:.6e}"
                    )));
                }
                dissipated += commit(&x[..n], states)?;
                cyc.push(t, &x[..n]);
            }
            let stats = cyc.finish(&[dissipated]);
            if let Some(p) = &prev {
                let d = test.push(change(p, &stats));
                if d <= self.tol {
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
            "time integration not periodic to {:.1e} within {} cycles",
            self.tol, self.max_cycles
        )))
    }
}

/// Relative displacement of element (i, j) in the state y (j = None: to ground).
pub fn element_slip(y: &[f64], i: usize, j: Option<usize>) -> f64 {
    y[i] - j.map_or(0.0, |j| y[j])
}

/// The elements' forces at displacements y from their committed states (a trial step:
/// the states are not changed): k₃d³ for a cubic spring, the library's point through
/// `jointlin_point_step` for a contact.
pub fn element_forces(
    sys: &System,
    y: &[f64],
    states: &[[f64; POINT_STATE_LEN]],
) -> Result<Vec<f64>, MhbError> {
    let mut scratch = [0.0; POINT_STATE_LEN];
    sys.elements
        .iter()
        .zip(states)
        .map(|(e, st)| {
            let d = element_slip(y, e.i, e.j);
            Ok(match e.law {
                Law::Cubic(k3) => k3 * d * d * d,
                Law::Point(tg) => {
                    capi::point_step(&tg, st, d, &mut scratch)
                        .map_err(AftError::from)?
                        .force
                }
            })
        })
        .collect()
}
