//! Flexible GMRES (Saad 1993) with the frequency's LU factorization as preconditioner,
//! for (S₀ + Bᵀ Δ B) u = f when the contact springs move away from the factorized
//! reference S₀. With M = S₀ the preconditioned operator is I + BᵀΔB S₀⁻¹, a low-rank
//! update of the identity: GMRES needs at most rank(Δ) + 1 iterations and, in practice,
//! a handful, each costing one solve with the factorization and one sparse product.

use nalgebra::ComplexField;

#[cfg(test)]
use super::C64;

/// Round-off floor of the stopping test, in units of ε = `f64::EPSILON`, as a normwise
/// backward error η = ‖f − A u‖ / (‖A‖‖u‖ + ‖f‖): a solve stops converged once η ≤
/// ROUNDOFF·ε, whatever its relative tolerance asks. Below that the computed residual is
/// round-off of the product A u and GMRES stagnates: on scenes/three-beams-coarse.toml
/// near the first resonance (‖A‖‖u‖/‖f‖ ≈ 4e7, ‖A‖ bounded by ‖S₀‖₁ + Σ|Δⱼ|‖bⱼ‖²) at
/// η = 0.1–0.3 ε, which is ‖f − A u‖/‖f‖ ≈ 1e-9, for 300 iterations. A direct solve with
/// the (unrefined) UMFPACK factorization leaves η ≤ 2 ε there: a solve at the floor is as
/// accurate as the factorization's own.
pub const ROUNDOFF: f64 = 8.0;

/// Result of a GMRES solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresStats {
    /// Preconditioner applications (solves with the factorization).
    pub iterations: usize,
    /// Final ‖f − A u‖ / ‖f‖.
    pub residual: f64,
    /// ‖f − A u‖ ≤ tol‖f‖, or at the round-off floor ([`ROUNDOFF`]).
    pub converged: bool,
}

/// y = A x.
pub type Apply<'a, T> = dyn FnMut(&[T], &mut [T]) + 'a;
/// y ≈ A⁻¹ x, fallible.
pub type Precond<'a, T, E> = dyn FnMut(&[T], &mut [T]) -> Result<(), E> + 'a;

fn dot<T: ComplexField<RealField = f64>>(a: &[T], b: &[T]) -> T {
    a.iter()
        .zip(b)
        .fold(T::zero(), |s, (x, y)| s + x.clone().conjugate() * y.clone())
}

fn norm<T: ComplexField<RealField = f64>>(a: &[T]) -> f64 {
    a.iter()
        .map(|x| x.clone().modulus_squared())
        .sum::<f64>()
        .sqrt()
}

/// Scratch of FGMRES(restart) for vectors of length n, reused across calls; real
/// (`f64`, the harmonic balance's Newton steps) or complex (`C64`, the fast sweep).
pub struct Gmres<T> {
    restart: usize,
    v: Vec<Vec<T>>,
    z: Vec<Vec<T>>,
    w: Vec<T>,
}

impl<T: ComplexField<RealField = f64> + Copy> Gmres<T> {
    pub fn new(n: usize, restart: usize) -> Self {
        Gmres {
            restart,
            v: vec![vec![T::zero(); n]; restart + 1],
            z: vec![vec![T::zero(); n]; restart],
            w: vec![T::zero(); n],
        }
    }

    /// Solves A u = f from the initial guess in `u` to ‖f − A u‖ ≤ tol‖f‖ or, when that
    /// is below round-off, to the floor ‖f − A u‖ ≤ [`ROUNDOFF`]·ε·(‖A‖‖u‖ + ‖f‖), with
    /// `apply(x, y)`: y = A x, `precond(x, y)`: y ≈ A⁻¹ x, and `anorm` an upper bound of
    /// ‖A‖₂ (an underestimate can put the floor out of reach). At most `max_iter`
    /// preconditioner applications.
    #[allow(clippy::too_many_arguments)]
    pub fn solve<E>(
        &mut self,
        apply: &mut Apply<'_, T>,
        precond: &mut Precond<'_, T, E>,
        f: &[T],
        u: &mut [T],
        tol: f64,
        anorm: f64,
        max_iter: usize,
    ) -> Result<GmresStats, E> {
        let fnorm = norm(f).max(f64::MIN_POSITIVE);
        let m = self.restart;
        let mut iterations = 0;
        loop {
            // r = f − A u into v[0].
            apply(u, &mut self.w);
            for (vi, (fi, wi)) in self.v[0].iter_mut().zip(f.iter().zip(&self.w)) {
                *vi = *fi - *wi;
            }
            let beta = norm(&self.v[0]);
            // Residual to reach: the tolerance, or the round-off floor at this u.
            let target = (tol * fnorm).max(ROUNDOFF * f64::EPSILON * (anorm * norm(u) + fnorm));
            if beta <= target || iterations >= max_iter {
                return Ok(GmresStats {
                    iterations,
                    residual: beta / fnorm,
                    converged: beta <= target,
                });
            }
            self.v[0].iter_mut().for_each(|x| *x = x.unscale(beta));
            let mut h = vec![vec![T::zero(); m]; m + 1];
            let mut cs = vec![T::zero(); m];
            let mut sn = vec![T::zero(); m];
            let mut g = vec![T::zero(); m + 1];
            g[0] = T::from_real(beta);
            let mut k = 0;
            while k < m && iterations < max_iter {
                precond(&self.v[k], &mut self.z[k])?;
                iterations += 1;
                apply(&self.z[k], &mut self.w);
                for i in 0..=k {
                    let hik = dot(&self.v[i], &self.w);
                    h[i][k] = hik;
                    for (wj, vj) in self.w.iter_mut().zip(&self.v[i]) {
                        *wj -= hik * *vj;
                    }
                }
                let hn = norm(&self.w);
                h[k + 1][k] = T::from_real(hn);
                if hn > 0.0 {
                    for (vj, wj) in self.v[k + 1].iter_mut().zip(&self.w) {
                        *vj = wj.unscale(hn);
                    }
                }
                // Apply earlier Givens rotations, then a new one to zero h[k+1][k].
                for i in 0..k {
                    let t = cs[i].conjugate() * h[i][k] + sn[i].conjugate() * h[i + 1][k];
                    h[i + 1][k] = -sn[i] * h[i][k] + cs[i] * h[i + 1][k];
                    h[i][k] = t;
                }
                let (a, b) = (h[k][k], h[k + 1][k]);
                let r = (a.modulus_squared() + b.modulus_squared()).sqrt();
                if r == 0.0 {
                    cs[k] = T::one();
                    sn[k] = T::zero();
                } else {
                    cs[k] = a.unscale(r);
                    sn[k] = b.unscale(r);
                }
                h[k][k] = T::from_real(r);
                h[k + 1][k] = T::zero();
                g[k + 1] = -sn[k] * g[k];
                g[k] = cs[k].conjugate() * g[k];
                k += 1;
                if g[k].modulus() <= target || hn == 0.0 {
                    break;
                }
            }
            // y = H⁻¹ g (upper triangular k × k); u += Z y.
            let mut y = vec![T::zero(); k];
            for i in (0..k).rev() {
                let mut s = g[i];
                for j in i + 1..k {
                    s -= h[i][j] * y[j];
                }
                y[i] = s / h[i][i];
            }
            for (j, yj) in y.iter().enumerate() {
                for (ui, zi) in u.iter_mut().zip(&self.z[j]) {
                    *ui += *yj * *zi;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::rng::Rng;
    use nalgebra::{DMatrix, DVector};

    /// FGMRES(20) on the dense A from u = 0, preconditioned by the dense LU of
    /// `precond` (identity when `None`), with ‖A‖ = ‖A‖_F as the norm bound.
    fn solve_dense(
        a: &DMatrix<C64>,
        precond: Option<&DMatrix<C64>>,
        f: &[C64],
        tol: f64,
        max_iter: usize,
    ) -> (Vec<C64>, GmresStats) {
        let lu = precond.map(|p| p.clone().lu());
        let mut x = vec![C64::new(0.0, 0.0); f.len()];
        let stats = Gmres::new(f.len(), 20)
            .solve::<()>(
                &mut |x, y| y.copy_from_slice((a * DVector::from_column_slice(x)).as_slice()),
                &mut |x, y| {
                    match &lu {
                        Some(lu) => y.copy_from_slice(
                            lu.solve(&DVector::from_column_slice(x)).unwrap().as_slice(),
                        ),
                        None => y.copy_from_slice(x),
                    }
                    Ok(())
                },
                f,
                &mut x,
                tol,
                a.norm(),
                max_iter,
            )
            .unwrap();
        (x, stats)
    }

    #[test]
    fn low_rank_update_converges_in_rank_plus_one_with_exact_preconditioner() {
        // A = A₀ + U Vᵀ (rank 3), preconditioned by A₀⁻¹: at most 4 iterations, solution
        // equal to a dense LU's to 1e-10.
        let mut rng = Rng::new(7);
        let n = 30;
        let c = |rng: &mut Rng| C64::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        let a0 = DMatrix::from_fn(n, n, |i, j| {
            if i == j {
                C64::new(4.0, 1.0)
            } else {
                c(&mut rng) * 0.1
            }
        });
        let u = DMatrix::from_fn(n, 3, |_, _| c(&mut rng));
        let v = DMatrix::from_fn(n, 3, |_, _| c(&mut rng));
        let a = &a0 + &u * v.transpose();
        let f: Vec<C64> = (0..n).map(|_| c(&mut rng)).collect();
        let (x, stats) = solve_dense(&a, Some(&a0), &f, 1e-12, 50);
        assert!(stats.converged && stats.iterations <= 4, "{stats:?}");
        let exact = a.lu().solve(&DVector::from_column_slice(&f)).unwrap();
        let err = x
            .iter()
            .zip(exact.iter())
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        assert!(err < 1e-10 * exact.norm(), "{err}");
    }

    /// A = Q₁ diag(σ) Q₂ᴴ + U Vᵀ (rank 3) with σ from 1e8 down to 1e2 (cond ≈ 1e6, as a
    /// lightly damped resonance) and ‖A‖_F‖u‖/‖f‖ ≈ 3e5, so ‖f − A u‖/‖f‖ cannot get far
    /// below 1e-11; the preconditioner is A₀⁻¹ (dense LU of the first term).
    fn ill_conditioned(rng: &mut Rng) -> (DMatrix<C64>, DMatrix<C64>, Vec<C64>) {
        let n = 30;
        let c = |rng: &mut Rng| C64::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
        let q1 = DMatrix::from_fn(n, n, |_, _| c(rng)).qr().q();
        let q2 = DMatrix::from_fn(n, n, |_, _| c(rng)).qr().q();
        let sigma = DMatrix::from_fn(n, n, |i, j| {
            let t = i as f64 / (n - 1) as f64;
            C64::new(if i == j { 1e8 * 1e-6f64.powf(t) } else { 0.0 }, 0.0)
        });
        let a0 = &q1 * sigma * q2.adjoint();
        let u = DMatrix::from_fn(n, 3, |_, _| c(rng) * 10.0);
        let v = DMatrix::from_fn(n, 3, |_, _| c(rng));
        let a = &a0 + &u * v.transpose();
        let f = (0..n).map(|_| c(rng)).collect();
        (a0, a, f)
    }

    #[test]
    fn a_tolerance_below_round_off_stops_converged_at_the_floor() {
        // Asked for 1e-15 relative, which the residual of no solve reaches here: converged
        // at η ≤ ROUNDOFF·ε after a handful of iterations (measured 5, η = 3e-17; when the
        // test compared with tol alone it ran to max_iter and said not converged), with
        // the forward error of a backward-stable solve: ≤ cond·ROUNDOFF·ε (1.9e-9; measured
        // 7.7e-12) against a dense LU of A, whose own error is ~cond·ε.
        let (a0, a, f) = ill_conditioned(&mut Rng::new(11));
        let anorm = a.norm();
        let (x, stats) = solve_dense(&a, Some(&a0), &f, 1e-15, 200);
        let x = DVector::from_column_slice(&x);
        let fv = DVector::from_column_slice(&f);
        let eta = (&fv - &a * &x).norm() / (anorm * x.norm() + fv.norm());
        let sv = a.clone().singular_values();
        let cond = sv.max() / sv.min();
        let exact = a.lu().solve(&fv).unwrap();
        let err = (&x - &exact).norm() / exact.norm();
        eprintln!("{stats:?}, eta {eta:.2e}, cond {cond:.2e}, forward error {err:.2e}");
        assert!(
            stats.residual > 1e-15,
            "the floor is not exercised: {stats:?}"
        );
        assert!(stats.converged && stats.iterations <= 10, "{stats:?}");
        assert!(eta <= ROUNDOFF * f64::EPSILON, "{eta}");
        assert!(err <= cond * ROUNDOFF * f64::EPSILON, "{err} (cond {cond})");
    }

    #[test]
    fn running_out_of_iterations_above_the_floor_is_not_converged() {
        // The same system without a preconditioner: 5 iterations leave the residual far
        // above both the tolerance and the floor, and the solve says so.
        let (_, a, f) = ill_conditioned(&mut Rng::new(11));
        let (_, stats) = solve_dense(&a, None, &f, 1e-15, 5);
        assert!(!stats.converged && stats.residual > 1e-3, "{stats:?}");
    }
}
