//! The thesis's first-order method on a lumped system, for comparison with the harmonic
//! balance: every element replaced by k* + iω d* for its relative-displacement amplitude
//! A (points: `jointlin_linearize`, k* by (3.8) on the Ersatzfunktion (4.3), d* by
//! (3.14); cubic spring: C* = ¾ k₃ A², (3.8) for f = k₃x³), the complex linear system
//! (K − ω²M + iωD + Σ Pᵀ(k* + iωd*)P) x̂ = f̂ solved, A ← |P x̂|, made consistent
//! (A = |P x̂(A)|, thesis §4.2.3) by [`super::consistency`]'s Newton iteration with the
//! map's exact derivative (`amplitude_derivative`: one more solve with the same
//! factorization per iteration, where forward differences took one factorization per
//! element).

use nalgebra::{Complex, DMatrix, DVector};

use super::{consistency, Law, MhbError, System};
use crate::capi;

type C64 = Complex<f64>;
/// A factorization of the complex dynamic stiffness.
type Factored = nalgebra::LU<C64, nalgebra::Dyn, nalgebra::Dyn>;

/// Consistency reached: relative change of every element amplitude below this.
pub const TOL: f64 = 1e-12;

/// The first-order response x̂ (complex first harmonic per DOF) at ω, from the element
/// amplitudes `a0` (start estimate).
pub fn solve(sys: &System, omega: f64, a0: &[f64]) -> Result<Vec<C64>, MhbError> {
    let g = |amp: &[f64]| -> Result<Vec<f64>, MhbError> {
        let x = response(sys, omega, amp)?.0;
        Ok(element_amplitudes(sys, &x))
    };
    let mut derivative = |amp: &[f64]| amplitude_derivative(sys, omega, amp);
    match consistency::solve_with(
        a0,
        g,
        Some(&mut derivative),
        &vec![0; a0.len()],
        TOL,
        MAX_ITER,
    )? {
        Ok(c) => Ok(response(sys, omega, &c.x)?.0),
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
    element_amplitudes_complex(sys, x)
        .iter()
        .map(|u| u.norm())
        .collect()
}

/// The element's linearized impedance z = k* + iωd* at amplitude `a`.
fn impedance(law: Law, omega: f64, a: f64) -> Result<C64, MhbError> {
    Ok(match law {
        Law::Cubic(k3) => C64::new(
            capi::linearize_cubic(0.0, k3, a).map_err(super::AftError::from)?,
            0.0,
        ),
        Law::Point(t) => {
            let l = capi::linearize(&t, a, omega).map_err(super::AftError::from)?;
            C64::new(l.k_star, omega * l.d_star)
        }
    })
}

/// ∂g/∂a of the map g(a) = |P x̂(a)|: with u = P x̂, H = P S⁻¹ Pᵀ and z'_k = dz/dA at
/// a_k (central difference of the library's k*, d*, relative step 1e-6),
/// ∂u_e/∂a_k = −H_ek z'_k u_k (from S x̂ = f̂) and ∂g_e/∂a_k = Re(ū_e ∂u_e/∂a_k)/|u_e|
/// (0 where u_e = 0).
pub(super) fn amplitude_derivative(
    sys: &System,
    omega: f64,
    amp: &[f64],
) -> Result<DMatrix<f64>, MhbError> {
    let (x, lu) = response(sys, omega, amp)?;
    let (n, ne) = (sys.n(), sys.elements.len());
    let mut pt = DMatrix::<C64>::zeros(n, ne);
    for (k, e) in sys.elements.iter().enumerate() {
        pt[(e.i, k)] += C64::new(1.0, 0.0);
        if let Some(j) = e.j {
            pt[(j, k)] -= C64::new(1.0, 0.0);
        }
    }
    let y = lu.solve(&pt).ok_or(MhbError::Singular { omega })?;
    let u: Vec<C64> = element_amplitudes_complex(sys, &x);
    let mut out = DMatrix::zeros(ne, ne);
    for (k, e) in sys.elements.iter().enumerate() {
        let a = amp[k];
        let h = 1e-6 * a.abs().max(f64::MIN_POSITIVE);
        let lo = (a - h).max(0.0);
        let dz = (impedance(e.law, omega, a + h)? - impedance(e.law, omega, lo)?) / (a + h - lo);
        for (r, f) in sys.elements.iter().enumerate() {
            let h_rk = y[(f.i, k)] - f.j.map_or(C64::new(0.0, 0.0), |j| y[(j, k)]);
            let du = -h_rk * dz * u[k];
            if u[r].norm() > 0.0 {
                out[(r, k)] = (u[r].conj() * du).re / u[r].norm();
            }
        }
    }
    Ok(out)
}

/// The linearized response x̂ for element amplitudes `amp` (no consistency).
#[cfg(test)]
pub(super) fn solve_linear(sys: &System, omega: f64, amp: &[f64]) -> Result<Vec<C64>, MhbError> {
    Ok(response(sys, omega, amp)?.0)
}

/// Complex relative displacements P x̂ of the elements.
fn element_amplitudes_complex(sys: &System, x: &[C64]) -> Vec<C64> {
    sys.elements
        .iter()
        .map(|e| x[e.i] - e.j.map_or(C64::new(0.0, 0.0), |j| x[j]))
        .collect()
}

/// The linearized response for element amplitudes `amp`, and the factorization of S.
fn response(sys: &System, omega: f64, amp: &[f64]) -> Result<(Vec<C64>, Factored), MhbError> {
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
        let z = impedance(e.law, omega, a)?;
        s[(e.i, e.i)] += z;
        if let Some(j) = e.j {
            s[(j, j)] += z;
            s[(e.i, j)] -= z;
            s[(j, e.i)] -= z;
        }
    }
    let f = DVector::from_iterator(n, sys.f1.iter().copied());
    let lu = s.lu();
    let x = lu.solve(&f).ok_or(MhbError::Singular { omega })?;
    Ok((x.iter().copied().collect(), lu))
}
