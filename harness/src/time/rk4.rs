//! Classical Runge–Kutta (thesis Appendix D, (D.2)), fourth order:
//!
//!   k₁ = f(t, x), k₂ = f(t + h/2, x + h k₁/2), k₃ = f(t + h/2, x + h k₂/2),
//!   k₄ = f(t + h, x + h k₃), x ← x + h (k₁ + 2k₂ + 2k₃ + k₄)/6.
//!
//! [`rk4_step`] for small ODEs (Duffing, tests); [`SceneRk4`] for a scene's model in
//! first-order form u' = v, M v' = f(t) − K u − D v − Bᵀ q(Bu), where every stage asks
//! UINTER for q at the stage's displacement from the committed contact state (a trial) and
//! the state is committed once, at the accepted step's end. Explicit: stable for
//! h ω_max < 2√2 (the imaginary-axis limit of RK4), so [`stable_steps_per_cycle`] raises
//! the step count to that limit with a margin.

use super::contact::Contacts;
use super::{Forcing, State, Stepper, TimeError};
use crate::fe::csc::Csc;
use crate::model::Problem;
use crate::solve::umfpack::Numeric;

/// One classical RK4 step (D.2) of x' = f(t, x), x of fixed size (small ODEs).
pub fn rk4_step<const N: usize>(
    f: &impl Fn(f64, &[f64; N]) -> [f64; N],
    t: f64,
    x: &[f64; N],
    h: f64,
) -> [f64; N] {
    let g = |t: f64, y: &[f64]| f(t, y.try_into().expect("N values")).to_vec();
    rk4_step_slice(&g, t, x, h).try_into().expect("N values")
}

/// One classical RK4 step (D.2) of x' = f(t, x), x of any size (lumped systems).
pub fn rk4_step_slice(f: &impl Fn(f64, &[f64]) -> Vec<f64>, t: f64, x: &[f64], h: f64) -> Vec<f64> {
    let add = |b: &[f64], s: f64| -> Vec<f64> { x.iter().zip(b).map(|(a, b)| a + s * b).collect() };
    let k1 = f(t, x);
    let k2 = f(t + 0.5 * h, &add(&k1, 0.5 * h));
    let k3 = f(t + 0.5 * h, &add(&k2, 0.5 * h));
    let k4 = f(t + h, &add(&k3, h));
    (0..x.len())
        .map(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
        .collect()
}

/// RK4's stability limit on the imaginary axis, h ω < 2√2 ≈ 2.83.
pub const RK4_LIMIT: f64 = 2.828;
/// Fraction of the limit used.
pub const RK4_MARGIN: f64 = 0.8;

/// Steps per period 2π/ω that keep h ω_max within the stability limit (with margin).
pub fn stable_steps_per_cycle(omega: f64, omega_max: f64) -> usize {
    let period = 2.0 * std::f64::consts::PI / omega;
    (period * omega_max / (RK4_LIMIT * RK4_MARGIN)).ceil() as usize
}

/// Largest eigenfrequency (rad/time) of M⁻¹ K₀ by power iteration (`m` factors M,
/// `k0` is the stiffness with the points stuck). 60 iterations from a fixed start; the
/// estimate is raised by 5 % (power iteration approaches from below).
pub fn max_frequency(m: &Numeric<f64>, k0: &Csc<f64>) -> Result<f64, TimeError> {
    let n = k0.n();
    let mut x: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64 * 0.1).collect();
    let mut lambda = 0.0;
    for _ in 0..60 {
        let y = k0.mul_vec(&x);
        let z = m.solve(&y)?;
        let nz = z.iter().map(|v| v * v).sum::<f64>().sqrt();
        let nx = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        if nz == 0.0 {
            break;
        }
        lambda = nz / nx;
        x = z.iter().map(|v| v / nz).collect();
    }
    Ok(1.05 * lambda.sqrt())
}

/// RK4 on a scene's model.
pub struct SceneRk4<'a, 'n> {
    pub p: &'a Problem,
    /// LU factors of M.
    pub m: &'n Numeric<'n, f64>,
    pub damping: Option<&'a Csc<f64>>,
    pub forcing: Forcing<'a>,
    pub h: f64,
}

impl SceneRk4<'_, '_> {
    /// M⁻¹(f(t) − K u − D v − Bᵀ q(Bu)) with q from a trial of the contacts.
    pub fn acceleration(
        &self,
        t: f64,
        u: &[f64],
        v: &[f64],
        contacts: &mut Contacts,
    ) -> Result<Vec<f64>, TimeError> {
        let n = u.len();
        let mut r = vec![0.0; n];
        self.forcing.at(t, &mut r);
        for (ri, ku) in r.iter_mut().zip(self.p.sys.k.mul_vec(u)) {
            *ri -= ku;
        }
        if let Some(d) = self.damping {
            for (ri, dv) in r.iter_mut().zip(d.mul_vec(v)) {
                *ri -= dv;
            }
        }
        let delta = contacts.local(u);
        contacts.evaluate(&delta, None)?;
        let q: Vec<[f64; 3]> = contacts
            .trial_force()
            .iter()
            .map(|f| f.map(|x| -x))
            .collect();
        contacts.add_internal(&q, &mut r);
        let a = self.m.solve(&r)?;
        if a.iter().any(|x| !x.is_finite()) {
            return Err(TimeError::NonFinite { t });
        }
        Ok(a)
    }
}

impl Stepper for SceneRk4<'_, '_> {
    fn h(&self) -> f64 {
        self.h
    }

    fn step(&mut self, st: &mut State, contacts: &mut Contacts) -> Result<usize, TimeError> {
        let (t, h) = (st.t, self.h);
        let axpy = |x: &[f64], y: &[f64], s: f64| -> Vec<f64> {
            x.iter().zip(y).map(|(a, b)| a + s * b).collect()
        };
        // k₁ = (v, a): a at the committed state is st.a (computed at the last commit).
        let (k1u, k1v) = (st.v.clone(), st.a.clone());
        let u2 = axpy(&st.u, &k1u, 0.5 * h);
        let v2 = axpy(&st.v, &k1v, 0.5 * h);
        let k2v = self.acceleration(t + 0.5 * h, &u2, &v2, contacts)?;
        let u3 = axpy(&st.u, &v2, 0.5 * h);
        let v3 = axpy(&st.v, &k2v, 0.5 * h);
        let k3v = self.acceleration(t + 0.5 * h, &u3, &v3, contacts)?;
        let u4 = axpy(&st.u, &v3, h);
        let v4 = axpy(&st.v, &k3v, h);
        let k4v = self.acceleration(t + h, &u4, &v4, contacts)?;
        for i in 0..st.u.len() {
            st.u[i] += h / 6.0 * (k1u[i] + 2.0 * v2[i] + 2.0 * v3[i] + v4[i]);
            st.v[i] += h / 6.0 * (k1v[i] + 2.0 * k2v[i] + 2.0 * k3v[i] + k4v[i]);
        }
        st.t = t + h;
        // The end state: one more trial there, committed; its acceleration is the next k₁.
        let (u, v) = (st.u.clone(), st.v.clone());
        st.a = self.acceleration(st.t, &u, &v, contacts)?;
        contacts.commit();
        Ok(0)
    }
}
