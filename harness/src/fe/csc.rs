//! Compressed sparse column storage with 64-bit indices (UMFPACK's `zl` layout).
//!
//! A [`CscPattern`] is built once and shared (`Arc`) by every matrix of a system
//! (K, M, D, the dynamic stiffness): they differ only in their `values`, so per-frequency
//! work is a loop over values with no allocation, and one UMFPACK symbolic analysis
//! serves them all.

use std::sync::Arc;

use nalgebra::{Complex, DMatrix};

/// Square sparsity pattern: column `j` holds rows `row_idx[col_ptr[j]..col_ptr[j+1]]`,
/// sorted ascending, no duplicates.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CscPattern {
    pub n: usize,
    pub col_ptr: Vec<i64>,
    pub row_idx: Vec<i64>,
}

impl CscPattern {
    /// Builds a pattern from (row, col) entries (any order, duplicates allowed).
    /// Panics if an index is ≥ n (a programming error, not user input).
    pub fn from_entries(n: usize, entries: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut cols: Vec<Vec<i64>> = vec![Vec::new(); n];
        for (r, c) in entries {
            assert!(r < n && c < n, "entry ({r}, {c}) outside {n}×{n}");
            cols[c].push(r as i64);
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for mut col in cols {
            col.sort_unstable();
            col.dedup();
            row_idx.extend_from_slice(&col);
            col_ptr.push(row_idx.len() as i64);
        }
        CscPattern {
            n,
            col_ptr,
            row_idx,
        }
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Index into `values` of entry (row, col), if it is in the pattern (binary search).
    pub fn find(&self, row: usize, col: usize) -> Option<usize> {
        let lo = self.col_ptr[col] as usize;
        let hi = self.col_ptr[col + 1] as usize;
        self.row_idx[lo..hi]
            .binary_search(&(row as i64))
            .ok()
            .map(|k| lo + k)
    }
}

/// A sparse square matrix: shared pattern plus values.
#[derive(Debug, Clone, PartialEq)]
pub struct Csc<T> {
    pub pattern: Arc<CscPattern>,
    pub values: Vec<T>,
}

impl<T: Copy + Default> Csc<T> {
    /// All-zero matrix on `pattern`.
    pub fn zeros(pattern: Arc<CscPattern>) -> Self {
        let values = vec![T::default(); pattern.nnz()];
        Csc { pattern, values }
    }

    /// Dimension n.
    pub fn n(&self) -> usize {
        self.pattern.n
    }
}

impl Csc<f64> {
    /// y = A x.
    pub fn mul_vec(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.pattern.n];
        self.mul_vec_into(x, &mut y);
        y
    }

    /// y = A x into `y` (length n), no allocation.
    pub fn mul_vec_into(&self, x: &[f64], y: &mut [f64]) {
        let p = &self.pattern;
        y.fill(0.0);
        for j in 0..p.n {
            for k in p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize {
                y[p.row_idx[k] as usize] += self.values[k] * x[j];
            }
        }
    }

    /// y = |A| |x| (entrywise absolute values): the size of the terms A x sums, for
    /// round-off bounds.
    pub fn abs_mul_vec(&self, x: &[f64]) -> Vec<f64> {
        let p = &self.pattern;
        let mut y = vec![0.0; p.n];
        for j in 0..p.n {
            for k in p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize {
                y[p.row_idx[k] as usize] += (self.values[k] * x[j]).abs();
            }
        }
        y
    }

    /// ‖A‖₁, the largest absolute column sum.
    pub fn norm_1(&self) -> f64 {
        let p = &self.pattern;
        (0..p.n)
            .map(|j| {
                let col = p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize;
                self.values[col].iter().map(|v| v.abs()).sum::<f64>()
            })
            .fold(0.0, f64::max)
    }

    /// Dense copy (tests, small problems).
    pub fn to_dense(&self) -> DMatrix<f64> {
        let p = &self.pattern;
        let mut d = DMatrix::zeros(p.n, p.n);
        for j in 0..p.n {
            for k in p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize {
                d[(p.row_idx[k] as usize, j)] += self.values[k];
            }
        }
        d
    }
}

impl Csc<Complex<f64>> {
    /// √(‖A‖₁‖A‖∞) (largest column and row sums of |aᵢⱼ|): an upper bound of the
    /// spectral norm ‖A‖₂, within a factor √n of it.
    pub fn norm2_bound(&self) -> f64 {
        let p = &self.pattern;
        let (mut cols, mut rows) = (vec![0.0f64; p.n], vec![0.0f64; p.n]);
        for j in 0..p.n {
            for k in p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize {
                let v = self.values[k].norm();
                cols[j] += v;
                rows[p.row_idx[k] as usize] += v;
            }
        }
        let max = |s: &[f64]| s.iter().fold(0.0f64, |m, &v| m.max(v));
        (max(&cols) * max(&rows)).sqrt()
    }

    /// y = A x.
    pub fn mul_vec(&self, x: &[Complex<f64>]) -> Vec<Complex<f64>> {
        let p = &self.pattern;
        let mut y = vec![Complex::new(0.0, 0.0); p.n];
        for j in 0..p.n {
            for k in p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize {
                y[p.row_idx[k] as usize] += self.values[k] * x[j];
            }
        }
        y
    }

    /// Dense copy (tests, small problems).
    pub fn to_dense(&self) -> DMatrix<Complex<f64>> {
        let p = &self.pattern;
        let mut d = DMatrix::from_element(p.n, p.n, Complex::new(0.0, 0.0));
        for j in 0..p.n {
            for k in p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize {
                d[(p.row_idx[k] as usize, j)] += self.values[k];
            }
        }
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pattern_sorted_deduplicated_and_findable() {
        let p = CscPattern::from_entries(3, [(2, 0), (0, 0), (2, 0), (1, 1), (0, 2), (2, 2)]);
        assert_eq!(p.col_ptr, vec![0, 2, 3, 5]);
        assert_eq!(p.row_idx, vec![0, 2, 1, 0, 2]);
        assert_eq!(p.find(2, 0), Some(1));
        assert_eq!(p.find(1, 0), None);
        assert_eq!(p.find(2, 2), Some(4));
        let mut a = Csc::<f64>::zeros(Arc::new(p));
        a.values.copy_from_slice(&[1.0, 2.0, 3.0, 4.0, 5.0]);
        // A = [[1,0,4],[0,3,0],[2,0,5]]; A·(1,1,1) = (5,3,7)
        assert_eq!(a.mul_vec(&[1.0, 1.0, 1.0]), vec![5.0, 3.0, 7.0]);
        assert_eq!(a.to_dense()[(2, 0)], 2.0);
    }
}
