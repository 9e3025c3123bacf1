//! Newton on the condensed balance R(r) = 0 (the parent module's equations): FGMRES
//! preconditioned with I + Ĝ Γ_d, step halving when ‖R‖ grows, and the load ramp for
//! responses Newton does not reach from the stuck one.

use std::time::Instant;

use nalgebra::DMatrix;

use super::{
    FeBalance, FeSolution, GMRES_MAX, GMRES_RESTART, GMRES_TOL, PINV_RCOND, RAMP_HALVINGS,
};
use crate::mhb::{MhbError, NewtonOptions};
use crate::solve::sweep::krylov::Gmres;
use crate::util::rusage::cpu_seconds;

impl FeBalance<'_, '_> {
    /// The preconditioner (I + Ĝ Γ_d)⁻¹, one dense block per harmonic (order m for h = 0,
    /// 2m else; unknowns ordered direction-major, (cos, sin) within a direction). A block
    /// that is singular to [`PINV_RCOND`] is pseudo-inverted: e.g. the mean position of a
    /// mass held only by friction, whose closed loops re-centre (∂F̂₀/∂r₀ = 0), is
    /// undetermined, and Newton then leaves it where it starts.
    fn preconditioner(&self, gamma: &[f64]) -> Vec<DMatrix<f64>> {
        let m = self.m();
        let group_of = self.group_of();
        // Σ over the directions l coupled with j of G[k, l] Γ[(l, a), (j, b)].
        let members = |j: usize| {
            let g = &self.groups[group_of[j]];
            g.first..g.first + g.len
        };
        let gm =
            |l: usize, a: usize, j: usize, b: usize| self.gamma_at(gamma, &group_of, l, a, j, b);
        self.rec
            .iter()
            .enumerate()
            .map(|(h, rec)| {
                let p = if h == 0 {
                    DMatrix::from_fn(m, m, |k, j| {
                        f64::from(u8::from(k == j))
                            + members(j)
                                .map(|l| rec.g[k + m * l].re * gm(l, 0, j, 0))
                                .sum::<f64>()
                    })
                } else {
                    let c = [2 * h - 1, 2 * h];
                    DMatrix::from_fn(2 * m, 2 * m, |row, col| {
                        let (k, a, j, b) = (row / 2, row % 2, col / 2, col % 2);
                        let gd: f64 = members(j)
                            .map(|l| {
                                let g = rec.g[k + m * l];
                                // Real 2×2 block of g on (cos, sin): [[gr, gi], [−gi, gr]].
                                let blk = [[g.re, g.im], [-g.im, g.re]];
                                blk[a][0] * gm(l, c[0], j, c[b]) + blk[a][1] * gm(l, c[1], j, c[b])
                            })
                            .sum();
                        f64::from(u8::from(row == col)) + gd
                    })
                };
                let lu = p.clone().lu();
                let piv = lu.u().diagonal().map(f64::abs);
                match lu.try_inverse() {
                    Some(inv) if piv.min() > PINV_RCOND * piv.max() => inv,
                    _ => {
                        let svd = p.svd(true, true);
                        let tol = PINV_RCOND * svd.singular_values.max();
                        svd.pseudo_inverse(tol)
                            .expect("tolerance ≥ 0, both factors computed")
                    }
                }
            })
            .collect()
    }

    /// Newton from `start` at the condensed ω, with step halving when ‖R‖ grows. Not
    /// converging within `opt.max_iter` is not an error: the last iterate comes back
    /// with `converged = false`; errors are the C API's and the FGMRES preconditioner's.
    pub fn solve(&mut self, start: &[f64], opt: NewtonOptions) -> Result<FeSolution, MhbError> {
        let (t0, cpu) = (Instant::now(), cpu_seconds());
        let out = self.newton(start, opt);
        self.stats.contact_seconds += t0.elapsed().as_secs_f64();
        self.stats.contact_cpu += cpu_seconds() - cpu;
        out
    }

    /// [`FeBalance::solve`] with the first-harmonic load raised from zero in `steps`
    /// steps, each from the last converged solution (a step that fails is halved, at
    /// most [`RAMP_HALVINGS`] times in a row): for loads whose solution Newton does not
    /// reach from the stuck response (sliding, separation). Not reaching the full load
    /// returns the full load's Newton from the last converged solution, not converged.
    pub fn solve_ramped(
        &mut self,
        steps: usize,
        opt: NewtonOptions,
    ) -> Result<FeSolution, MhbError> {
        let full = 1.0 / steps.max(1) as f64;
        let (mut at, mut step, mut halvings) = (0.0f64, full, 0);
        let mut r = vec![0.0; self.size()];
        let out = loop {
            self.load = (at + step).min(1.0);
            let sol = self.solve(&r, opt);
            match sol {
                Ok(s) if s.converged => {
                    if self.load >= 1.0 {
                        break Ok(s);
                    }
                    (at, r, halvings) = (self.load, s.r, 0);
                    step = (2.0 * step).min(full);
                }
                _ if halvings < RAMP_HALVINGS => {
                    halvings += 1;
                    step *= 0.5;
                }
                _ => {
                    self.load = 1.0;
                    break self.solve(&r, opt);
                }
            }
        };
        self.load = 1.0;
        out
    }

    fn newton(&mut self, start: &[f64], opt: NewtonOptions) -> Result<FeSolution, MhbError> {
        let (nc, size) = (self.tr.ncoef(), self.size());
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let scale = (self.load * norm(&self.linear_start())).max(f64::MIN_POSITIVE);
        let mut r = start.to_vec();
        let mut f = self.forces(&r, true)?;
        let mut big_r = self.residual(&r, &f.ghat);
        let mut res = norm(&big_r) / scale;
        let mut gmres = Gmres::<f64>::new(size, GMRES_RESTART);
        let mut it = 0;
        while res > opt.rtol && it < opt.max_iter {
            it += 1;
            if f.gamma.is_empty() {
                f = self.forces(&r, true)?;
            }
            let inverses = self.preconditioner(&f.gamma);
            let mut du = vec![0.0; size];
            let mut gv = vec![0.0; size];
            let gamma = &f.gamma;
            let this = &*self;
            let stats = gmres.solve::<MhbError>(
                &mut |x: &[f64], y: &mut [f64]| {
                    // y = x + Ĝ Γ x
                    this.apply_gamma(gamma, x, &mut gv);
                    this.apply_g(&gv, y);
                    for (yi, xi) in y.iter_mut().zip(x) {
                        *yi += xi;
                    }
                },
                &mut |x: &[f64], y: &mut [f64]| {
                    for (h, inv) in inverses.iter().enumerate() {
                        let cs: &[usize] = if h == 0 { &[0] } else { &[2 * h - 1, 2 * h] };
                        let at = |i: usize| (i / cs.len()) * nc + cs[i % cs.len()];
                        let b = nalgebra::DVector::from_fn(inv.ncols(), |i, _| x[at(i)]);
                        for (i, v) in (inv * b).iter().enumerate() {
                            y[at(i)] = *v;
                        }
                    }
                    Ok(())
                },
                &big_r,
                &mut du,
                GMRES_TOL,
                // No bound of ‖I + ĜΓ‖ at hand: the floor stays ROUNDOFF·ε·‖R‖, far
                // below GMRES_TOL, which alone decides.
                0.0,
                GMRES_MAX,
            )?;
            self.stats.gmres_iterations += stats.iterations;
            let mut lambda = 1.0;
            loop {
                let trial: Vec<f64> = r.iter().zip(&du).map(|(x, d)| x - lambda * d).collect();
                let ft = self.forces(&trial, false)?;
                let rt = self.residual(&trial, &ft.ghat);
                let nt = norm(&rt) / scale;
                if nt < res || lambda < 1e-2 {
                    r = trial;
                    f = ft;
                    big_r = rt;
                    res = nt;
                    break;
                }
                lambda *= 0.5;
            }
        }
        self.stats.newton_iterations += it;
        Ok(FeSolution {
            outputs: self.outputs(&f.ghat),
            r,
            dissipated: f.dissipated,
            describing: f.describing,
            iterations: it,
            residual: res,
            converged: res <= opt.rtol,
            ghat: f.ghat,
        })
    }
}
