//! Lowest eigenpairs of K φ = λ M φ (λ = ω², (rad/time)²) by shift-invert subspace
//! iteration (Bathe, "Finite Element Procedures", §11.6), factorizing K − σM once with
//! UMFPACK (real matrix through the complex interface).
//!
//! Per iteration, with q = min(max(2p, p+8), n) vectors X (n×q):
//!   Y = M X;  X̄ = (K − σM)⁻¹ Y;  K̂ = X̄ᵀ Y (= X̄ᵀ(K − σM)X̄);  M̂ = X̄ᵀ M X̄;
//!   K̂ Z = M̂ Z diag(μ) (dense, via Cholesky of M̂);  X ← X̄ Z;  λ = σ + μ.
//! The Ritz pairs closest to σ converge first; iteration stops when the p wanted ones
//! have relative residuals ‖Kφ − λMφ‖ / ‖(K − σM)φ‖ below `tol` (this norm stays
//! meaningful for rigid modes, λ ≈ 0, found with σ < 0), or when the residual has stopped
//! falling (the round-off floor of an ill-conditioned K, e.g. penalty ties: then
//! `Modes::converged` is false and `residuals` tells how far it got). Shapes come out
//! M-orthonormal (φᵀMφ = 1).

/// Residual progress: an iteration counts as progress if it lowers the best residual
/// by this factor...
const PROGRESS: f64 = 0.9;
/// ...and iteration stops as stalled after this many iterations without progress. A
/// genuinely converging run improves by λ_p/λ_(q+1) per iteration, far below 0.9^(1/10)
/// = 0.99 with q ≥ p + 8 vectors.
const STALL_ITERS: usize = 10;

use nalgebra::{Complex, DMatrix, SymmetricEigen};
use thiserror::Error;

use crate::fe::assembly::same_pattern;
use crate::fe::csc::Csc;
use crate::solve::umfpack::{Symbolic, UmfpackError};
use crate::util::rng::Rng;

/// Errors of the eigensolver.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModalError {
    #[error(transparent)]
    Umfpack(#[from] UmfpackError),
    #[error("K and M are not on one sparsity pattern")]
    PatternMismatch,
    #[error("asked for {wanted} modes of a system with {n} DOFs")]
    TooManyModes { wanted: usize, n: usize },
    #[error("projected mass matrix not positive definite (M singular on the subspace?)")]
    ProjectedMass,
    #[error(
        "no convergence after {iterations} iterations (largest relative residual {residual:.3e})"
    )]
    NotConverged { iterations: usize, residual: f64 },
}

/// Settings of [`lowest_modes`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalOptions {
    /// Number of modes wanted, p ≥ 1.
    pub n_modes: usize,
    /// Shift σ in (rad/time)²: modes nearest σ converge first. 0 for a clamped
    /// structure; slightly negative (e.g. −1e-3·λ₁ estimate) for a free one.
    pub shift: f64,
    /// Stop when every wanted mode has ‖Kφ − λMφ‖ / ‖(K − σM)φ‖ < tol. The eigenvalue
    /// error is then about tol² relative (Rayleigh quotient).
    pub tol: f64,
    pub max_iter: usize,
    /// Seed of the random start vectors (results are deterministic).
    pub seed: u64,
}

impl Default for ModalOptions {
    fn default() -> Self {
        ModalOptions {
            n_modes: 6,
            shift: 0.0,
            tol: 1e-8,
            max_iter: 200,
            seed: 1,
        }
    }
}

/// Eigenpairs sorted by ascending λ.
#[derive(Debug, Clone)]
pub struct Modes {
    /// λᵢ = ωᵢ² in (rad/time)².
    pub eigenvalues: Vec<f64>,
    /// φᵢ on the free DOFs, M-normalized.
    pub shapes: Vec<Vec<f64>>,
    /// ‖Kφ − λMφ‖ / ‖(K − σM)φ‖ per mode.
    pub residuals: Vec<f64>,
    pub iterations: usize,
    /// All residuals below `tol`; false if the iteration stopped at a round-off floor.
    pub converged: bool,
}

impl Modes {
    /// Natural frequencies fᵢ = √λᵢ / 2π in 1/time (Hz for seconds). Negative λ
    /// (round-off around rigid modes) gives 0.
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.eigenvalues
            .iter()
            .map(|&l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
            .collect()
    }
}

fn mul_cols(a: &Csc<f64>, x: &DMatrix<f64>) -> DMatrix<f64> {
    let mut y = DMatrix::zeros(x.nrows(), x.ncols());
    for c in 0..x.ncols() {
        let col = a.mul_vec(x.column(c).as_slice());
        y.column_mut(c).copy_from_slice(&col);
    }
    y
}

/// The shifts [`lowest_modes`] tries in turn when σ = 0 fails (a structure not held: K
/// singular, rigid-body modes at λ = 0): −rel × max diag K / max diag M, (rad/time)². The
/// diagonal ratio is about the stiffest element's own ω²; the first shift lies far below
/// the first flexible mode (three-beams-coarse unclamped: −4e5 against λ = 2.1e9 of its
/// 7354 Hz mode), a larger one keeps the rigid modes' amplified vectors from swamping
/// the projected mass (a free 20 × 4 × 4 mm steel box needs −1e6).
const FREE_SHIFT_REL: [f64; 3] = [1e-8, 1e-6, 1e-4];

/// A shift of a free structure ([`FREE_SHIFT_REL`]).
fn free_shift(k: &Csc<f64>, m: &Csc<f64>, rel: f64) -> f64 {
    let diag_max = |a: &Csc<f64>| {
        (0..a.n())
            .filter_map(|j| a.pattern.find(j, j).map(|s| a.values[s].abs()))
            .fold(0.0f64, f64::max)
    };
    let (dk, dm) = (diag_max(k), diag_max(m));
    if dm > 0.0 && dk > 0.0 {
        -rel * dk / dm
    } else {
        -1.0
    }
}

/// The `opts.n_modes` eigenpairs of K φ = λ M φ nearest `opts.shift` (the lowest ones
/// for a shift at or below the spectrum). K, M symmetric on one pattern, M positive
/// definite. With `shift` 0 and K singular (a free structure: the factorization, the
/// projected mass or the iteration fails) it tries once more below the spectrum
/// ([`FREE_SHIFT_REL`]); other shifts must leave K − σM nonsingular.
pub fn lowest_modes(k: &Csc<f64>, m: &Csc<f64>, opts: &ModalOptions) -> Result<Modes, ModalError> {
    let mut result = lowest_modes_about(k, m, opts);
    for rel in FREE_SHIFT_REL {
        match result {
            Err(
                ModalError::ProjectedMass
                | ModalError::NotConverged { .. }
                | ModalError::Umfpack(UmfpackError::Singular { .. }),
            ) if opts.shift == 0.0 => {
                let shift = free_shift(k, m, rel);
                result = lowest_modes_about(k, m, &ModalOptions { shift, ..*opts });
            }
            _ => break,
        }
    }
    result
}

/// [`lowest_modes`] about `opts.shift` as given.
fn lowest_modes_about(
    k: &Csc<f64>,
    m: &Csc<f64>,
    opts: &ModalOptions,
) -> Result<Modes, ModalError> {
    if !same_pattern(&k.pattern, &m.pattern) {
        return Err(ModalError::PatternMismatch);
    }
    let n = k.n();
    let p = opts.n_modes;
    if p == 0 || p > n {
        return Err(ModalError::TooManyModes { wanted: p, n });
    }
    let q = (2 * p).max(p + 8).min(n);
    let mut shifted = Csc::<Complex<f64>>::zeros(k.pattern.clone());
    for (s, (kv, mv)) in shifted
        .values
        .iter_mut()
        .zip(k.values.iter().zip(&m.values))
    {
        *s = Complex::new(kv - opts.shift * mv, 0.0);
    }
    let symbolic = Symbolic::new(k.pattern.clone())?;
    let lu = symbolic.factor(&shifted)?;

    // Start: diag(M) (excites all DOFs, Bathe) plus random vectors.
    let mut rng = Rng::new(opts.seed);
    let mut x = DMatrix::from_fn(n, q, |_, _| rng.uniform(-1.0, 1.0));
    for j in 0..n {
        if let Some(s) = m.pattern.find(j, j) {
            x[(j, 0)] = m.values[s];
        }
    }
    let mut worst = f64::INFINITY;
    let (mut best, mut best_it) = (f64::INFINITY, 0);
    let mut rhs = vec![Complex::new(0.0, 0.0); n];
    let mut sol = vec![Complex::new(0.0, 0.0); n];
    for it in 1..=opts.max_iter {
        let y = mul_cols(m, &x);
        let mut xb = DMatrix::zeros(n, q);
        for c in 0..q {
            for (r, v) in rhs.iter_mut().zip(y.column(c).iter()) {
                *r = Complex::new(*v, 0.0);
            }
            lu.solve_into(&rhs, &mut sol)?;
            for (t, s) in xb.column_mut(c).iter_mut().zip(&sol) {
                *t = s.re;
            }
        }
        let kr = xb.transpose() * &y;
        let kr = (&kr + kr.transpose()) * 0.5;
        let mx = mul_cols(m, &xb);
        let mr = xb.transpose() * &mx;
        let mr = (&mr + mr.transpose()) * 0.5;
        let chol = mr.cholesky().ok_or(ModalError::ProjectedMass)?;
        // C = L⁻¹ K̂ L⁻ᵀ, symmetric; K̂ Z = M̂ Z μ with Z = L⁻ᵀ V.
        let l = chol.l();
        let linv_k = l
            .solve_lower_triangular(&kr)
            .ok_or(ModalError::ProjectedMass)?;
        let c = l
            .solve_lower_triangular(&linv_k.transpose())
            .ok_or(ModalError::ProjectedMass)?;
        let c = (&c + c.transpose()) * 0.5;
        let eig = SymmetricEigen::new(c);
        let z_all = l
            .transpose()
            .solve_upper_triangular(&eig.eigenvectors)
            .ok_or(ModalError::ProjectedMass)?;
        // Nearest the shift first.
        let mut order: Vec<usize> = (0..q).collect();
        order.sort_by(|&a, &b| {
            eig.eigenvalues[a]
                .abs()
                .total_cmp(&eig.eigenvalues[b].abs())
        });
        let mut z = DMatrix::zeros(q, q);
        for (dst, &src) in order.iter().enumerate() {
            z.set_column(dst, &z_all.column(src));
        }
        x = &xb * z;
        let lambdas: Vec<f64> = order
            .iter()
            .map(|&i| opts.shift + eig.eigenvalues[i])
            .collect();
        let residuals: Vec<f64> = (0..p)
            .map(|i| residual(k, m, x.column(i).as_slice(), lambdas[i], opts.shift))
            .collect();
        worst = residuals.iter().copied().fold(0.0, f64::max);
        if worst < opts.tol {
            return Ok(finish(&x, &lambdas[..p], &residuals, it, true));
        }
        if worst < PROGRESS * best {
            best = worst;
            best_it = it;
        } else if it - best_it >= STALL_ITERS {
            // Round-off floor (ill-conditioned K, e.g. penalty ties): stop, say so.
            return Ok(finish(&x, &lambdas[..p], &residuals, it, false));
        }
    }
    Err(ModalError::NotConverged {
        iterations: opts.max_iter,
        residual: worst,
    })
}

/// ‖Kφ − λMφ‖ / ‖(K − σM)φ‖: relative residual, also meaningful for rigid modes (Kφ ≈ 0)
/// when σ ≠ 0.
fn residual(k: &Csc<f64>, m: &Csc<f64>, phi: &[f64], lambda: f64, shift: f64) -> f64 {
    let kp = k.mul_vec(phi);
    let mp = m.mul_vec(phi);
    let (mut r, mut s) = (0.0, 0.0);
    for (a, b) in kp.iter().zip(&mp) {
        r += (a - lambda * b).powi(2);
        s += (a - shift * b).powi(2);
    }
    (r / s.max(f64::MIN_POSITIVE)).sqrt()
}

fn finish(
    x: &DMatrix<f64>,
    lambdas: &[f64],
    residuals: &[f64],
    iterations: usize,
    converged: bool,
) -> Modes {
    let mut idx: Vec<usize> = (0..lambdas.len()).collect();
    idx.sort_by(|&a, &b| lambdas[a].total_cmp(&lambdas[b]));
    Modes {
        eigenvalues: idx.iter().map(|&i| lambdas[i]).collect(),
        shapes: idx
            .iter()
            .map(|&i| x.column(i).iter().copied().collect())
            .collect(),
        residuals: idx.iter().map(|&i| residuals[i]).collect(),
        iterations,
        converged,
    }
}

#[cfg(test)]
#[path = "modal_tests.rs"]
mod tests;
