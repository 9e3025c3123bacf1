//! Harmonic balance of lumped systems with three-direction contact points
//! (docs/contact3d.md): a unilateral normal law, so the normal force N(t) varies within
//! the cycle and the point may separate, and two tangential directions under one
//! circular slip limit ‖t‖ ≤ μN(t). The AFT ([`super::aft`]'s transforms) marches the
//! library's point (`jointlin_point3d_step`) over the periodic samples of the two
//! tangential displacements and the overclosure together until the loop closes; the
//! Jacobian of the element's force coefficients is a forward difference of that whole
//! map (the coupled, path-dependent law has no exact incremental rule here).
//!
//! Kinematics of element e: weighted sums of DOFs give the point's tangential relative
//! displacements u₁, u₂ and its opening g along the normal; the overclosure is h = g₀ − g
//! (g₀ the overclosure at x = 0). A point on a body's DOFs (t₁, t₂, n) against a rigid
//! plane ([`Element3::on_plane`]): u₁ = x_{t₁}, u₂ = x_{t₂}, g = x_n (n points from the
//! plane into the body). Internal forces: Σ_a F_a ∂u_a/∂x with u₃ = h: +F₁, +F₂ along
//! the tangential rows (the point returns them with the sign of the displacement) and
//! −N along the normal row.

use nalgebra::{DMatrix, DVector};

use super::aft::{AftError, Transforms};
use super::{linear_coefficients, Hb, MhbError, NewtonOptions};
use crate::linalg;
use crate::model::lumped_system::SIGN;

mod march;

pub use crate::model::lumped_system::{Element3, Row, System3};
pub use march::{march3, march3_from, march_point, step, Marched, Period3, States, VIRGIN};

/// Residual, Jacobian and per element energies and normal force ranges at one state.
pub struct Evaluated3 {
    pub r: DVector<f64>,
    pub j: DMatrix<f64>,
    /// ∂R/∂ω (the points are rate independent: the linear part's).
    pub r_omega: DVector<f64>,
    /// Energy dissipated per period by each 1D element of the linear system (force·length).
    pub element_dissipated: Vec<f64>,
    /// Energy dissipated per period by each point (force·length).
    pub dissipated: Vec<f64>,
    /// Smallest and largest normal force over the period per point (force).
    pub normal_range: Vec<(f64, f64)>,
    /// Each point's closed states.
    pub states: Vec<States>,
}

/// The harmonic balance of a [`System3`] at H harmonics and N samples.
pub struct Hb3<'a> {
    sys: &'a System3,
    linear: Hb<'a>,
    tr: Transforms,
    /// Where each point's march starts: the closed states of the last accepted iterate
    /// (virgin at first). A stuck point keeps its sliders where they are, so the
    /// balance's map depends on this memory; the Jacobian's columns start from the same
    /// states as the residual (consistent), and the memory moves with the accepted
    /// iterates as the history of a stepped sweep would.
    memory: Vec<States>,
}

/// A converged periodic solution: coefficients DOF-major (layout of [`super::aft`]), the
/// energy dissipated per period by each 1D element and each point (force·length) and
/// each point's normal force range (force).
#[derive(Debug, Clone)]
pub struct Solution3 {
    pub omega: f64,
    pub u: Vec<f64>,
    pub element_dissipated: Vec<f64>,
    pub dissipated: Vec<f64>,
    pub normal_range: Vec<(f64, f64)>,
    pub iterations: usize,
    pub residual: f64,
    /// Each point's closed states: where a nearby solve's marches may start.
    pub memory: Vec<States>,
}

impl<'a> Hb3<'a> {
    pub fn new(sys: &'a System3, h: usize, n: usize) -> Self {
        Hb3 {
            sys,
            linear: Hb::new(&sys.linear, h, n),
            tr: Transforms::new(n, h),
            memory: vec![VIRGIN; sys.elements.len()],
        }
    }

    fn m(&self) -> usize {
        self.tr.ncoef()
    }

    /// Harmonics H.
    pub fn h(&self) -> usize {
        self.tr.h
    }

    /// Coefficients per DOF, 2H + 1.
    pub fn ncoef(&self) -> usize {
        self.m()
    }

    /// The system balanced.
    pub fn system(&self) -> &'a System3 {
        self.sys
    }

    /// How the 1D elements' Jacobians are formed (the points' are differences always).
    pub fn set_jacobian(&mut self, j: super::aft::Jacobian) {
        self.linear.jacobian = j;
    }

    /// Each point's smallest and largest normal force over the period at `u` (force),
    /// marched from the memory: the ranges of [`Hb3::eval`] without its Jacobian.
    pub fn normal_ranges(&mut self, u: &[f64]) -> Result<Vec<(f64, f64)>, MhbError> {
        let mut out = Vec::with_capacity(self.sys.elements.len());
        for (k, e) in self.sys.elements.iter().enumerate() {
            let c = self.element_coefficients(e, u);
            let memory = self.memory[k];
            let (_, period) = self.element_forces(e, &c, &memory)?;
            out.push(range(&period.force[2]));
        }
        Ok(out)
    }

    /// The element's relative coefficients (u₁, u₂, h) from the system's u.
    fn element_coefficients(&self, e: &Element3, u: &[f64]) -> Vec<f64> {
        let m = self.m();
        let mut c = vec![0.0; 3 * m];
        for (a, row) in e.rows.iter().enumerate() {
            for &(d, w) in row {
                for q in 0..m {
                    c[a * m + q] += SIGN[a] * w * u[d * m + q];
                }
            }
        }
        c[2 * m] += e.gap;
        c
    }

    /// Force coefficients (F₁, F₂, N; 3(2H+1)) and the closed period at relative
    /// coefficients `c`, marched from `start`.
    fn element_forces(
        &mut self,
        e: &Element3,
        c: &[f64],
        start: &States,
    ) -> Result<(Vec<f64>, Marched), AftError> {
        let (n, m) = (self.tr.n, self.m());
        let mut samples = vec![[0.0; 3]; n];
        let mut x = vec![0.0; n];
        for a in 0..3 {
            self.tr.synthesize(&c[a * m..(a + 1) * m], &mut x);
            for k in 0..n {
                samples[k][a] = x[k];
            }
        }
        let period = march_point(&e.contact, e.coupled, &samples, start)?;
        let mut f = vec![0.0; 3 * m];
        for a in 0..3 {
            self.tr
                .analyse(&period.force[a], &mut f[a * m..(a + 1) * m]);
        }
        Ok((f, period))
    }

    /// Residual and Jacobian at (u, ω), with each element's and point's dissipated energy
    /// per period and each point's normal force range.
    pub fn eval(&mut self, u: &[f64], omega: f64) -> Result<Evaluated3, MhbError> {
        let ev = self.linear.eval(u, omega)?;
        let (mut r, mut j) = (ev.r, ev.j);
        let m = self.m();
        let mut dissipated = Vec::with_capacity(self.sys.elements.len());
        let mut normal_range = Vec::with_capacity(self.sys.elements.len());
        let mut states = Vec::with_capacity(self.sys.elements.len());
        for (k, e) in self.sys.elements.iter().enumerate() {
            let c = self.element_coefficients(e, u);
            let memory = self.memory[k];
            let (f, period) = self.element_forces(e, &c, &memory)?;
            dissipated.push(period.dissipated);
            states.push(period.states);
            normal_range.push(range(&period.force[2]));
            for (a, row) in e.rows.iter().enumerate() {
                for &(d, w) in row {
                    for q in 0..m {
                        r[d * m + q] += SIGN[a] * w * f[a * m + q];
                    }
                }
            }
            // Forward differences of the element map (marched from the same memory):
            // step 1e-7 of the larger of max|c| and the stick displacement μN/k_T0 at the
            // mean normal force; only the components with a row move.
            let n0 = (e.contact.k_n * c[2 * m]).max(0.0);
            let scale = c
                .iter()
                .fold(e.contact.mu * n0 / e.contact.k_t0, |s, v| s.max(v.abs()));
            let eps = 1e-7 * scale.max(f64::MIN_POSITIVE);
            let mut cp = c.clone();
            for b in (0..3).filter(|&b| !e.rows[b].is_empty()) {
                for qb in 0..m {
                    let col = b * m + qb;
                    cp[col] = c[col] + eps;
                    let (fp, _) = self.element_forces(e, &cp, &memory)?;
                    cp[col] = c[col];
                    for (a, row_a) in e.rows.iter().enumerate() {
                        for qa in 0..m {
                            let d = SIGN[a] * SIGN[b] * (fp[a * m + qa] - f[a * m + qa]) / eps;
                            for &(da, wa) in row_a {
                                for &(db, wb) in &e.rows[b] {
                                    j[(da * m + qa, db * m + qb)] += wa * wb * d;
                                }
                            }
                        }
                    }
                }
            }
        }
        Ok(Evaluated3 {
            r,
            j,
            r_omega: ev.r_omega,
            element_dissipated: ev.dissipated,
            dissipated,
            normal_range,
            states,
        })
    }

    /// Newton from `u0` at fixed ω with step halving (as [`Hb::solve`]).
    pub fn solve(
        &mut self,
        u0: &[f64],
        omega: f64,
        opt: NewtonOptions,
    ) -> Result<Solution3, MhbError> {
        let scale = self.linear.load().norm().max(f64::MIN_POSITIVE);
        let mut u = DVector::from_column_slice(u0);
        let mut ev = self.eval(u.as_slice(), omega)?;
        let mut res = ev.r.norm() / scale;
        for it in 0..=opt.max_iter {
            if res <= opt.rtol {
                return Ok(Solution3 {
                    omega,
                    u: u.as_slice().to_vec(),
                    element_dissipated: ev.element_dissipated,
                    dissipated: ev.dissipated,
                    normal_range: ev.normal_range,
                    iterations: it,
                    residual: res,
                    memory: ev.states,
                });
            }
            if it == opt.max_iter {
                break;
            }
            let du = linalg::solve(&ev.j, &ev.r).ok_or(MhbError::Singular { omega })?;
            let mut lambda = 1.0;
            loop {
                let trial = &u - lambda * &du;
                let e2 = self.eval(trial.as_slice(), omega)?;
                let res2 = e2.r.norm() / scale;
                if res2 < res || lambda < 1e-2 {
                    (u, ev, res) = (trial, e2, res2);
                    self.memory.clone_from(&ev.states);
                    break;
                }
                lambda *= 0.5;
            }
        }
        Err(MhbError::Newton {
            omega,
            residual: res,
            iterations: opt.max_iter,
        })
    }

    /// The linear response with every 1D element stuck ([`crate::model::lumped_system::System::stuck_stiffness`]) and
    /// every point stuck and closed (k_T0 along its tangential rows, k_N along its normal
    /// row, that spring preloaded by k_N·g₀): the start of a solve.
    pub fn stuck_start(&self, omega: f64) -> Vec<f64> {
        let s = &self.sys.linear;
        let (k, f0) = self.sys.stuck();
        linear_coefficients(s, &k, &f0, omega, self.m())
    }

    /// First-harmonic amplitude of DOF `dof` in `u`.
    pub fn amplitude(&self, u: &[f64], dof: usize) -> f64 {
        self.linear.amplitude(u, dof)
    }

    /// First-harmonic amplitude of the point's component `a` (u₁, u₂, g) in `u`.
    pub fn component_amplitude(&self, u: &[f64], e: &Element3, a: usize) -> f64 {
        let m = self.m();
        let coef = |q: usize| {
            e.rows[a]
                .iter()
                .map(|&(d, w)| w * u[d * m + q])
                .sum::<f64>()
        };
        coef(1).hypot(coef(2))
    }
}

/// Smallest and largest sample.
fn range(v: &[f64]) -> (f64, f64) {
    (
        v.iter().copied().fold(f64::INFINITY, f64::min),
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

/// Load-step halvings before [`solve_ramped`] gives up.
const MAX_RAMP_HALVINGS: usize = 12;

/// Solves `sys` at ω with its harmonic load ramped from 0: `steps` equal steps, each
/// solve starting from the last converged one (the first from the stuck start), a step
/// whose Newton fails halved (at most [`MAX_RAMP_HALVINGS`] times in a row): the way
/// through separation or sliding, where Newton from the stuck start at the full load may
/// not converge.
pub fn solve_ramped(
    sys: &System3,
    h: usize,
    n: usize,
    omega: f64,
    steps: usize,
    opt: NewtonOptions,
) -> Result<Solution3, MhbError> {
    let full = 1.0 / steps.max(1) as f64;
    let (mut at, mut step, mut halvings) = (0.0f64, full, 0);
    let mut last: Option<Solution3> = None;
    loop {
        let w = (at + step).min(1.0);
        let mut part = sys.clone();
        part.linear.f1.iter_mut().for_each(|f| *f *= w);
        let mut hb = Hb3::new(&part, h, n);
        let start = match &last {
            Some(s) => {
                hb.memory.clone_from(&s.memory);
                s.u.clone()
            }
            None => hb.stuck_start(omega),
        };
        match hb.solve(&start, omega, opt) {
            Ok(sol) => {
                if w >= 1.0 {
                    return Ok(sol);
                }
                (at, halvings) = (w, 0);
                step = (2.0 * step).min(full);
                last = Some(sol);
            }
            Err(e) if halvings >= MAX_RAMP_HALVINGS => return Err(e),
            Err(_) => {
                halvings += 1;
                step *= 0.5;
            }
        }
    }
}
