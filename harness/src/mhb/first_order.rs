//! The thesis's first-order method on a lumped system, for comparison with the harmonic
//! balance: every element replaced by k* + iω d* for its relative-displacement amplitude
//! A (points: `jointlin_linearize`, k* by (3.8) on the Ersatzfunktion (4.3), d* by
//! (3.14); cubic spring: C* = ¾ k₃ A², (3.8) for f = k₃x³), the complex linear system
//! (K − ω²M + iωD + Σ Pᵀ(k* + iωd*)P) x̂ = f̂ solved, A ← |P x̂|, made consistent
//! (A = |P x̂(A)|, thesis §4.2.3) by [`super::consistency`].

use nalgebra::{Complex, DMatrix, DVector};

use super::{consistency, Law, MhbError, System};
use crate::capi;

type C64 = Complex<f64>;

/// Consistency reached: relative change of every element amplitude below this.
pub const TOL: f64 = 1e-12;

/// The first-order response x̂ (complex first harmonic per DOF) at ω, from the element
/// amplitudes `a0` (start estimate).
pub fn solve(sys: &System, omega: f64, a0: &[f64]) -> Result<Vec<C64>, MhbError> {
    let g = |amp: &[f64]| -> Result<Vec<f64>, MhbError> {
        let x = response(sys, omega, amp)?;
        Ok(element_amplitudes(sys, &x))
    };
    match consistency::solve(a0, g, TOL, MAX_ITER)? {
        Ok(c) => response(sys, omega, &c.x),
        Err(st) => Err(MhbError::Consistency {
            omega,
            mismatch: st.mismatch,
            iterations: st.iterations,
        }),
    }
}

/// Iterations of [`consistency::solve`] at most (converged runs take 2–10).
const MAX_ITER: usize = 100;

/// Relative-displacement amplitudes |P x̂| of the elements.
pub fn element_amplitudes(sys: &System, x: &[C64]) -> Vec<f64> {
    sys.elements
        .iter()
        .map(|e| (x[e.i] - e.j.map_or(C64::new(0.0, 0.0), |j| x[j])).norm())
        .collect()
}

/// The linearized response for element amplitudes `amp`.
fn response(sys: &System, omega: f64, amp: &[f64]) -> Result<Vec<C64>, MhbError> {
    let n = sys.n();
    let mut s = DMatrix::<C64>::zeros(n, n);
    for a in 0..n {
        for b in 0..n {
            s[(a, b)] = C64::new(
                sys.k[(a, b)] - omega * omega * sys.m[(a, b)],
                omega * sys.d[(a, b)],
            );
        }
    }
    for (e, &a) in sys.elements.iter().zip(amp) {
        let z = match e.law {
            Law::Cubic(k3) => {
                let k_star = capi::linearize_cubic(0.0, k3, a).map_err(super::AftError::from)?;
                C64::new(k_star, 0.0)
            }
            Law::Point(t) => {
                let l = capi::linearize(&t, a, omega).map_err(super::AftError::from)?;
                C64::new(l.k_star, omega * l.d_star)
            }
        };
        s[(e.i, e.i)] += z;
        if let Some(j) = e.j {
            s[(j, j)] += z;
            s[(e.i, j)] -= z;
            s[(j, e.i)] -= z;
        }
    }
    let f = DVector::from_iterator(n, sys.f1.iter().copied());
    let x = s.lu().solve(&f).ok_or(MhbError::Singular { omega })?;
    Ok(x.iter().copied().collect())
}
