//! In-place dense complex LU with partial pivoting for the condensed contact system
//! (m × m, m = 2 × contact points), on caller-owned scratch so that the contact
//! iterations allocate nothing. Right-looking and unblocked, its updates run down the
//! columns. (LAPACK's `zgetrf` from OpenBLAS was tried: its threaded version overflows a
//! 2 MB thread stack, as in the test harness's threads or a host code's.)

use nalgebra::Complex;

type C64 = Complex<f64>;

/// Solves A x = b in place: `a` (n×n, column-major, overwritten by its LU factors),
/// `b` (length n, overwritten by x). Returns false if a pivot is exactly zero or the
/// result is not finite.
pub fn lu_solve_in_place(a: &mut [C64], n: usize, b: &mut [C64]) -> bool {
    debug_assert_eq!(a.len(), n * n);
    debug_assert_eq!(b.len(), n);
    let at = |r: usize, c: usize| r + n * c;
    for k in 0..n {
        // Pivot: largest |a_ik|, i ≥ k.
        let mut p = k;
        let mut best = a[at(k, k)].norm();
        for i in k + 1..n {
            let v = a[at(i, k)].norm();
            if v > best {
                best = v;
                p = i;
            }
        }
        if best == 0.0 {
            return false;
        }
        if p != k {
            for c in 0..n {
                a.swap(at(k, c), at(p, c));
            }
            b.swap(k, p);
        }
        // Multipliers in column k, then the trailing columns one by one: each update is a
        // contiguous axpy down a column (column-major), the same products and
        // differences per entry as a row-by-row update.
        let inv = a[at(k, k)].inv();
        for i in k + 1..n {
            a[at(i, k)] *= inv;
        }
        let (head, tail) = a.split_at_mut(n * (k + 1));
        let l = &head[at(k + 1, k)..];
        for col in tail.chunks_exact_mut(n) {
            let u = col[k];
            if u != C64::new(0.0, 0.0) {
                for (x, li) in col[k + 1..].iter_mut().zip(l) {
                    *x -= li * u;
                }
            }
        }
        let bk = b[k];
        if bk != C64::new(0.0, 0.0) {
            for (x, li) in b[k + 1..].iter_mut().zip(l) {
                *x -= li * bk;
            }
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for c in k + 1..n {
            s -= a[at(k, c)] * b[c];
        }
        b[k] = s / a[at(k, k)];
    }
    b.iter().all(|v| v.re.is_finite() && v.im.is_finite())
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
            assert!(lu_solve_in_place(&mut aa, n, &mut x));
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
        assert!(!lu_solve_in_place(&mut singular, 2, &mut b));
    }
}
