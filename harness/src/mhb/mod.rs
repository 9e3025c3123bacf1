//! Multi-harmonic balance: the rungs between the thesis's first-order
//! linearization and time integration, for few-DOF lumped systems (mass/spring/damper
//! chains with contact elements between DOFs or to ground).
//!
//! M ẍ + D ẋ + K x + Σ_e Pₑᵀ Fₑ(Pₑ x) = f₀ + Re(f̂ e^{iωt}), with Pₑ x = x_i − x_j the
//! element's relative displacement. x is sought as a Fourier series with H harmonics (the
//! zeroth included, [`aft`] layout per DOF); the residual per harmonic h (cos/sin pair)
//!
//!   R_h = [K − h²ω²M, hωD; −hωD, K − h²ω²M] (a_h, b_h) + F̂ₑ,h − f̂_h
//!
//! (Galerkin projection of the equation of motion on cos hτ, sin hτ, e.g. Krack & Gross,
//! *Harmonic Balance for Nonlinear Vibration Problems*, 2019, eq. 2.19) with the element
//! forces F̂ₑ from the alternating frequency–time scheme ([`aft`]), the library's
//! stateful point marched through the C API. Newton ([`Hb::solve`]) uses the Jacobian
//! assembled from the tangents the point returns; [`continuation`] traces branches in ω
//! through folds. H = 1 is the thesis's first-order harmonic balance (3.5–3.8) applied to
//! the actual force rather than to the Ersatzfunktion (4.3); [`first_order`] is the
//! library's linearization (`jointlin_linearize`) iterated to consistency, for comparison.
//!
//! The system itself ([`System`], its [`Element`]s and their [`Law`]s) is the model's
//! (`model::lumped_system`). Built on this room: the FE sweep's harmonic balance (`solve::sweep::harmonic_fe`), the
//! RK4 reference of these systems (`time::mhb_reference`) and the cost tables of
//! `jointlin mhb` (`bench::mhb_chain`, `bench::mhb_fe`).

pub mod aft;
mod aitken;
pub mod consistency;
pub mod contact3d;
pub mod continuation;
pub mod first_order;
pub mod loops;
pub mod lumped_sweep;

#[cfg(test)]
mod tests;

use nalgebra::{DMatrix, DVector};

use crate::linalg::{self, Lu};
use crate::util::parallel::{in_parallel_with, threads};

pub use crate::model::lumped_system::{Element, Law, System};
pub use aft::{AftError, Transforms};

/// Zeroth and first harmonics (DOF-major, `m` = 2H + 1 coefficients per DOF, higher ones
/// zero) of the linear system with stiffness `k` in place of `sys.k`: K x̄ = f₀ and
/// (K − ω²M + iωD) x̂ = f̂ (a singular system leaves its harmonic at zero).
pub fn linear_coefficients(
    sys: &System,
    k: &DMatrix<f64>,
    f0: &DVector<f64>,
    omega: f64,
    m: usize,
) -> Vec<f64> {
    use nalgebra::Complex;
    let n = sys.n();
    let dyn_k = DMatrix::from_fn(n, n, |a, b| {
        Complex::new(
            k[(a, b)] - omega * omega * sys.m[(a, b)],
            omega * sys.d[(a, b)],
        )
    });
    let f1 = DVector::from_iterator(n, sys.f1.iter().copied());
    let x1 = dyn_k.lu().solve(&f1);
    let x0 = k.clone().lu().solve(f0);
    let mut u = vec![0.0; n * m];
    for d in 0..n {
        if let Some(x0) = &x0 {
            u[d * m] = x0[d];
        }
        if let Some(x1) = &x1 {
            u[d * m + 1] = x1[d].re;
            u[d * m + 2] = -x1[d].im;
        }
    }
    u
}

/// The state (x, ẋ) at t = 0 of a solution `u` with H harmonics (DOF-major, `u.len()` /
/// (2H + 1) DOFs) at ω: x(0) = c₀ + Σ a_h, ẋ(0) = Σ hω b_h. The start of a time-domain
/// reference on a balance's solution.
pub fn state_at_zero(u: &[f64], h: usize, omega: f64) -> (Vec<f64>, Vec<f64>) {
    let m = 2 * h + 1;
    let n = u.len() / m;
    let x = (0..n)
        .map(|d| u[d * m] + (1..=h).map(|j| u[d * m + 2 * j - 1]).sum::<f64>())
        .collect();
    let v = (0..n)
        .map(|d| {
            (1..=h)
                .map(|j| j as f64 * omega * u[d * m + 2 * j])
                .sum::<f64>()
        })
        .collect();
    (x, v)
}

/// Samples per period used unless a caller sets N: 16(H + 1) rounded up to a power of
/// two, at least 64 (the contact force has kinks, so its spectrum decays like h⁻²; the
/// sampled force aliases harmonics above N − H onto the retained ones; 16 samples per
/// retained harmonic keep that below 1e-3 of the first harmonic, tests measure it).
pub fn default_samples(h: usize) -> usize {
    (16 * (h + 1)).next_power_of_two().max(64)
}

/// Newton settings.
#[derive(Debug, Clone, Copy)]
pub struct NewtonOptions {
    /// ‖R‖ ≤ rtol·‖load‖ to stop.
    pub rtol: f64,
    pub max_iter: usize,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            // Far above the AFT round-off (loop closure 1e-11), far below any physics.
            rtol: 1e-9,
            max_iter: 60,
        }
    }
}

/// Errors of the harmonic balance.
#[derive(Debug, thiserror::Error)]
pub enum MhbError {
    #[error(transparent)]
    Aft(#[from] AftError),
    #[error("Newton did not converge at ω = {omega:.6e} (|R|/|f| = {residual:.3e} after {iterations} iterations)")]
    Newton {
        omega: f64,
        residual: f64,
        iterations: usize,
    },
    #[error(
        "first-order amplitudes not consistent at ω = {omega:.6e} (relative mismatch {mismatch:.3e} after {iterations} steps of {method})",
        method = consistency::METHOD
    )]
    Consistency {
        omega: f64,
        mismatch: f64,
        iterations: usize,
    },
    #[error("singular Jacobian at ω = {omega:.6e}")]
    Singular { omega: f64 },
    #[error("continuation: {0}")]
    Continuation(String),
}

/// The harmonic balance of one system at H harmonics and N samples.
pub struct Hb<'a> {
    pub sys: &'a System,
    pub tr: Transforms,
    /// AFT evaluations (element marches) made.
    pub evaluations: u64,
    /// Threads the element marches run on: one until an evaluation's marches take
    /// longer than [`PARALLEL_ABOVE`], then the machine's (the elements are independent,
    /// so the numbers do not depend on it).
    threads: usize,
    /// How Mindlin points' Jacobians are formed (exact unless a caller falls back).
    pub jacobian: aft::Jacobian,
}

/// Marching all elements once taking longer than this (seconds) moves the marches onto
/// threads: below it, starting threads would cost more than it saves.
const PARALLEL_ABOVE: f64 = 2e-3;

/// Residual, its Jacobian in u and its derivative in ω at one point.
pub struct Eval {
    pub r: DVector<f64>,
    pub j: DMatrix<f64>,
    pub r_omega: DVector<f64>,
    /// Energy dissipated per period by each element.
    pub dissipated: Vec<f64>,
}

/// A converged periodic solution.
#[derive(Debug, Clone)]
pub struct Solution {
    pub omega: f64,
    /// Coefficients, DOF-major: u[dof·(2H+1) + c].
    pub u: Vec<f64>,
    pub iterations: usize,
    pub residual: f64,
    /// sign of det ∂R/∂u (changes at folds; see [`continuation`]).
    pub det_sign: f64,
    pub dissipated: Vec<f64>,
}

impl<'a> Hb<'a> {
    pub fn new(sys: &'a System, h: usize, n: usize) -> Self {
        Hb {
            sys,
            tr: Transforms::new(n, h),
            evaluations: 0,
            threads: 1,
            jacobian: aft::Jacobian::Exact,
        }
    }

    pub fn h(&self) -> usize {
        self.tr.h
    }

    /// Unknowns n·(2H+1).
    pub fn size(&self) -> usize {
        self.sys.n() * self.tr.ncoef()
    }

    /// Load coefficients f̂ in the unknowns' layout.
    pub fn load(&self) -> DVector<f64> {
        let m = self.tr.ncoef();
        let mut f = DVector::zeros(self.size());
        for i in 0..self.sys.n() {
            f[i * m] = self.sys.f0[i];
            f[i * m + 1] = self.sys.f1[i].re;
            f[i * m + 2] = -self.sys.f1[i].im;
        }
        f
    }

    /// Residual and derivatives at (u, ω).
    pub fn eval(&mut self, u: &[f64], omega: f64) -> Result<Eval, MhbError> {
        let (n, m) = (self.sys.n(), self.tr.ncoef());
        let size = n * m;
        let mut j = DMatrix::zeros(size, size);
        let mut r_omega = DVector::zeros(size);
        let s = self.sys;
        // Linear part, per harmonic (module docs).
        for a in 0..n {
            for b in 0..n {
                j[(a * m, b * m)] = s.k[(a, b)];
                for h in 1..=self.tr.h {
                    let hw = h as f64 * omega;
                    let kd = s.k[(a, b)] - hw * hw * s.m[(a, b)];
                    let (ca, sa) = (a * m + 2 * h - 1, a * m + 2 * h);
                    let (cb, sb) = (b * m + 2 * h - 1, b * m + 2 * h);
                    j[(ca, cb)] = kd;
                    j[(sa, sb)] = kd;
                    j[(ca, sb)] = hw * s.d[(a, b)];
                    j[(sa, cb)] = -hw * s.d[(a, b)];
                    // ∂/∂ω of the blocks times u.
                    let hh = h as f64;
                    let dk = -2.0 * hh * hw * s.m[(a, b)];
                    let dd = hh * s.d[(a, b)];
                    r_omega[ca] += dk * u[cb] + dd * u[sb];
                    r_omega[sa] += dk * u[sb] - dd * u[cb];
                }
            }
        }
        let uv = DVector::from_column_slice(u);
        let mut r = &j * &uv - self.load();
        let mut dissipated = Vec::with_capacity(s.elements.len());
        for (e, ev) in s.elements.iter().zip(self.march_elements(u)?) {
            dissipated.push(ev.period.dissipated);
            // Pᵀ F̂ and Pᵀ J P with P = [I, −I] on (i, j).
            let ends: [(usize, f64); 2] = [(e.i, 1.0), (e.j.unwrap_or(usize::MAX), -1.0)];
            for &(p, sp) in &ends {
                if p == usize::MAX {
                    continue;
                }
                for c in 0..m {
                    r[p * m + c] += sp * ev.force[c];
                }
                for &(q, sq) in &ends {
                    if q == usize::MAX {
                        continue;
                    }
                    for a in 0..m {
                        for b in 0..m {
                            j[(p * m + a, q * m + b)] += sp * sq * ev.jac[a * m + b];
                        }
                    }
                }
            }
        }
        Ok(Eval {
            r,
            j,
            r_omega,
            dissipated,
        })
    }

    /// Every element's AFT at the coefficients `u`, on [`Hb::threads`] threads.
    fn march_elements(&mut self, u: &[f64]) -> Result<Vec<aft::ElementEval>, MhbError> {
        let m = self.tr.ncoef();
        let relative = |e: &Element| -> Vec<f64> {
            (0..m)
                .map(|c| u[e.i * m + c] - e.j.map_or(0.0, |jj| u[jj * m + c]))
                .collect()
        };
        let started = std::time::Instant::now();
        let elements = &self.sys.elements;
        let jacobian = self.jacobian;
        let evals: Vec<_> = if self.threads == 1 {
            let tr = &mut self.tr;
            elements
                .iter()
                .map(|e| aft::evaluate_with(tr, &e.law, &relative(e), jacobian))
                .collect()
        } else {
            let (n, h) = (self.tr.n, self.tr.h);
            in_parallel_with(
                elements,
                self.threads,
                || Transforms::new(n, h),
                |tr, e| aft::evaluate_with(tr, &e.law, &relative(e), jacobian),
            )
        };
        self.evaluations += elements.len() as u64;
        if started.elapsed().as_secs_f64() > PARALLEL_ABOVE {
            self.threads = threads();
        }
        Ok(evals.into_iter().collect::<Result<_, _>>()?)
    }

    /// Newton from `u0` at fixed ω, with step halving when the residual grows.
    pub fn solve(
        &mut self,
        u0: &[f64],
        omega: f64,
        opt: NewtonOptions,
    ) -> Result<Solution, MhbError> {
        let scale = self.load().norm().max(f64::MIN_POSITIVE);
        let mut u = DVector::from_column_slice(u0);
        let mut ev = self.eval(u.as_slice(), omega)?;
        let mut res = ev.r.norm() / scale;
        for it in 1..=opt.max_iter {
            let du = linalg::solve(&ev.j, &ev.r).ok_or(MhbError::Singular { omega })?;
            let mut lambda = 1.0;
            let mut accepted = None;
            for _ in 0..10 {
                let trial = &u - lambda * &du;
                let e2 = self.eval(trial.as_slice(), omega)?;
                let r2 = e2.r.norm() / scale;
                if r2 < res || lambda < 1e-2 {
                    accepted = Some((trial, e2, r2));
                    break;
                }
                lambda *= 0.5;
            }
            let (trial, e2, r2) = accepted.expect("the last halving is always accepted");
            u = trial;
            ev = e2;
            res = r2;
            if res <= opt.rtol {
                let det_sign = Lu::factor(&ev.j).map_or(0.0, |lu| lu.determinant_sign());
                return Ok(Solution {
                    omega,
                    u: u.as_slice().to_vec(),
                    iterations: it,
                    residual: res,
                    det_sign,
                    dissipated: ev.dissipated,
                });
            }
        }
        Err(MhbError::Newton {
            omega,
            residual: res,
            iterations: opt.max_iter,
        })
    }

    /// The start vector of the linear system without its elements at ω (first harmonic
    /// of (K − ω²M + iωD) x̂ = f̂, zeroth from K x̄ = f₀): a cold start for Newton, e.g.
    /// after a sweep has passed a fold (the old branch no longer exists).
    pub fn linear_start(&self, omega: f64) -> Vec<f64> {
        self.linear_response(omega, false)
    }

    /// The start vector of the linear system with every contact element stuck (its
    /// stiffness k_T0 between its DOFs, thesis (2.46); cubic springs contribute nothing
    /// at zero amplitude): the exact solution while every contact sticks (a Jenkins
    /// element below μF_N), the usual start of a sweep from low forces.
    pub fn stuck_start(&self, omega: f64) -> Vec<f64> {
        self.linear_response(omega, true)
    }

    /// First and zeroth harmonics of the linear system, contact elements removed or
    /// stuck.
    fn linear_response(&self, omega: f64, stuck: bool) -> Vec<f64> {
        let m = self.tr.ncoef();
        let s = &self.sys;
        let k = if stuck {
            s.stuck_stiffness()
        } else {
            s.k.clone()
        };
        linear_coefficients(s, &k, &DVector::from_column_slice(&s.f0), omega, m)
    }

    /// First-harmonic amplitude √(a₁² + b₁²) of DOF `dof` in `u`.
    pub fn amplitude(&self, u: &[f64], dof: usize) -> f64 {
        let m = self.tr.ncoef();
        u[dof * m + 1].hypot(u[dof * m + 2])
    }

    /// Half the peak-to-peak range of DOF `dof` over the N samples of the period.
    pub fn half_range(&mut self, u: &[f64], dof: usize) -> f64 {
        let m = self.tr.ncoef();
        let mut x = vec![0.0; self.tr.n];
        self.tr.synthesize(&u[dof * m..(dof + 1) * m], &mut x);
        let (lo, hi) = x
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                (l.min(v), h.max(v))
            });
        0.5 * (hi - lo)
    }

    /// Amplitude √(a_h² + b_h²) of harmonic h of DOF `dof`.
    pub fn harmonic(&self, u: &[f64], dof: usize, h: usize) -> f64 {
        let m = self.tr.ncoef();
        if h == 0 {
            return u[dof * m].abs();
        }
        u[dof * m + 2 * h - 1].hypot(u[dof * m + 2 * h])
    }

    /// Coefficients of a solution at H harmonics from one at fewer or more (truncated
    /// or zero-padded per DOF): the start of a higher-H solve.
    pub fn embed(&self, u: &[f64], h_from: usize) -> Vec<f64> {
        let (mf, m) = (2 * h_from + 1, self.tr.ncoef());
        let mut out = vec![0.0; self.size()];
        for d in 0..self.sys.n() {
            for c in 0..mf.min(m) {
                out[d * m + c] = u[d * mf + c];
            }
        }
        out
    }
}
