//! The fast mode's state across frequencies and its steps at one frequency: the
//! reference factorization and receptance, the contact iterations (condensed or FGMRES,
//! with a cold retry), the independent check and the frequency's row. Scratch is
//! allocated once per sweep (G and O only when condensing).

use std::time::Instant;

use super::anderson::Anderson;
use super::bracket::Bracket;
use super::driver::Outcome;
use super::fast_coupled::{correlation, rho_consistent, Lin2};
use super::fast_unknowns::{Unknowns, CUBIC_TIMING, ZERO_AMP_REL};
use super::fast_update::{consistent, next_estimate, updated_product};
use super::krylov::Gmres;
use super::modal_route::{ModalRoute, ModeChoice};
use super::receptance::Receptance;
use super::{Options, Setup, SweepError, SweepResult, C64};
use crate::capi::Linearized;
use crate::fe::csc::Csc;
use crate::settings::IterationSpec;
use crate::solve::dense::DenseLu;
use crate::solve::umfpack::Numeric;

/// Anderson history depth.
const DEPTH: usize = 5;
/// FGMRES stops at ‖f − S u‖ ≤ GMRES_REL × rtol × ‖f‖ (1e-7 at the default rtol 1e-3:
/// far below the amplitude tolerance), or where that is below round-off, at the
/// residual's round-off floor ([`super::krylov::ROUNDOFF`]: as accurate as a direct solve
/// with the factorization); 1.1–1.3 solves per contact iteration on three-beams-coarse at
/// rtol 1e-3…1e-8. A fixed relative floor instead (1e-9) was out of reach near resonance,
/// where ‖S‖‖u‖/‖f‖ ≈ 4e7 there: those solves ran to GMRES_MAX and flagged their
/// frequencies not converged at rtol ≤ 1e-5 although the amplitudes had converged.
const GMRES_REL: f64 = 1e-4;
/// FGMRES restart length and most preconditioner applications per contact iteration.
const GMRES_RESTART: usize = 30;
const GMRES_MAX: usize = 300;

/// The iterate of a first try, kept while the cold start tries again.
struct Attempt {
    a: Vec<f64>,
    a_star: Vec<f64>,
    rho: Vec<f64>,
    r: Vec<C64>,
    delta: Vec<C64>,
    delta_off: Vec<C64>,
    lin: Vec<Linearized>,
    lin2: Vec<Lin2>,
    ks: Vec<f64>,
    u: Vec<C64>,
    gmres_ok: bool,
}

/// State and scratch of the fast sweep.
pub struct Workspace {
    /// Contact iterations on the condensed system (else FGMRES on the full one).
    pub(super) condensed: bool,
    pub(super) rec: Receptance,
    /// FGMRES: the full solution û (length).
    pub(super) u: Vec<C64>,
    /// Condensed: the full solution for the check, and its right side.
    pub(super) x_full: Vec<C64>,
    pub(super) x_rhs: Vec<C64>,
    pub(super) gmres: Gmres<C64>,
    /// I + GΔ (m × m) and its factorization's scratch.
    pub(super) work: Vec<C64>,
    lu: DenseLu,
    /// B û, Δ (per unknown) and, with coupled slip, Δ₁₂ per point.
    pub(super) r: Vec<C64>,
    pub(super) delta: Vec<C64>,
    pub(super) delta_off: Vec<C64>,
    pub(super) lin: Vec<Linearized>,
    pub(super) lin2: Vec<Lin2>,
    /// Springs' k* now and in the factorized reference.
    pub(super) ks: Vec<f64>,
    pub(super) ks0: Vec<f64>,
    /// Amplitudes: the estimate a and the computed a*.
    pub a: Vec<f64>,
    pub(super) a_star: Vec<f64>,
    /// Converged estimates of the two previous frequencies, for the predictor.
    pub hist: Vec<(f64, Vec<f64>)>,
    /// κ₀ of the factorized reference, per active point.
    pub(super) kappa0: Vec<[C64; 2]>,
    /// Coupled slip: the phase cosine ρ per point, estimate and computed.
    pub rho: Vec<f64>,
    pub(super) rho_star: Vec<f64>,
    /// Upper bound of ‖S₀‖₂ for FGMRES's round-off floor.
    pub(super) s0_norm: f64,
}

impl Workspace {
    pub fn new(un: &Unknowns, n: usize, nout: usize, condensed: bool, opts: &Options) -> Self {
        let (m, mc, na, nc) = (un.m, un.mc, un.active.len(), un.coupled_points());
        let zero = C64::new(0.0, 0.0);
        let mut rec = Receptance::new(n, if condensed { m } else { 0 }, nout);
        rec.r0 = vec![zero; m];
        let x_full = vec![zero; if condensed { n } else { 0 }];
        Workspace {
            condensed,
            rec,
            u: vec![zero; if condensed { 0 } else { n }],
            x_rhs: x_full.clone(),
            x_full,
            gmres: Gmres::new(if condensed { 0 } else { n }, GMRES_RESTART),
            work: vec![zero; if condensed { m * m } else { 0 }],
            lu: DenseLu::new(if condensed { m } else { 0 }),
            r: vec![zero; m],
            delta: vec![zero; m],
            delta_off: vec![zero; nc],
            lin: vec![Linearized::default(); mc],
            lin2: vec![Lin2::default(); nc],
            ks: vec![0.0; m - mc],
            ks0: vec![0.0; m - mc],
            a: vec![opts.iteration.initial_amplitude; m],
            a_star: vec![0.0; m],
            hist: Vec::new(),
            kappa0: vec![[zero; 2]; na],
            rho: vec![0.0; nc],
            rho_star: vec![0.0; nc],
            s0_norm: 0.0,
        }
    }

    /// The modal route: the reference is the stuck structure (κ₀ = κ at amplitude 0,
    /// the springs' linear k) for every frequency, its modes and residual once (or from
    /// `cache`, built by an earlier sweep of the same problem, with this sweep's load).
    pub fn modal_basis<'c>(
        &mut self,
        setup: &mut Setup,
        un: &Unknowns,
        (modes, residual): (ModeChoice, bool),
        f0: f64,
        cache: &'c mut Option<ModalRoute>,
        res: &mut SweepResult,
    ) -> Result<&'c mut ModalRoute, SweepError> {
        let t = Instant::now();
        let omega = 2.0 * std::f64::consts::PI * f0;
        let zeros = vec![0.0; un.m];
        let lins = (&mut self.lin[..], &mut self.lin2[..]);
        un.linearize((&zeros, &self.rho), omega, lins, &mut 0)?;
        un.linearize_springs(&zeros, &mut self.ks0)?;
        for j in 0..un.mc {
            self.kappa0[j / 2][j % 2] = un.kappa(&self.lin[j], omega);
        }
        res.time("linearization (C API)", t);
        let t = Instant::now();
        let p = un.p;
        let row = |j: usize| un.row(j);
        match cache {
            Some(route) if route.serves((modes, residual), setup, &self.kappa0, &self.ks0) => {
                route
                    .set_load(&p.excitation, &row, &p.outputs)
                    .map_err(|source| SweepError::ModalField { freq: f0, source })?;
            }
            _ => {
                *cache = Some(ModalRoute::new(
                    setup,
                    &self.kappa0,
                    &self.ks0,
                    (un.m, &row),
                    modes,
                    residual,
                )?)
            }
        }
        let route = cache.as_mut().expect("set above");
        res.modal = Some(route.summary.clone());
        res.time("modal basis (modes, residual)", t);
        Ok(route)
    }

    /// Every unknown's law at the estimate a.
    pub fn linearize(
        &mut self,
        un: &Unknowns,
        omega: f64,
        res: &mut SweepResult,
    ) -> Result<(), SweepError> {
        let t = Instant::now();
        let lins = (&mut self.lin[..], &mut self.lin2[..]);
        un.linearize((&self.a, &self.rho), omega, lins, &mut res.macroslip_caps)?;
        res.time("linearization (C API)", t);
        let t = Instant::now();
        un.linearize_springs(&self.a, &mut self.ks)?;
        res.time(CUBIC_TIMING, t);
        Ok(())
    }

    /// The reference state κ₀ is the estimate's: κ(a₀) and the springs' k*.
    pub fn take_reference(&mut self, un: &Unknowns, omega: f64) {
        for j in 0..un.mc {
            self.kappa0[j / 2][j % 2] = un.kappa(&self.lin[j], omega);
        }
        self.ks0.copy_from_slice(&self.ks);
    }

    /// κ₀ and the springs' stiffnesses of the reference.
    pub fn reference_state(&self) -> (&[[C64; 2]], &[f64]) {
        (&self.kappa0, &self.ks0)
    }

    /// The factorization of S₀ = S(ω, κ₀) (filled into `setup` since `since`), the load's
    /// solve and, condensed, the receptance G, O: `None` where S₀ is singular (by its
    /// pivots or by the bound of the load's solve: an undamped resonance).
    pub fn reference<'s>(
        &mut self,
        setup: &'s Setup,
        un: &Unknowns,
        f: f64,
        since: Instant,
        res: &mut SweepResult,
    ) -> Result<Option<Numeric<'s>>, SweepError> {
        let p = un.p;
        let umf = |source| SweepError::Umfpack { freq: f, source };
        let row = |j: usize| un.row(j);
        let num = setup.factor(f)?;
        res.factorizations += 1;
        res.time("factorization", since);
        let Some(num) = num else { return Ok(None) };
        let t = Instant::now();
        if self.condensed {
            self.rec
                .load(&num, &p.excitation, &row, &p.outputs)
                .map_err(umf)?;
        } else {
            self.s0_norm = setup.s.norm2_bound();
            num.solve_into(&p.excitation, &mut self.u).map_err(umf)?;
            for j in 0..un.m {
                self.rec.r0[j] = row(j).iter().map(|&(i, w)| self.u[i] * w).sum();
            }
        }
        let x0 = if self.condensed { &self.rec.x } else { &self.u };
        if setup.rcond_bound(&p.excitation, x0) < super::SINGULAR_RCOND {
            return Ok(None);
        }
        if self.condensed {
            self.rec.condense(&num, &row, &p.outputs).map_err(umf)?;
        }
        res.time("receptance solves", t);
        Ok(Some(num))
    }

    /// The modal route's receptance at ω: false where Z(ω) is singular.
    pub fn modal_reference(&mut self, route: &mut ModalRoute, omega: f64) -> bool {
        route.receptance(omega, &mut self.rec)
    }

    /// A singular frequency: the next one starts without extrapolation.
    pub fn singular(&mut self) -> Outcome {
        self.hist.clear();
        Outcome::Singular
    }

    /// The contact iterations at frequency f from the estimate (its laws already evaluated when
    /// `fresh`), then once more from the cold start if a warm start does not converge
    /// (it may lie on a branch that ended at a fold); the better try is kept. Returns
    /// (iterations, converged, FGMRES converged).
    pub fn iterate(
        &mut self,
        un: &Unknowns,
        (s0, num): (&Csc<C64>, Option<&Numeric>),
        f: f64,
        fresh: bool,
        it: IterationSpec,
        res: &mut SweepResult,
    ) -> Result<(usize, bool, bool), SweepError> {
        let m = un.m;
        let omega = 2.0 * std::f64::consts::PI * f;
        let mut lin_fresh = fresh;
        let mut acc = Anderson::new(DEPTH);
        let mut bracket = Bracket::new();
        let mut gmres_ok = true;
        let mut iterations = 0;
        let mut converged = m == 0;
        self.r.copy_from_slice(&self.rec.r0);
        self.delta.iter_mut().for_each(|d| *d = C64::new(0.0, 0.0));
        let mut cold = self.a.iter().all(|&v| v == it.initial_amplitude);
        let mut budget = it.max_passes;
        let mut first = None;
        loop {
            while m > 0 && iterations < budget {
                iterations += 1;
                if !lin_fresh {
                    self.linearize(un, omega, res)?;
                }
                lin_fresh = false;
                let t = Instant::now();
                self.update(un, omega);
                match num.filter(|_| !self.condensed) {
                    Some(num) => gmres_ok = self.krylov_step(un, (s0, num), f, it, res)?,
                    None => self.condensed_step(un, f)?,
                }
                for j in 0..m {
                    self.a_star[j] = self.r[j].norm();
                }
                for (q, v) in self.rho_star.iter_mut().enumerate() {
                    *v = correlation(self.r[2 * q], self.r[2 * q + 1]);
                }
                let floor = ZERO_AMP_REL
                    * self
                        .a
                        .iter()
                        .chain(&self.a_star)
                        .fold(f64::MIN_POSITIVE, |x, &y| x.max(y));
                converged = consistent(&self.a, &self.a_star, floor, it.tolerance)
                    && rho_consistent(&self.a_star, &self.rho, &self.rho_star, it.tolerance);
                res.time("condensed iterations", t);
                if converged {
                    break;
                }
                (self.a, self.rho) = next_estimate(
                    (&self.a, &self.a_star),
                    (&self.rho, &self.rho_star),
                    floor,
                    &mut acc,
                    &mut bracket,
                );
                if self.a.iter().any(|v| !v.is_finite()) {
                    break;
                }
            }
            if converged || cold {
                break;
            }
            // Kept if the cold start does not converge either.
            first = Some(self.attempt(gmres_ok));
            cold = true;
            budget += it.max_passes;
            self.a.iter_mut().for_each(|v| *v = it.initial_amplitude);
            self.rho.iter_mut().for_each(|v| *v = 0.0);
            acc = Anderson::new(DEPTH);
            bracket = Bracket::new();
            lin_fresh = false;
        }
        if let (false, Some(kept)) = (converged, first) {
            gmres_ok = self.restore(kept);
        }
        Ok((iterations, converged, gmres_ok))
    }

    /// Δ = (κ − κ₀)·area per unknown and, with coupled slip, Δ₁₂ per point.
    fn update(&mut self, un: &Unknowns, omega: f64) {
        let mc = un.mc;
        for j in 0..un.m {
            let (now, reference) = if j < mc {
                (un.kappa(&self.lin[j], omega), self.kappa0[j / 2][j % 2])
            } else {
                (
                    C64::new(self.ks[j - mc], 0.0),
                    C64::new(self.ks0[j - mc], 0.0),
                )
            };
            self.delta[j] = (now - reference) * un.weight(j);
        }
        for (q, l) in self.lin2.iter().enumerate() {
            self.delta_off[q] = un.kappa2(l, 0, 1, omega) * un.area[q];
        }
    }

    /// One FGMRES solve of (S₀ + BᵀΔB) û = f̂ from the previous û, and r = Bû; whether
    /// it converged.
    fn krylov_step(
        &mut self,
        un: &Unknowns,
        (s0, num): (&Csc<C64>, &Numeric),
        f: f64,
        it: IterationSpec,
        res: &mut SweepResult,
    ) -> Result<bool, SweepError> {
        let row = |j: usize| un.row(j);
        let n2 = &un.row_norm2;
        // ‖S₀ + BᵀΔB‖₂ ≤ ‖S₀‖₂ + Σⱼ |Δⱼ|‖Bⱼ‖₂².
        // Coupled: ‖B₁ᵀΔ₁₂B₂ + B₂ᵀΔ₁₂B₁‖₂ ≤ 2|Δ₁₂|‖B₁‖₂‖B₂‖₂.
        let anorm = self.s0_norm
            + self
                .delta
                .iter()
                .zip(n2)
                .map(|(d, b2)| d.norm() * b2)
                .sum::<f64>()
            + self
                .delta_off
                .iter()
                .enumerate()
                .map(|(q, d)| 2.0 * d.norm() * (n2[2 * q] * n2[2 * q + 1]).sqrt())
                .sum::<f64>();
        let (delta, delta_off) = (&self.delta, &self.delta_off);
        let stats = self.gmres.solve(
            &mut |xv: &[C64], y: &mut [C64]| updated_product(s0, delta, delta_off, &row, xv, y),
            &mut |xv: &[C64], y: &mut [C64]| num.solve_into(xv, y),
            &un.p.excitation,
            &mut self.u,
            GMRES_REL * it.tolerance,
            anorm,
            GMRES_MAX,
        );
        let stats = stats.map_err(|source| SweepError::Umfpack { freq: f, source })?;
        res.gmres_solves += stats.iterations;
        // The amplitudes tested next (and the outputs) come from this solve.
        for j in 0..un.m {
            self.r[j] = row(j).iter().map(|&(i, w)| self.u[i] * w).sum();
        }
        Ok(stats.converged)
    }

    /// r from (I + GΔ) r = r₀; with coupled slip Δ has the 2 × 2 block of each point.
    fn condensed_step(&mut self, un: &Unknowns, f: f64) -> Result<(), SweepError> {
        let (m, nc) = (un.m, un.coupled_points());
        for jc in 0..m {
            for k in 0..m {
                self.work[k + m * jc] = self.rec.g[k + m * jc] * self.delta[jc];
            }
            if jc < nc * 2 {
                let partner = jc ^ 1;
                for k in 0..m {
                    self.work[k + m * jc] += self.rec.g[k + m * partner] * self.delta_off[jc / 2];
                }
            }
            self.work[jc + m * jc] += C64::new(1.0, 0.0);
        }
        self.r.copy_from_slice(&self.rec.r0);
        if self.lu.solve_in_place(&mut self.work, m, &mut self.r) {
            Ok(())
        } else {
            Err(SweepError::Condensed { freq: f })
        }
    }

    fn attempt(&self, gmres_ok: bool) -> Attempt {
        Attempt {
            a: self.a.clone(),
            a_star: self.a_star.clone(),
            rho: self.rho.clone(),
            r: self.r.clone(),
            delta: self.delta.clone(),
            delta_off: self.delta_off.clone(),
            lin: self.lin.clone(),
            lin2: self.lin2.clone(),
            ks: self.ks.clone(),
            u: self.u.clone(),
            gmres_ok,
        }
    }

    /// Back to a kept try; its FGMRES flag.
    fn restore(&mut self, k: Attempt) -> bool {
        (self.a, self.a_star, self.rho) = (k.a, k.a_star, k.rho);
        (self.r, self.delta, self.delta_off) = (k.r, k.delta, k.delta_off);
        (self.lin, self.lin2, self.ks, self.u) = (k.lin, k.lin2, k.ks, k.u);
        k.gmres_ok
    }
}
