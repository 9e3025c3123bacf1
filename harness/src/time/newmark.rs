//! Implicit Newmark in Hilber–Hughes–Taylor form (HHT-α, α ∈ [−1/3, 0], β = (1 − α)²/4,
//! γ = 1/2 − α: second order, unconditionally stable; α = 0 is the average-acceleration
//! rule without numerical damping, α < 0 damps the highest frequencies of the mesh and the
//! contact penalties, per step by a spectral radius ≈ (1 + α)/(1 − α), while the damping
//! it adds at the forcing frequency is O((ωh)³): as Abaqus/Standard's *DYNAMIC, ALPHA),
//! with Newton iterations on the contact unknowns.
//!
//! With a₊ = a₀(u₊ − u) − a₂v − a₃a (a₀ = 1/(βh²), a₂ = 1/(βh), a₃ = 1/(2β) − 1) and
//! v₊ = v + h((1 − γ)a + γa₊), the HHT equation of motion
//! M a₊ + (1 + α)(D v₊ + K u₊ + Bᵀq₊ − f₊) − α(D v + K u + Bᵀq − f) = 0, divided by 1 + α, is
//!
//!   K̂ u₊ + Bᵀ q(Bu₊) = f̂,   K̂ = K + c a₀M + a₁D (a₁ = γ/(βh), c = 1/(1 + α)),
//!   f̂ = f(t + h) + c M(a₀u + a₂v + a₃a) + D(a₁u + a₄v + a₅a) − cα (f(t) − D v − K u − Bᵀq),
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
use crate::linalg;
use crate::model::Problem;
use crate::solve::static_step::StaticState;
use crate::solve::umfpack::Numeric;

/// Newmark's β, γ and the mass factor c = 1/(1 + α) of HHT-α.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hht {
    pub alpha: f64,
    pub beta: f64,
    pub gamma: f64,
}

impl Hht {
    /// The scheme for α ∈ [−1/3, 0] (checked by the settings).
    pub fn new(alpha: f64) -> Self {
        Hht {
            alpha,
            beta: 0.25 * (1.0 - alpha) * (1.0 - alpha),
            gamma: 0.5 - alpha,
        }
    }

    /// [a₀, a₁, a₂, a₃, a₄, a₅] of step h (module docs).
    pub fn coefficients(&self, h: f64) -> [f64; 6] {
        let (beta, gamma) = (self.beta, self.gamma);
        [
            1.0 / (beta * h * h),
            gamma / (beta * h),
            1.0 / (beta * h),
            0.5 / beta - 1.0,
            gamma / beta - 1.0,
            0.5 * h * (gamma / beta - 2.0),
        ]
    }

    /// c = 1/(1 + α), the weight of M against K, D and the contacts.
    fn mass_weight(&self) -> f64 {
        1.0 / (1.0 + self.alpha)
    }
}
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

/// K̂ = K + c a₀M + a₁D for step h.
pub fn effective_stiffness(
    p: &Problem,
    damping: Option<&Csc<f64>>,
    h: f64,
    scheme: Hht,
) -> Csc<f64> {
    let [a0, a1, ..] = scheme.coefficients(h);
    let a0 = scheme.mass_weight() * a0;
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

/// What an implicit integrator of a scene's model is built from.
#[derive(Clone)]
pub struct Setup<'a> {
    pub p: &'a Problem,
    /// Stuck blocks K_c0 per point ([`stuck_blocks`]).
    pub kc0: Vec<Matrix3<f64>>,
    pub damping: Option<&'a Csc<f64>>,
    pub forcing: Forcing<'a>,
    /// Step (time).
    pub h: f64,
    pub scheme: Hht,
    /// Newton: ‖Φ‖∞ ≤ this × max|r|.
    pub tol: f64,
}

/// Newmark on a scene's model.
pub struct Newmark<'a, 'n> {
    p: &'a Problem,
    k0: &'n Numeric<'n, f64>,
    damping: Option<&'a Csc<f64>>,
    forcing: Forcing<'a>,
    h: f64,
    scheme: Hht,
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
    /// Precomputes H and G with the factors `k0` of K̂₀ (m solves), K̂₀ built with the
    /// setup's step and scheme ([`effective_stiffness`] and its K_c0).
    pub fn new(setup: Setup<'a>, k0: &'n Numeric<'n, f64>) -> Result<Self, TimeError> {
        let Setup {
            p,
            kc0,
            damping,
            forcing,
            h,
            scheme,
            tol,
        } = setup;
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
            scheme,
            kc0,
            hmat,
            g,
            tol,
            loose_steps: 0,
        })
    }

    /// f̂ of the step from `st` (module docs).
    fn effective_load(&self, st: &State, contacts: &Contacts) -> Vec<f64> {
        let [a0, a1, a2, a3, a4, a5] = self.scheme.coefficients(self.h);
        let c = self.scheme.mass_weight();
        let n = st.u.len();
        let mut rhs = vec![0.0; n];
        self.forcing.at(st.t + self.h, &mut rhs);
        self.add_old_state_forces(st, contacts, &mut rhs);
        let mv: Vec<f64> = (0..n)
            .map(|i| c * (a0 * st.u[i] + a2 * st.v[i] + a3 * st.a[i]))
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
        rhs
    }

    /// rhs −= cα (f(t) − D v − K u − Bᵀq) at the committed state (HHT's weight of the
    /// old step; nothing for α = 0).
    fn add_old_state_forces(&self, st: &State, contacts: &Contacts, rhs: &mut [f64]) {
        let alpha = self.scheme.alpha;
        if alpha == 0.0 {
            return;
        }
        let n = st.u.len();
        let mut old = vec![0.0; n];
        self.forcing.at(st.t, &mut old);
        for (o, x) in old.iter_mut().zip(self.p.sys.k.mul_vec(&st.u)) {
            *o -= x;
        }
        if let Some(d) = self.damping {
            for (o, x) in old.iter_mut().zip(d.mul_vec(&st.v)) {
                *o -= x;
            }
        }
        let mut internal = vec![0.0; n];
        contacts.add_internal(&contacts.force, &mut internal);
        let w = alpha * self.scheme.mass_weight();
        for ((r, o), q) in rhs.iter_mut().zip(&old).zip(&internal) {
            *r -= w * (o - q);
        }
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

    /// The Newton matrix's contact part: per point its tangent less K_c0 (the 3 × 3
    /// blocks of a block-diagonal m × m).
    fn tangent_stiffness(&self, tangents: &[Matrix3<f64>]) -> Vec<Matrix3<f64>> {
        tangents.iter().zip(&self.kc0).map(|(t, k)| t - k).collect()
    }

    /// I + G D for the block-diagonal D of `blocks` (3 × 3 per point): each point's
    /// three columns of G times its block, 9m² products instead of a dense m³.
    fn newton_matrix(&self, blocks: &[Matrix3<f64>]) -> DMatrix<f64> {
        let m = 3 * blocks.len();
        let mut jac = DMatrix::identity(m, m);
        for (i, block) in blocks.iter().enumerate() {
            jac.columns_mut(3 * i, 3)
                .gemm(1.0, &self.g.columns(3 * i, 3), block, 1.0);
        }
        jac
    }

    /// The secant iterations' contact part: per component the chord stiffness from the
    /// committed state to the trial at `r` (no kink inside a chord, so no cycling across
    /// one), less K_c0; the tangent where the chord is shorter than 1e-14 `scale`.
    fn secant_stiffness(
        &self,
        contacts: &Contacts,
        r: &DVector<f64>,
        tangents: &[Matrix3<f64>],
        scale: f64,
    ) -> Vec<Matrix3<f64>> {
        let q = contacts.trial_force();
        (0..contacts.len())
            .map(|i| {
                Matrix3::from_fn(|a, b| {
                    if a != b {
                        return 0.0;
                    }
                    let dd = r[3 * i + a] - contacts.delta[i][a];
                    let chord = if dd.abs() > 1e-14 * scale {
                        (q[i][a] - contacts.force[i][a]) / dd
                    } else {
                        tangents[i][(a, a)]
                    };
                    chord - self.kc0[i][(a, a)]
                })
            })
            .collect()
    }

    /// u₊ = u₀ − H g: the linear step's displacement corrected by the contacts'
    /// nonlinear part g through H's columns.
    fn corrected(&self, mut u: Vec<f64>, g: &DVector<f64>) -> Vec<f64> {
        let n = u.len();
        for (j, &gj) in g.iter().enumerate() {
            if gj != 0.0 {
                let col = &self.hmat[n * j..n * (j + 1)];
                for (x, hv) in u.iter_mut().zip(col) {
                    *x -= hv * gj;
                }
            }
        }
        u
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
        let (h, gamma) = (self.h, self.scheme.gamma);
        let [a0, _, a2, a3, _, _] = self.scheme.coefficients(h);
        let n = st.u.len();
        let t1 = st.t + h;
        let u0 = self.k0.solve(&self.effective_load(st, contacts))?;
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
        // The best iterate so far: the secant phase may wander off a Newton iterate that
        // was already within the loose tolerance.
        let mut best = (f64::INFINITY, r.clone());
        loop {
            let res = phi.amax() / scale;
            if res <= self.tol {
                break;
            }
            if res < best.0 {
                best = (res, r.clone());
            }
            if iterations == MAX_NEWTON + MAX_FIXED_POINT {
                if best.0 <= LOOSE_TOLERANCE.max(self.tol) {
                    gr = eval(&best.1, contacts, &mut tangents)?.0;
                    self.loose_steps += 1;
                    break;
                }
                return Err(TimeError::Newton {
                    t: t1,
                    residual: best.0,
                    iterations,
                });
            }
            iterations += 1;
            if iterations > MAX_NEWTON {
                let d = self.secant_stiffness(contacts, &r, &tangents, scale);
                let Some(dr) = linalg::solve(&self.newton_matrix(&d), &(-&phi)) else {
                    return Err(TimeError::Singular { t: t1 });
                };
                r += dr;
                let (g2, p2) = eval(&r, contacts, &mut tangents)?;
                gr = g2;
                phi = p2;
                continue;
            }
            let jac = self.newton_matrix(&self.tangent_stiffness(&tangents));
            let Some(dr) = linalg::solve(&jac, &(-&phi)) else {
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
        let u1 = self.corrected(u0, &gr);
        if u1.iter().any(|x| !x.is_finite()) {
            return Err(TimeError::NonFinite { t: t1 });
        }
        contacts.commit();
        for i in 0..n {
            let acc = a0 * (u1[i] - st.u[i]) - a2 * st.v[i] - a3 * st.a[i];
            st.v[i] += h * ((1.0 - gamma) * st.a[i] + gamma * acc);
            st.a[i] = acc;
            st.u[i] = u1[i];
        }
        st.t = t1;
        Ok(iterations)
    }
}
