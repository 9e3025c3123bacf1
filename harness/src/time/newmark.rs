//! Implicit Newmark, average acceleration (β = 1/4, γ = 1/2: second order, unconditionally
//! stable, no numerical damping), with Newton iterations on the contact unknowns.
//!
//! With a = a₀(u₊ − u) − a₂v − a₃a (a₀ = 1/(βh²), a₂ = 1/(βh), a₃ = 1/(2β) − 1) and
//! v₊ = v + h((1 − γ)a + γa₊), the equation of motion at t + h is
//!
//!   K̂ u₊ + Bᵀ q(Bu₊) = f̂,   K̂ = K + a₀M + a₁D (a₁ = γ/(βh)),
//!   f̂ = f(t + h) + M(a₀u + a₂v + a₃a) + D(a₁u + a₄v + a₅a),
//!
//! (a₄ = γ/β − 1, a₅ = h(γ/β − 2)/2). Write q(r) = K_c0 r + g(r) with K_c0 the stuck
//! contact stiffness (k_N, k_T0, k_T0 per closed point) and K̂₀ = K̂ + Bᵀ K_c0 B, factored
//! once. Then u₊ = u₀ − H g(r) with u₀ = K̂₀⁻¹ f̂ and H = K̂₀⁻¹ Bᵀ, and the contact
//! displacements r = B u₊ solve the condensed equation
//!
//!   Φ(r) = r − B u₀ + G g(r) = 0,   G = B H  (m × m, m = 3 × points),
//!
//! by Newton with J = I + G (T(r) − K_c0), T the points' tangents from UINTER (each trial
//! evaluated from the committed state), with backtracking on ‖Φ‖; a Newton that stalls
//! (trials crossing a reversal, where the tangent jumps from k_T to k_T0, can cycle) goes
//! on with secant iterations (per component the chord from the committed state to the
//! trial). The accepted r is committed once. Per step: one sparse solve and m UINTER calls per Newton iteration.

use nalgebra::{DMatrix, DVector, Matrix3};

use super::contact::Contacts;
use super::{Forcing, State, Stepper, TimeError};
use crate::fe::csc::Csc;
use crate::fe::pair_blocks::to_global;
use crate::model::Problem;
use crate::solve::static_step::StaticState;
use crate::solve::umfpack::Numeric;

/// β, γ of the average-acceleration rule.
pub const BETA: f64 = 0.25;
pub const GAMMA: f64 = 0.5;
/// Most Newton iterations per step.
pub const MAX_NEWTON: usize = 40;
/// Secant (chord) iterations after a stalled Newton.
pub const MAX_FIXED_POINT: usize = 60;
/// Backtracking halvings per Newton iteration.
const MAX_HALVINGS: usize = 10;
/// A step whose Newton stalls is accepted when ‖Φ‖∞ ≤ this × max|r| and counted in
/// `loose_steps`. Seen on the coarse three beams at the second resonance: where the
/// pressure of a point changes during a step that reverses its slip, the library's force
/// at zero slip increment differs between the loading side (Mindlin branch rescaled to the
/// new pressure) and the unloading side (elastic from the committed force), a jump of
/// ∂F/∂p·Δp (9.4e-4 N on a 2.685 N force there, ~2e-9 mm of slip): Φ has no zero, and the
/// iteration stops in the jump at |Φ| ~ 1e-4 max|r|.
pub const LOOSE_TOLERANCE: f64 = 1e-3;

/// Stuck contact stiffness per point (local δ coordinates, × area): diag(k_N, k_T0, k_T0)
/// for points closed in the static step, 0 for open ones.
pub fn stuck_blocks(p: &Problem, stat: &StaticState) -> Vec<Matrix3<f64>> {
    p.contacts
        .iter()
        .enumerate()
        .map(|(i, c)| {
            if !stat.closed[i] {
                return Matrix3::zeros();
            }
            let kt = p.interfaces[c.interface].contact.k_t0_per_area;
            Matrix3::from_diagonal(&nalgebra::Vector3::new(stat.normal_stiffness[i], kt, kt))
                * c.area
        })
        .collect()
}

/// values += Σ Bᵀ K_p B for local blocks K_p.
pub fn add_blocks(p: &Problem, values: &mut [f64], blocks: &[Matrix3<f64>]) {
    for (c, k) in p.contacts.iter().zip(blocks) {
        p.sys.pairs.add(values, c.pair, &to_global(&c.frame, k));
    }
}

/// K̂ = K + a₀M + a₁D for step h.
pub fn effective_stiffness(p: &Problem, damping: Option<&Csc<f64>>, h: f64) -> Csc<f64> {
    let a0 = 1.0 / (BETA * h * h);
    let a1 = GAMMA / (BETA * h);
    let mut v: Vec<f64> = p
        .sys
        .k
        .values
        .iter()
        .zip(&p.sys.m.values)
        .map(|(k, m)| k + a0 * m)
        .collect();
    if let Some(d) = damping {
        for (x, dv) in v.iter_mut().zip(&d.values) {
            *x += a1 * dv;
        }
    }
    Csc {
        pattern: p.sys.pattern.clone(),
        values: v,
    }
}

/// Newmark on a scene's model.
pub struct Newmark<'a, 'n> {
    p: &'a Problem,
    k0: &'n Numeric<'n, f64>,
    damping: Option<&'a Csc<f64>>,
    forcing: Forcing<'a>,
    h: f64,
    /// Stuck blocks K_c0 per point.
    kc0: Vec<Matrix3<f64>>,
    /// H = K̂₀⁻¹ Bᵀ, n × m column-major.
    hmat: Vec<f64>,
    /// G = B H.
    g: DMatrix<f64>,
    tol: f64,
    /// Steps whose Newton stopped at MAX_NEWTON with ‖Φ‖ within LOOSE_TOLERANCE (accepted).
    pub loose_steps: usize,
}

impl<'a, 'n> Newmark<'a, 'n> {
    /// Precomputes H and G with the factors `k0` of K̂₀ (m solves).
    pub fn new(
        p: &'a Problem,
        k0: &'n Numeric<'n, f64>,
        kc0: Vec<Matrix3<f64>>,
        damping: Option<&'a Csc<f64>>,
        forcing: Forcing<'a>,
        h: f64,
        tol: f64,
    ) -> Result<Self, TimeError> {
        let n = p.sys.dofs.n_free();
        let np = p.contacts.len();
        let m = 3 * np;
        let mut hmat = vec![0.0; n * m];
        let mut g = DMatrix::zeros(m, m);
        let mut b = vec![0.0; n];
        let mut x = vec![0.0; n];
        for j in 0..m {
            let row = &p.contacts[j / 3].rows[j % 3];
            for &(i, w) in row {
                b[i] = w;
            }
            k0.solve_into(&b, &mut x)?;
            for &(i, _) in row {
                b[i] = 0.0;
            }
            for i in 0..n {
                hmat[i + n * j] = x[i];
            }
            for k in 0..m {
                g[(k, j)] = p.contacts[k / 3].rows[k % 3]
                    .iter()
                    .map(|&(i, w)| w * x[i])
                    .sum();
            }
        }
        Ok(Newmark {
            p,
            k0,
            damping,
            forcing,
            h,
            kc0,
            hmat,
            g,
            tol,
            loose_steps: 0,
        })
    }

    /// g(r) = q(r) − K_c0 r from the last trial.
    fn nonlinear_part(&self, contacts: &Contacts, r: &DVector<f64>) -> DVector<f64> {
        let q = contacts.trial_force();
        let mut out = DVector::zeros(r.len());
        for (i, k) in self.kc0.iter().enumerate() {
            for a in 0..3 {
                let mut kr = 0.0;
                for b in 0..3 {
                    kr += k[(a, b)] * r[3 * i + b];
                }
                out[3 * i + a] = q[i][a] - kr;
            }
        }
        out
    }
}

fn to_points(r: &DVector<f64>) -> Vec<[f64; 3]> {
    (0..r.len() / 3)
        .map(|i| [r[3 * i], r[3 * i + 1], r[3 * i + 2]])
        .collect()
}

impl Stepper for Newmark<'_, '_> {
    fn h(&self) -> f64 {
        self.h
    }

    fn loose_steps(&self) -> usize {
        self.loose_steps
    }

    fn step(&mut self, st: &mut State, contacts: &mut Contacts) -> Result<usize, TimeError> {
        let h = self.h;
        let (a0, a1, a2, a3) = (
            1.0 / (BETA * h * h),
            GAMMA / (BETA * h),
            1.0 / (BETA * h),
            0.5 / BETA - 1.0,
        );
        let (a4, a5) = (GAMMA / BETA - 1.0, 0.5 * h * (GAMMA / BETA - 2.0));
        let n = st.u.len();
        let t1 = st.t + h;
        let mut rhs = vec![0.0; n];
        self.forcing.at(t1, &mut rhs);
        let mv: Vec<f64> = (0..n)
            .map(|i| a0 * st.u[i] + a2 * st.v[i] + a3 * st.a[i])
            .collect();
        for (r, x) in rhs.iter_mut().zip(self.p.sys.m.mul_vec(&mv)) {
            *r += x;
        }
        if let Some(d) = self.damping {
            let dv: Vec<f64> = (0..n)
                .map(|i| a1 * st.u[i] + a4 * st.v[i] + a5 * st.a[i])
                .collect();
            for (r, x) in rhs.iter_mut().zip(d.mul_vec(&dv)) {
                *r += x;
            }
        }
        let u0 = self.k0.solve(&rhs)?;
        let m = 3 * contacts.len();
        let r0 = DVector::from_iterator(
            m,
            (0..m).map(|j| {
                self.p.contacts[j / 3].rows[j % 3]
                    .iter()
                    .map(|&(i, w)| w * u0[i])
                    .sum()
            }),
        );

        // Start: the committed nonlinear part carried over, r = r₀ − G g(r_committed).
        let committed = DVector::from_iterator(m, contacts.delta.iter().flat_map(|d| *d));
        let gq = DVector::from_iterator(
            m,
            (0..m).map(|j| {
                let i = j / 3;
                contacts.force[i][j % 3]
                    - (0..3)
                        .map(|b| self.kc0[i][(j % 3, b)] * committed[3 * i + b])
                        .sum::<f64>()
            }),
        );
        let mut r = &r0 - &self.g * &gq;
        let mut tangents = vec![Matrix3::zeros(); contacts.len()];
        let eval = |r: &DVector<f64>,
                    contacts: &mut Contacts,
                    tangents: &mut [Matrix3<f64>]|
         -> Result<(DVector<f64>, DVector<f64>), TimeError> {
            contacts.evaluate(&to_points(r), Some(tangents))?;
            let gr = self.nonlinear_part(contacts, r);
            let phi = r - &r0 + &self.g * &gr;
            Ok((gr, phi))
        };
        let (mut gr, mut phi) = eval(&r, contacts, &mut tangents)?;
        let scale = r0.amax().max(r.amax()).max(f64::MIN_POSITIVE);
        let mut iterations = 0;
        loop {
            let res = phi.amax() / scale;
            if res <= self.tol {
                break;
            }
            if iterations == MAX_NEWTON + MAX_FIXED_POINT {
                if res <= LOOSE_TOLERANCE.max(self.tol) {
                    self.loose_steps += 1;
                    break;
                }
                return Err(TimeError::Newton {
                    t: t1,
                    residual: res,
                    iterations,
                });
            }
            iterations += 1;
            let mut d = DMatrix::zeros(m, m);
            if iterations > MAX_NEWTON {
                // Secant iterations: per component the chord stiffness from the committed
                // state to the trial (no kink inside a chord, so no cycling across one).
                let q = contacts.trial_force();
                for i in 0..contacts.len() {
                    for a in 0..3 {
                        let dd = r[3 * i + a] - contacts.delta[i][a];
                        let chord = if dd.abs() > 1e-14 * scale {
                            (q[i][a] - contacts.force[i][a]) / dd
                        } else {
                            tangents[i][(a, a)]
                        };
                        d[(3 * i + a, 3 * i + a)] = chord - self.kc0[i][(a, a)];
                    }
                }
                let jac = DMatrix::identity(m, m) + &self.g * d;
                let Some(dr) = jac.lu().solve(&(-&phi)) else {
                    return Err(TimeError::Singular { t: t1 });
                };
                r += dr;
                let (g2, p2) = eval(&r, contacts, &mut tangents)?;
                gr = g2;
                phi = p2;
                continue;
            }
            for (i, t) in tangents.iter().enumerate() {
                let dt = t - self.kc0[i];
                for a in 0..3 {
                    for b in 0..3 {
                        d[(3 * i + a, 3 * i + b)] = dt[(a, b)];
                    }
                }
            }
            let jac = DMatrix::identity(m, m) + &self.g * d;
            let Some(dr) = jac.lu().solve(&(-&phi)) else {
                return Err(TimeError::Singular { t: t1 });
            };
            let old = phi.amax();
            let mut step = 1.0;
            let mut accepted = None;
            for _ in 0..=MAX_HALVINGS {
                let trial = &r + &dr * step;
                let (g2, p2) = eval(&trial, contacts, &mut tangents)?;
                if p2.amax() < old || step < 2f64.powi(-(MAX_HALVINGS as i32) + 1) {
                    accepted = Some((trial, g2, p2));
                    break;
                }
                step *= 0.5;
            }
            let (tr, g2, p2) = accepted.expect("the last halving is always accepted");
            r = tr;
            gr = g2;
            phi = p2;
        }
        // u₊ = u₀ − H g(r); the last evaluation was at r: commit it.
        let mut u1 = u0;
        for j in 0..m {
            let gj = gr[j];
            if gj != 0.0 {
                let col = &self.hmat[n * j..n * (j + 1)];
                for (u, hv) in u1.iter_mut().zip(col) {
                    *u -= hv * gj;
                }
            }
        }
        if u1.iter().any(|x| !x.is_finite()) {
            return Err(TimeError::NonFinite { t: t1 });
        }
        contacts.commit();
        for i in 0..n {
            let acc = a0 * (u1[i] - st.u[i]) - a2 * st.v[i] - a3 * st.a[i];
            st.v[i] += h * ((1.0 - GAMMA) * st.a[i] + GAMMA * acc);
            st.a[i] = acc;
            st.u[i] = u1[i];
        }
        st.t = t1;
        Ok(iterations)
    }
}
