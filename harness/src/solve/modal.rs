//! Lowest eigenpairs of K φ = λ M φ (λ = ω², (rad/time)²): shift-invert Lanczos
//! (ARPACK, [`crate::solve::arpack`], as CalculiX's `*FREQUENCY`) on one UMFPACK
//! factorization of K − σM, or a dense generalized eigensolution where the wanted modes
//! are so many that the Lanczos basis would span every DOF.
//!
//! The Ritz pairs nearest σ converge first. Each pair's quality is its normwise backward
//! error ‖Kφ − λMφ‖ / (‖K‖₁ + |λ|‖M‖₁)‖φ‖ (the relative change of K and M that makes
//! (λ, φ) exact): it stays near machine precision on ill-conditioned K (penalty ties),
//! where a residual relative to ‖Kφ‖ meets a round-off floor. Shapes come out
//! M-orthonormal (φᵀMφ = 1).

use nalgebra::{DMatrix, SymmetricEigen};
use thiserror::Error;

use crate::fe::assembly::same_pattern;
use crate::fe::csc::Csc;
use crate::solve::arpack::{self, LanczosError};
use crate::solve::cholmod::{Cholesky, CholmodError};
use crate::solve::umfpack::{Symbolic, UmfpackError};
use crate::util::rng::Rng;

/// Largest system solved densely when the wanted modes fill the Lanczos basis (n²
/// doubles per matrix: 128 MB at 4000 DOFs).
pub const DENSE_MAX_DOFS: usize = 4000;

/// Errors of the eigensolver.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModalError {
    #[error(transparent)]
    Umfpack(#[from] UmfpackError),
    #[error(transparent)]
    Cholmod(#[from] CholmodError),
    #[error("K and M are not on one sparsity pattern")]
    PatternMismatch,
    #[error("asked for {wanted} modes of a system with {n} DOFs")]
    TooManyModes { wanted: usize, n: usize },
    #[error(
        "asked for {wanted} of the {n} modes: more than a Lanczos basis leaves out, and \
         {n} DOFs is beyond the dense eigensolver's {DENSE_MAX_DOFS}"
    )]
    TooManyForDense { wanted: usize, n: usize },
    #[error(
        "mass matrix not positive definite: the dense eigensolver needs every DOF to carry mass"
    )]
    SingularMass,
    #[error(transparent)]
    Lanczos(#[from] LanczosError<ModalSolveError>),
}

/// A failed solve with the factorization of K − σM.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModalSolveError {
    #[error(transparent)]
    Cholmod(#[from] CholmodError),
    #[error(transparent)]
    Umfpack(#[from] UmfpackError),
}

impl From<ModalSolveError> for ModalError {
    fn from(e: ModalSolveError) -> Self {
        match e {
            ModalSolveError::Umfpack(u) => ModalError::Umfpack(u),
            ModalSolveError::Cholmod(c) => ModalError::Cholmod(c),
        }
    }
}

/// Settings of [`lowest_modes`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalOptions {
    /// Number of modes wanted, p ≥ 1.
    pub n_modes: usize,
    /// Shift σ in (rad/time)²: modes nearest σ converge first. 0 for a clamped
    /// structure; slightly negative (e.g. −1e-3·λ₁ estimate) for a free one.
    pub shift: f64,
    /// ARPACK's relative accuracy of the Ritz values of (K − σM)⁻¹M; the eigenvalues'
    /// relative error is then about tol² (Rayleigh quotient).
    pub tol: f64,
    /// Implicit restarts allowed.
    pub max_restarts: usize,
    /// Seed of the random start vector (results are deterministic).
    pub seed: u64,
}

impl Default for ModalOptions {
    fn default() -> Self {
        ModalOptions {
            n_modes: 6,
            shift: 0.0,
            tol: 1e-10,
            max_restarts: 300,
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
    /// Backward error ‖Kφ − λMφ‖ / (‖K‖₁ + |λ|‖M‖₁)‖φ‖ per mode.
    pub residuals: Vec<f64>,
    /// Solves with the factorization of K − σM (0 for the dense route).
    pub solves: usize,
    /// Every backward error below [`CONVERGED_BACKWARD_ERROR`].
    pub converged: bool,
}

/// A pair with a larger backward error is reported as not converged (the Lanczos
/// criterion met, but the pair is not an eigenpair of K, M to working accuracy).
pub const CONVERGED_BACKWARD_ERROR: f64 = 1e-8;

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

/// The shifts [`lowest_modes`] tries in turn when σ = 0 fails (a structure not held: K
/// singular, rigid-body modes at λ = 0): −rel × max diag K / max diag M, (rad/time)². The
/// diagonal ratio is about the stiffest element's own ω²; the first shift lies far below
/// the first flexible mode (three-beams-coarse unclamped: −4e5 against λ = 2.1e9 of its
/// 7354 Hz mode).
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
/// semidefinite. With `shift` 0 and K singular (a free structure: the factorization
/// fails, or the pairs found are not eigenpairs) it tries again below the spectrum
/// ([`FREE_SHIFT_REL`]); other shifts must leave K − σM nonsingular.
pub fn lowest_modes(k: &Csc<f64>, m: &Csc<f64>, opts: &ModalOptions) -> Result<Modes, ModalError> {
    let mut result = lowest_modes_about(k, m, opts);
    for rel in FREE_SHIFT_REL {
        let retry = match &result {
            Err(ModalError::Umfpack(UmfpackError::Singular { .. }))
            | Err(ModalError::Lanczos(_)) => true,
            Ok(modes) => !modes.converged,
            Err(_) => false,
        };
        if !(retry && opts.shift == 0.0) {
            break;
        }
        let shift = free_shift(k, m, rel);
        result = lowest_modes_about(k, m, &ModalOptions { shift, ..*opts });
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
    let (shapes, solves) = if arpack::basis_size(p, n) >= n {
        if n > DENSE_MAX_DOFS {
            return Err(ModalError::TooManyForDense { wanted: p, n });
        }
        (dense_modes(k, m, p)?, 0)
    } else {
        let found = lanczos_modes(k, m, opts)?;
        (found.vectors, found.solves)
    };
    // Rayleigh quotients φᵀKφ / φᵀMφ with the exact K and M: error ~ (vector error)²,
    // where λ = σ + 1/θ from the Ritz values carries the solves' error to first order.
    let mut pairs: Vec<(f64, Vec<f64>)> = shapes
        .into_iter()
        .map(|phi| {
            let (kp, mp) = (k.mul_vec(&phi), m.mul_vec(&phi));
            let dot = |a: &[f64]| a.iter().zip(&phi).map(|(x, y)| x * y).sum::<f64>();
            let mass = dot(&mp);
            let scale = 1.0 / mass.abs().sqrt().max(f64::MIN_POSITIVE);
            (dot(&kp) / mass, phi.iter().map(|v| v * scale).collect())
        })
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (lambdas, shapes): (Vec<f64>, Vec<Vec<f64>>) = pairs.into_iter().unzip();
    let norms = (k.norm_1(), m.norm_1());
    let residuals: Vec<f64> = lambdas
        .iter()
        .zip(&shapes)
        .map(|(&l, phi)| backward_error(k, m, norms, phi, l))
        .collect();
    let converged = residuals.iter().all(|&r| r < CONVERGED_BACKWARD_ERROR);
    Ok(Modes {
        eigenvalues: lambdas,
        shapes,
        residuals,
        solves,
        converged,
    })
}

/// x = (K − σM)⁻¹ b with one factorization.
type ShiftedSolve<'a> = dyn FnMut(&[f64], &mut [f64]) -> Result<(), ModalSolveError> + 'a;

/// Shift-invert Lanczos on one factorization of K − σM: CHOLMOD's supernodal Cholesky
/// where K − σM is positive definite (σ below the spectrum of a held structure), else
/// UMFPACK's LU (σ inside the spectrum).
fn lanczos_modes(
    k: &Csc<f64>,
    m: &Csc<f64>,
    opts: &ModalOptions,
) -> Result<arpack::Lanczos, ModalError> {
    let n = k.n();
    let mut shifted = Csc::<f64>::zeros(k.pattern.clone());
    for (s, (kv, mv)) in shifted
        .values
        .iter_mut()
        .zip(k.values.iter().zip(&m.values))
    {
        *s = kv - opts.shift * mv;
    }
    let mut rng = Rng::new(opts.seed);
    let start: Vec<f64> = (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect();
    let mass = |x: &[f64], y: &mut [f64]| m.mul_vec_into(x, y);
    let run = |solve: &mut ShiftedSolve| {
        arpack::shift_invert(
            opts.n_modes,
            opts.shift,
            opts.tol,
            opts.max_restarts,
            &start,
            solve,
            mass,
        )
    };
    match Cholesky::factor(&shifted) {
        Ok(mut chol) => Ok(run(&mut |b, x| Ok(chol.solve_into(b, x)?))?),
        Err(CholmodError::NotPositiveDefinite { .. }) => {
            // AMD on the symmetric pattern, diagonal pivots preferred.
            let mut symbolic = Symbolic::symmetric(k.pattern.clone())?;
            // Lanczos tolerates the LU's own backward error (the eigenvalues are
            // Rayleigh quotients); refinement would double each solve.
            symbolic.set_refinement_steps(0);
            let lu = symbolic.factor(&shifted)?;
            Ok(run(&mut |b, x| Ok(lu.solve_into(b, x)?))?)
        }
        Err(e) => Err(ModalSolveError::from(e).into()),
    }
}

/// The vectors of the p lowest pairs of the dense pencil (K, M): M = LLᵀ,
/// L⁻¹KL⁻ᵀ = VΛVᵀ, Φ = L⁻ᵀV.
fn dense_modes(k: &Csc<f64>, m: &Csc<f64>, p: usize) -> Result<Vec<Vec<f64>>, ModalError> {
    let (kd, md) = (k.to_dense(), m.to_dense());
    let kd = (&kd + kd.transpose()) * 0.5;
    let md = (&md + md.transpose()) * 0.5;
    let chol = md.cholesky().ok_or(ModalError::SingularMass)?;
    let l = chol.l();
    let linv_k = l
        .solve_lower_triangular(&kd)
        .ok_or(ModalError::SingularMass)?;
    let c = l
        .solve_lower_triangular(&linv_k.transpose())
        .ok_or(ModalError::SingularMass)?;
    let eig = SymmetricEigen::new((&c + c.transpose()) * 0.5);
    let phi: DMatrix<f64> = l
        .transpose()
        .solve_upper_triangular(&eig.eigenvectors)
        .ok_or(ModalError::SingularMass)?;
    let mut order: Vec<usize> = (0..k.n()).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    order.truncate(p);
    Ok(order
        .iter()
        .map(|&i| phi.column(i).iter().copied().collect())
        .collect())
}

/// ‖Kφ − λMφ‖₁ / ((‖K‖₁ + |λ|‖M‖₁)‖φ‖₁): the normwise backward error of (λ, φ).
fn backward_error(
    k: &Csc<f64>,
    m: &Csc<f64>,
    (nk, nm): (f64, f64),
    phi: &[f64],
    lambda: f64,
) -> f64 {
    let kp = k.mul_vec(phi);
    let mp = m.mul_vec(phi);
    let r: f64 = kp
        .iter()
        .zip(&mp)
        .map(|(a, b)| (a - lambda * b).abs())
        .sum();
    let x: f64 = phi.iter().map(|v| v.abs()).sum();
    r / ((nk + lambda.abs() * nm) * x).max(f64::MIN_POSITIVE)
}

#[cfg(test)]
#[path = "modal_tests.rs"]
pub(crate) mod tests;
