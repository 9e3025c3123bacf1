//! Sparse Cholesky of a real symmetric positive definite matrix by CHOLMOD's supernodal
//! factorization (SuiteSparse, BLAS-3 on the supernodes: the factorization CalculiX's
//! and Abaqus's eigensolvers rely on, several times faster than an LU of the same
//! matrix). `shim.c` (compiled by build.rs) owns CHOLMOD's workspace, so nothing here
//! depends on CHOLMOD's struct layouts.
//!
//! A matrix that is not positive definite is [`CholmodError::NotPositiveDefinite`]: the
//! caller falls back to an LU (UMFPACK) where indefinite matrices are legitimate.

use std::ffi::{c_int, c_void};
use std::ptr::{self, NonNull};

use thiserror::Error;

use crate::fe::csc::Csc;

extern "C" {
    fn jl_cholmod_factor(
        n: i64,
        col_ptr: *const i64,
        row_idx: *const i64,
        values: *const f64,
        out: *mut *mut c_void,
        minor: *mut i64,
        status: *mut c_int,
    ) -> c_int;
    fn jl_cholmod_solve(h: *mut c_void, ncol: i64, b: *const f64, x: *mut f64) -> c_int;
    fn jl_cholmod_free(h: *mut c_void);
}

/// Errors of [`Cholesky`].
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CholmodError {
    #[error("matrix not positive definite (CHOLMOD stopped at column {column})")]
    NotPositiveDefinite { column: i64 },
    #[error("CHOLMOD {call} failed with status {status}")]
    Failed { call: &'static str, status: i32 },
    #[error("vector length {got} does not fit n = {n}")]
    Length { got: usize, n: usize },
    #[error("solution is not finite")]
    NonFinite,
}

/// The factor L Lᵀ = A of one matrix.
pub struct Cholesky {
    handle: NonNull<c_void>,
    n: usize,
}

// SAFETY: the handle owns its factor and workspace and is used through &mut self only
// (solves use the workspace), so it may move between threads but not be shared.
unsafe impl Send for Cholesky {}

impl Cholesky {
    /// Factors `a` (symmetric, both triangles stored; the upper one is read).
    pub fn factor(a: &Csc<f64>) -> Result<Self, CholmodError> {
        let p = &a.pattern;
        let mut raw: *mut c_void = ptr::null_mut();
        let (mut minor, mut status) = (0i64, 0 as c_int);
        // SAFETY: col_ptr has n+1, row_idx and values col_ptr[n] entries (Csc
        // invariants); the shim copies nothing it keeps beyond the call but the factor.
        let code = unsafe {
            jl_cholmod_factor(
                p.n as i64,
                p.col_ptr.as_ptr(),
                p.row_idx.as_ptr(),
                a.values.as_ptr(),
                &mut raw,
                &mut minor,
                &mut status,
            )
        };
        match (code, NonNull::new(raw)) {
            (0, Some(handle)) => Ok(Cholesky { handle, n: p.n }),
            (1, _) => Err(CholmodError::NotPositiveDefinite { column: minor }),
            _ => Err(CholmodError::Failed {
                call: "cholmod_l_factorize",
                status,
            }),
        }
    }

    /// x = A⁻¹ b.
    pub fn solve_into(&mut self, b: &[f64], x: &mut [f64]) -> Result<(), CholmodError> {
        self.solve_many(1, b, x)
    }

    /// X = A⁻¹ B for `ncol` right sides at once (B, X n × ncol, column-major): one pass
    /// over the factor for all of them (blocked triangular solves).
    pub fn solve_many(
        &mut self,
        ncol: usize,
        b: &[f64],
        x: &mut [f64],
    ) -> Result<(), CholmodError> {
        for len in [b.len(), x.len()] {
            if len != self.n * ncol {
                return Err(CholmodError::Length {
                    got: len,
                    n: self.n * ncol,
                });
            }
        }
        if ncol == 0 {
            return Ok(());
        }
        // SAFETY: b and x hold n × ncol doubles; the handle is valid while self lives.
        let status = unsafe {
            jl_cholmod_solve(
                self.handle.as_ptr(),
                ncol as i64,
                b.as_ptr(),
                x.as_mut_ptr(),
            )
        };
        if status != 0 {
            return Err(CholmodError::Failed {
                call: "cholmod_l_solve",
                status,
            });
        }
        if x.iter().any(|v| !v.is_finite()) {
            return Err(CholmodError::NonFinite);
        }
        Ok(())
    }
}

impl Drop for Cholesky {
    fn drop(&mut self) {
        // SAFETY: created by jl_cholmod_factor, freed exactly once here.
        unsafe { jl_cholmod_free(self.handle.as_ptr()) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::csc::CscPattern;
    use crate::util::rng::Rng;
    use nalgebra::{DMatrix, DVector};
    use std::sync::Arc;

    fn dense_to_csc(a: &DMatrix<f64>) -> Csc<f64> {
        let n = a.nrows();
        let p = Arc::new(CscPattern::from_entries(
            n,
            (0..n).flat_map(|j| {
                (0..n)
                    .filter(move |&i| i.abs_diff(j) <= 3)
                    .map(move |i| (i, j))
            }),
        ));
        let mut c = Csc::zeros(p.clone());
        for j in 0..n {
            for i in 0..n {
                if let Some(s) = p.find(i, j) {
                    c.values[s] = a[(i, j)];
                }
            }
        }
        c
    }

    #[test]
    fn solves_a_banded_spd_system_as_dense_cholesky_and_refuses_an_indefinite_one() {
        let n = 60;
        let mut rng = Rng::new(7);
        let mut a = DMatrix::zeros(n, n);
        for j in 0..n {
            for i in j..n.min(j + 4) {
                let v = if i == j { 10.0 } else { rng.uniform(-1.0, 1.0) };
                a[(i, j)] = v;
                a[(j, i)] = v;
            }
        }
        let csc = dense_to_csc(&a);
        let b: Vec<f64> = (0..n).map(|i| (0.1 * i as f64).cos()).collect();
        let mut x = vec![0.0; n];
        Cholesky::factor(&csc)
            .unwrap()
            .solve_into(&b, &mut x)
            .unwrap();
        let reference = a
            .clone()
            .cholesky()
            .unwrap()
            .solve(&DVector::from_vec(b.clone()));
        for (u, v) in x.iter().zip(reference.iter()) {
            assert!((u - v).abs() < 1e-13 * reference.amax(), "{u} vs {v}");
        }
        // Three right sides at once give each one's solve (the same factor, blocked).
        let mut f = Cholesky::factor(&csc).unwrap();
        let many: Vec<f64> = (0..3 * n)
            .map(|i| ((i % n) as f64 * (1.0 + (i / n) as f64)).sin())
            .collect();
        let mut xs = vec![0.0; 3 * n];
        f.solve_many(3, &many, &mut xs).unwrap();
        for (col, (bc, xc)) in many.chunks(n).zip(xs.chunks(n)).enumerate() {
            let mut one = vec![0.0; n];
            f.solve_into(bc, &mut one).unwrap();
            for (u, v) in xc.iter().zip(&one) {
                assert!(
                    (u - v).abs() <= 1e-14 * v.abs().max(1.0),
                    "column {col}: {u} vs {v}"
                );
            }
        }
        // Lengths are checked.
        assert_eq!(
            f.solve_into(&b[..3], &mut x),
            Err(CholmodError::Length { got: 3, n })
        );
        // A negative pivot at column 17: not positive definite, named.
        let mut bad = a;
        bad[(17, 17)] = -50.0;
        assert!(matches!(
            Cholesky::factor(&dense_to_csc(&bad)),
            Err(CholmodError::NotPositiveDefinite { .. })
        ));
    }
}
