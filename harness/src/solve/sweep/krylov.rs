//! Flexible GMRES (Saad 1993) with the frequency's LU factorization as preconditioner,
//! for (S₀ + Bᵀ Δ B) u = f when the contact springs move away from the factorized
//! reference S₀. With M = S₀ the preconditioned operator is I + BᵀΔB S₀⁻¹, a low-rank
//! update of the identity: GMRES needs at most rank(Δ) + 1 iterations and, in practice,
//! a handful, each costing one solve with the factorization and one sparse product.

use nalgebra::ComplexField;

#[cfg(test)]
use super::C64;

/// Result of a GMRES solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmresStats {
    /// Preconditioner applications (solves with the factorization).
    pub iterations: usize,
    /// Final ‖f − A u‖ / ‖f‖.
    pub residual: f64,
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

    /// Solves A u = f from the initial guess in `u` to ‖f − A u‖ ≤ tol‖f‖, with
    /// `apply(x, y)`: y = A x, and `precond(x, y)`: y ≈ A⁻¹ x. At most `max_iter`
    /// preconditioner applications.
    pub fn solve<E>(
        &mut self,
        apply: &mut Apply<'_, T>,
        precond: &mut Precond<'_, T, E>,
        f: &[T],
        u: &mut [T],
        tol: f64,
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
            if beta <= tol * fnorm || iterations >= max_iter {
                return Ok(GmresStats {
                    iterations,
                    residual: beta / fnorm,
                    converged: beta <= tol * fnorm,
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
                if g[k].modulus() <= tol * fnorm || hn == 0.0 {
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
    use crate::rng::Rng;
    use nalgebra::{DMatrix, DVector};

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
        let lu0 = a0.clone().lu();
        let mut x = vec![C64::new(0.0, 0.0); n];
        let mut g = Gmres::new(n, 20);
        let stats = g
            .solve::<()>(
                &mut |x, y| y.copy_from_slice((&a * DVector::from_column_slice(x)).as_slice()),
                &mut |x, y| {
                    y.copy_from_slice(
                        lu0.solve(&DVector::from_column_slice(x))
                            .unwrap()
                            .as_slice(),
                    );
                    Ok(())
                },
                &f,
                &mut x,
                1e-12,
                50,
            )
            .unwrap();
        assert!(stats.converged && stats.iterations <= 4, "{stats:?}");
        let exact = a.lu().solve(&DVector::from_column_slice(&f)).unwrap();
        let err = x
            .iter()
            .zip(exact.iter())
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        assert!(err < 1e-10 * exact.norm(), "{err}");
    }
}
