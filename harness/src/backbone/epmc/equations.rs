//! The EPMC equations at one modal amplitude and Newton on them.
//!
//! Unknowns (ψ, ω, ξ) at modal amplitude q (x = x_s + qψ about the static state x_s,
//! DOF-major coefficients of [`crate::mhb::aft`]); equations
//!
//!   F = R(x_s + qψ, ω)/q − ξ ω M ∂ψ/∂τ-term = 0 (2H + 1 rows per DOF),
//!   ψ₁ᴴMψ₁ − 1 = 0 (normalization of the first harmonic),
//!   φ_rᵀM b₁ = 0 (phase: sine part of the first harmonic orthogonal to the stuck mode),
//!
//! plus, on the mean rows, a gauge spring s·Z Zᵀ ψ₀ (ψ₀ the mean coefficients, Z an
//! orthonormal basis of the mean motions the structure does not resist: the null space of
//! the linear stiffness with the points' normal springs, a block held tangentially only
//! by friction). The mean of such a motion is not set by the periodic balance: the thesis
//! rule's closed loop is the same for every constant offset of δ (it drifts to the loop
//! about zero force), and so is a sliding Jenkins or Masing point's, so those mean rows
//! are zero and their columns a null space of the Jacobian (the block on the plane: the
//! backbone stopped at its first amplitude). The spring picks the solution without a
//! mean offset; it acts on mean coefficients only, so no harmonic changes, and where a
//! stuck point does resist the offset the solution stays the one without it (the free
//! system's mean is zero).
//!
//! with R the residual of the free harmonic balance, one-direction elements and
//! three-direction points ([`crate::mhb::contact3d::Hb3::eval`]; R(x_s) = 0). The
//! derivative in ln q, for continuation through turning points, is exact:
//! ∂(R(x_s + qψ)/q)/∂ln q = R_x ψ − R/q (zero for a linear system).

use nalgebra::{DMatrix, DVector};

use super::super::BackboneError;
use crate::linalg;
use crate::mhb::contact3d::Hb3;

/// Newton tolerance on the scaled residual.
pub const RTOL: f64 = 1e-9;
/// A Newton step shorter than this (relative to the state) at a residual below
/// [`FLOOR_RTOL`] ends Newton at the round-off floor of a large system.
pub const STAGNATION: f64 = 1e-12;
pub const FLOOR_RTOL: f64 = 1e2 * RTOL;
const MAX_NEWTON: usize = 40;
/// Full Newton steps that raise |R| (at most tenfold) allowed per solve.
const MAX_NONMONOTONE: usize = 5;

/// ψ, ω (rad/time), ξ (1/time).
#[derive(Debug, Clone)]
pub struct State {
    pub psi: Vec<f64>,
    pub omega: f64,
    pub xi: f64,
}

/// Residual, Jacobians and energy per element at one state.
pub struct Evaluated {
    /// F (dim + 2).
    pub f: DVector<f64>,
    /// ∂F/∂(ψ, ω, ξ), square.
    pub jac: DMatrix<f64>,
    /// ∂F/∂ln q.
    pub d_lnq: DVector<f64>,
    /// Energy dissipated per cycle by each 1D element, then each point (force·length).
    pub dissipated: Vec<f64>,
}

pub struct Epmc<'a> {
    pub hb: Hb3<'a>,
    /// The static state's coefficients x_s (its mean only; zeros without a static load).
    pub rest: Vec<f64>,
    /// M·φ_r (phase condition row).
    pub m_ref: Vec<f64>,
    /// Residual scale ω₀² (ψ is mass-normalized).
    pub scale: f64,
    /// The gauge spring s·Z Zᵀ on the mean coefficients (module docs; n × n, zero where
    /// the structure resists every mean motion).
    pub gauge: DMatrix<f64>,
    /// Told every modal amplitude a solution is found at (progress of long backbones).
    pub on_point: Option<&'a dyn Fn(f64)>,
}

impl Epmc<'_> {
    /// Tells [`Epmc::on_point`] that a solution at modal amplitude `q` was found.
    pub fn passed(&self, q: f64) {
        if let Some(f) = self.on_point {
            f(q);
        }
    }

    /// F and its derivatives at (ψ, ω, ξ) and modal amplitude q.
    pub fn eval(&mut self, st: &State, q: f64) -> Result<Evaluated, BackboneError> {
        let s = &self.hb.system().linear;
        let (n, m) = (s.n(), self.hb.ncoef());
        let dim = n * m;
        let x: Vec<f64> = st
            .psi
            .iter()
            .zip(&self.rest)
            .map(|(v, r)| r + v * q)
            .collect();
        let ev = self.hb.eval(&x, st.omega)?;
        let mut f = DVector::zeros(dim + 2);
        let mut jac = DMatrix::zeros(dim + 2, dim + 2);
        let r_q = &ev.r / q;
        f.rows_mut(0, dim).copy_from(&r_q);
        let mut d_lnq = DVector::zeros(dim + 2);
        let psi = DVector::from_column_slice(&st.psi);
        d_lnq.rows_mut(0, dim).copy_from(&(&ev.j * &psi - &r_q));
        jac.view_mut((0, 0), (dim, dim)).copy_from(&ev.j);
        for i in 0..dim {
            jac[(i, dim)] = ev.r_omega[i] / q;
        }
        // The −ξM ẋ term, per harmonic h: [0, −hωξM; hωξM, 0] on (cos, sin).
        let (w, xi) = (st.omega, st.xi);
        for h in 1..=self.hb.h() {
            let hh = h as f64;
            for a in 0..n {
                let (ca, sa) = (a * m + 2 * h - 1, a * m + 2 * h);
                for b in 0..n {
                    let mab = s.m[(a, b)];
                    if mab == 0.0 {
                        continue;
                    }
                    let (cb, sb) = (b * m + 2 * h - 1, b * m + 2 * h);
                    let (pc, ps) = (st.psi[cb], st.psi[sb]);
                    f[ca] -= hh * w * xi * mab * ps;
                    f[sa] += hh * w * xi * mab * pc;
                    jac[(ca, sb)] -= hh * w * xi * mab;
                    jac[(sa, cb)] += hh * w * xi * mab;
                    jac[(ca, dim)] -= hh * xi * mab * ps;
                    jac[(sa, dim)] += hh * xi * mab * pc;
                    jac[(ca, dim + 1)] -= hh * w * mab * ps;
                    jac[(sa, dim + 1)] += hh * w * mab * pc;
                }
            }
        }
        // The gauge spring on the mean coefficients (module docs).
        for a in 0..n {
            for b in 0..n {
                let g = self.gauge[(a, b)];
                if g != 0.0 {
                    f[a * m] += g * st.psi[b * m];
                    jac[(a * m, b * m)] += g;
                }
            }
        }
        // Normalization ψ₁ᴴMψ₁ = 1 and phase φ_rᵀMb₁ = 0.
        let mut norm = -1.0;
        for a in 0..n {
            for b in 0..n {
                let mab = s.m[(a, b)];
                let (ca, sa, cb, sb) = (a * m + 1, a * m + 2, b * m + 1, b * m + 2);
                norm += mab * (st.psi[ca] * st.psi[cb] + st.psi[sa] * st.psi[sb]);
                jac[(dim, ca)] += 2.0 * mab * st.psi[cb];
                jac[(dim, sa)] += 2.0 * mab * st.psi[sb];
            }
            jac[(dim + 1, a * m + 2)] = self.m_ref[a];
        }
        f[dim] = norm;
        f[dim + 1] = (0..n).map(|a| self.m_ref[a] * st.psi[a * m + 2]).sum();
        let mut dissipated = ev.element_dissipated;
        dissipated.extend(ev.dissipated);
        Ok(Evaluated {
            f,
            jac,
            d_lnq,
            dissipated,
        })
    }

    /// The residual measure every convergence test uses: the balance rows over ω₀²,
    /// the normalization and phase rows as they are.
    pub fn scaled(&self, f: &DVector<f64>) -> f64 {
        let dim = f.len() - 2;
        (f.rows(0, dim).norm() / self.scale).max(f[dim].abs().max(f[dim + 1].abs()))
    }

    /// Newton at fixed q from `st` (line search, a few non-monotone steps). `Err` holds
    /// the last scaled residual.
    pub fn solve(&mut self, mut st: State, q: f64) -> Result<(State, Vec<f64>), f64> {
        let dim = st.psi.len();
        let Ok(mut ev) = self.eval(&st, q) else {
            return Err(f64::INFINITY);
        };
        let mut res = self.scaled(&ev.f);
        let mut nonmonotone = 0;
        for _ in 0..MAX_NEWTON {
            if res <= RTOL {
                return Ok((st, ev.dissipated));
            }
            let Some(dy) = linalg::solve(&ev.jac, &ev.f) else {
                return Err(res);
            };
            let size = st.psi.iter().map(|v| v * v).sum::<f64>().sqrt() + st.omega.abs();
            if res <= FLOOR_RTOL && dy.norm() <= STAGNATION * size {
                return Ok((st, ev.dissipated));
            }
            let step = damped_step(
                res,
                &mut nonmonotone,
                MAX_NONMONOTONE,
                |lambda| State {
                    psi: (0..dim).map(|i| st.psi[i] - lambda * dy[i]).collect(),
                    omega: st.omega - lambda * dy[dim],
                    xi: st.xi - lambda * dy[dim + 1],
                },
                |trial| {
                    let e2 = (trial.omega > 0.0).then(|| self.eval(trial, q).ok())??;
                    let r2 = self.scaled(&e2.f);
                    Some((e2, r2))
                },
            );
            match step {
                Some(next) => (st, ev, res) = next,
                None => return Err(res),
            }
        }
        if res <= RTOL {
            Ok((st, ev.dissipated))
        } else {
            Err(res)
        }
    }
}

/// Eigenvalues of the stiffness below this fraction of its largest count as free mean
/// motions ([`gauge_spring`]; a rigid block's are round-off, ~1e-16 of the largest).
const FREE_MEAN: f64 = 1e-10;

/// The gauge spring s·Z Zᵀ of the module docs for the stiffness `k` (symmetric, with
/// the normal springs; without the tangential joints): Z the eigenvectors of `k` with
/// |λ| ≤ [`FREE_MEAN`]·max|λ|, s the largest diagonal entry of `k` (so the spring is as
/// stiff as the stiffest DOF and the Jacobian's scale does not grow). Zero without free
/// mean motions.
pub fn gauge_spring(k: &DMatrix<f64>) -> DMatrix<f64> {
    let n = k.nrows();
    let mut g = DMatrix::zeros(n, n);
    let eig = nalgebra::SymmetricEigen::new(k.clone());
    let top = eig.eigenvalues.amax();
    let s = k.diagonal().max();
    if !(top > 0.0 && s > 0.0) {
        return g;
    }
    for (i, l) in eig.eigenvalues.iter().enumerate() {
        if l.abs() <= FREE_MEAN * top {
            let z = eig.eigenvectors.column(i);
            g += s * z * z.transpose();
        }
    }
    g
}

/// Halvings of a Newton step in [`damped_step`].
const LINE_SEARCH: usize = 8;

/// One damped Newton step from residual `res`: the first of the steps λ = 1, ½, … (at
/// most [`LINE_SEARCH`] halvings; `trial(λ)` the point, `eval` its evaluation and
/// residual) that lowers the residual. The contact forces of the AFT are piecewise
/// smooth (a sample changes between sticking and sliding): where no shortened step
/// lowers it, the full step is taken if it raises the residual less than tenfold, at most
/// `max_nonmonotone` times per solve (counted in `nonmonotone`). `None`: no step.
pub fn damped_step<S, E>(
    res: f64,
    nonmonotone: &mut usize,
    max_nonmonotone: usize,
    trial: impl Fn(f64) -> S,
    mut eval: impl FnMut(&S) -> Option<(E, f64)>,
) -> Option<(S, E, f64)> {
    let mut lambda = 1.0;
    let mut full = None;
    for _ in 0..LINE_SEARCH {
        let t = trial(lambda);
        if let Some((e, r)) = eval(&t) {
            if r < res {
                return Some((t, e, r));
            }
            if lambda == 1.0 && r < 10.0 * res {
                full = Some((t, e, r));
            }
        }
        lambda *= 0.5;
    }
    let f = full.filter(|_| *nonmonotone < max_nonmonotone)?;
    *nonmonotone += 1;
    Some(f)
}
