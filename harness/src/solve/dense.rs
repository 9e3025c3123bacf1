//! Dense complex LU with partial pivoting for the condensed contact system (m × m,
//! m = 2 × contact points), by faer (blocked and recursive, SIMD, one thread: the
//! same row-pivoting algorithm as the textbook's, so results differ by round-off only),
//! on scratch owned by the sweep so that the contact iterations allocate nothing. An
//! unblocked right-looking LU took ~50 ms per factorization at m = 338 (the bolted lap's
//! joint), a third of its modal sweep. (LAPACK's `zgetrf` from OpenBLAS was tried
//! first: its threaded version overflows a 2 MB thread stack, as in the test harness's
//! threads or a host code's.)

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{MatMut, MatRef, Par};
use nalgebra::Complex;

type C64 = Complex<f64>;

/// Scratch for solving systems of up to `n` unknowns.
pub struct DenseLu {
    n: usize,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    buffer: MemBuffer,
}

impl DenseLu {
    /// Scratch for systems of up to `n` unknowns.
    pub fn new(n: usize) -> Self {
        let req = StackReq::any_of(&[
            factor::lu_in_place_scratch::<usize, C64>(n, n, Par::Seq, Default::default()),
            solve::solve_in_place_scratch::<usize, C64>(n, 1, Par::Seq),
        ]);
        DenseLu {
            n,
            perm: vec![0; n],
            perm_inv: vec![0; n],
            buffer: MemBuffer::new(req),
        }
    }

    /// Solves A x = b in place: `a` (n×n, column-major, overwritten by its LU factors),
    /// `b` (length n, overwritten by x), n at most the scratch's size. Returns false if a
    /// pivot is exactly zero or the result is not finite.
    pub fn solve_in_place(&mut self, a: &mut [C64], n: usize, b: &mut [C64]) -> bool {
        assert!(n <= self.n && a.len() == n * n && b.len() == n);
        if n == 0 {
            return true;
        }
        let (perm, perm_inv) = (&mut self.perm[..n], &mut self.perm_inv[..n]);
        let lu = MatMut::from_column_major_slice_mut(a, n, n);
        let stack = MemStack::new(&mut self.buffer);
        let (_, p) = factor::lu_in_place(lu, perm, perm_inv, Par::Seq, stack, Default::default());
        let lu = MatRef::from_column_major_slice(a, n, n);
        if (0..n).any(|i| lu[(i, i)] == C64::new(0.0, 0.0)) {
            return false;
        }
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        solve::solve_in_place(lu, lu, p, rhs, Par::Seq, MemStack::new(&mut self.buffer));
        b.iter().all(|v| v.re.is_finite() && v.im.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::rng::Rng;
    use nalgebra::{DMatrix, DVector};

    #[test]
    fn matches_nalgebra_lu_on_random_systems() {
        let mut rng = Rng::new(11);
        for n in [1, 2, 5, 40, 300] {
            let a: Vec<C64> = (0..n * n)
                .map(|_| C64::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)))
                .collect();
            let b: Vec<C64> = (0..n)
                .map(|_| C64::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)))
                .collect();
            let reference = DMatrix::from_column_slice(n, n, &a)
                .lu()
                .solve(&DVector::from_column_slice(&b))
                .unwrap();
            let mut aa = a.clone();
            let mut x = b.clone();
            assert!(DenseLu::new(n).solve_in_place(&mut aa, n, &mut x));
            let err: f64 = x
                .iter()
                .zip(reference.iter())
                .map(|(p, q)| (p - q).norm())
                .fold(0.0, f64::max);
            // Both are partial-pivoting LU: agreement to round-off × cond (≤ 1e3 here).
            assert!(err < 1e-11 * reference.norm(), "n={n}: {err}");
        }
        let mut singular = vec![C64::new(0.0, 0.0); 4];
        let mut b = vec![C64::new(1.0, 0.0); 2];
        assert!(!DenseLu::new(2).solve_in_place(&mut singular, 2, &mut b));
    }
}
