//! Dense LU with partial pivoting by faer (blocked, SIMD; the same row-pivoting
//! algorithm as nalgebra's, so results differ by round-off only). nalgebra's own LU is
//! unblocked: on the 1322-row Jacobian of an H = 7 FE backbone it took ~40 % of the
//! run. (LAPACK's `dgetrf` from OpenBLAS was tried first: its parallel path keeps
//! megabytes of scratch on the stack and overflows the 2 MB stack of a spawned thread,
//! as a test thread or a host's worker has.)

use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Mat, MatRef};
use nalgebra::{DMatrix, DVector};

/// The LU factors of a square matrix.
pub struct Lu(PartialPivLu<f64>);

impl Lu {
    /// Factors `a`; `None` if it is not square, is empty, has a non-finite entry or an
    /// exactly zero pivot (singular), as nalgebra's `lu().solve` would answer `None`.
    pub fn factor(a: &DMatrix<f64>) -> Option<Lu> {
        let n = a.nrows();
        if a.ncols() != n || n == 0 || !a.iter().all(|v| v.is_finite()) {
            return None;
        }
        let lu = MatRef::from_column_major_slice(a.as_slice(), n, n).partial_piv_lu();
        let u = lu.U();
        (0..n).all(|i| u[(i, i)] != 0.0).then_some(Lu(lu))
    }

    /// x with A x = b; `None` if x is not finite (A nearly singular).
    pub fn solve(&self, b: &DVector<f64>) -> Option<DVector<f64>> {
        let n = self.0.U().nrows();
        if b.len() != n {
            return None;
        }
        let mut x = Mat::from_fn(n, 1, |i, _| b[i]);
        self.0.solve_in_place(x.as_mut());
        let x = DVector::from_fn(n, |i, _| x[(i, 0)]);
        x.iter().all(|v| v.is_finite()).then_some(x)
    }

    /// The sign of det A (±1): the product of U's diagonal signs and the permutation's
    /// parity (−1 per even-length cycle).
    pub fn determinant_sign(&self) -> f64 {
        let u = self.0.U();
        let mut sign = 1.0;
        for i in 0..u.nrows() {
            if u[(i, i)] < 0.0 {
                sign = -sign;
            }
        }
        let (forward, _) = self.0.P().arrays();
        let mut seen = vec![false; forward.len()];
        for start in 0..forward.len() {
            let mut length = 0;
            let mut i = start;
            while !seen[i] {
                seen[i] = true;
                i = forward[i];
                length += 1;
            }
            if length > 0 && length % 2 == 0 {
                sign = -sign;
            }
        }
        sign
    }
}

/// x with A x = b (the factorization copies A): `None` when singular (see [`Lu::factor`]).
pub fn solve(a: &DMatrix<f64>, b: &DVector<f64>) -> Option<DVector<f64>> {
    Lu::factor(a)?.solve(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against nalgebra's LU on a seeded random system: solution and determinant sign.
    #[test]
    fn equals_nalgebra_on_random_systems() {
        let mut rng = crate::util::rng::Rng::new(7);
        for n in [1, 2, 5, 40, 130] {
            let a = DMatrix::from_fn(n, n, |_, _| rng.uniform(-0.5, 0.5));
            let b = DVector::from_fn(n, |_, _| rng.uniform(-0.5, 0.5));
            let lu = Lu::factor(&a).expect("random matrix is regular");
            let x = lu.solve(&b).unwrap();
            let reference = a.clone().lu().solve(&b).unwrap();
            let err = (&x - &reference).norm() / reference.norm();
            assert!(err < 1e-10, "n = {n}: relative difference {err:e}");
            let det = a.lu().determinant();
            assert_eq!(lu.determinant_sign(), det.signum(), "n = {n}");
        }
    }

    /// Singular and non-finite matrices are refused, not factored into NaN.
    #[test]
    fn refuses_singular_and_non_finite() {
        let singular = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert!(Lu::factor(&singular).is_none());
        let nan = DMatrix::from_row_slice(2, 2, &[1.0, f64::NAN, 0.0, 1.0]);
        assert!(Lu::factor(&nan).is_none());
        let empty = DMatrix::<f64>::zeros(0, 0);
        assert!(Lu::factor(&empty).is_none());
    }
}
