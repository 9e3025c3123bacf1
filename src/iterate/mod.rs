//! Amplitude consistency (4.2.3, Fig. 4.12–4.14): k*, d* depend on the amplitude a they
//! are linearized for, and the linear solve with them returns an amplitude a*; the
//! consistent amplitude is the fixed point a = a*(a).
//!
//! [`next_estimate`] is the one update rule shared by the single-point/dense solvers here and
//! the UEXTERNALDB-side [`crate::store`]: from the history of (estimate, computed) pairs it
//! proposes the next estimate.
//!
//! [`solve_point`] solves the thesis's single-point problem (4.2) and [`solve_dense`] a
//! small dense system with contact elements; both return an [`IterateError`] naming the
//! reason when there is no consistent amplitude.

use crate::error::Error;
use crate::linearize::{linearize, Contact, Linearization, Method};
use nalgebra::{Complex, DMatrix, DVector};

/// Complex amplitude (re-exported from nalgebra's num-complex).
pub type Complex64 = Complex<f64>;

/// How the next amplitude estimate follows from the earlier (a, a*) pairs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[repr(i32)]
pub enum Scheme {
    /// a ← a*: fast when the map contracts, but can flip between two values forever (Fig. 4.13).
    Direct = 0,
    /// The thesis's relaxation a ← (a + a*)/2 (Fig. 4.14).
    Relaxation = 1,
    /// Default: root of the residual r(s) = ln a*(e^s) − s in s = ln a, kept inside a
    /// bracket once a sign change is found (so it cannot 2-cycle). [`solve_point`] runs it
    /// as bracket expansion + Illinois false position; the stateless [`next_estimate`]
    /// (used across passes by the store) as a secant step with a bisection safeguard.
    #[default]
    Secant = 2,
}

/// Largest change of ln a in one unbracketed secant step (a factor of 10).
const MAX_LOG_STEP: f64 = std::f64::consts::LN_10;

/// The next estimate from `history` = [(a₀, a₀*), (a₁, a₁*), …], oldest first, all > 0 and
/// finite (checked by the caller). Returns the last a* when the history is empty of
/// information (one pair, `Direct` or `Secant`).
pub fn next_estimate(scheme: Scheme, history: &[(f64, f64)]) -> f64 {
    let Some(&(a, a_star)) = history.last() else {
        return f64::NAN; // callers always pass at least one pair
    };
    match scheme {
        Scheme::Direct => a_star,
        Scheme::Relaxation => 0.5 * (a + a_star), // Fig. 4.14
        Scheme::Secant => secant(history).exp(),
    }
}

/// Residual points (s, r) with s = ln a, r = ln a* − ln a.
fn residual(pair: &(f64, f64)) -> (f64, f64) {
    (pair.0.ln(), pair.1.ln() - pair.0.ln())
}

fn secant(history: &[(f64, f64)]) -> f64 {
    let (s2, r2) = residual(history.last().expect("non-empty"));
    if history.len() == 1 || r2 == 0.0 {
        return s2 + r2; // a ← a*
    }
    // Tightest bracket: largest s with r > 0 and smallest s with r < 0 above it.
    let points: Vec<(f64, f64)> = history.iter().map(residual).collect();
    let lo = points
        .iter()
        .filter(|p| p.1 > 0.0)
        .max_by(|x, y| x.0.total_cmp(&y.0));
    let hi = points
        .iter()
        .filter(|p| p.1 < 0.0)
        .min_by(|x, y| x.0.total_cmp(&y.0));
    if let (Some(&(sl, rl)), Some(&(sh, rh))) = (lo, hi) {
        if sl < sh {
            let (_, r1) = points[points.len() - 2];
            let mid = 0.5 * (sl + sh);
            if r1.signum() == r2.signum() {
                return mid; // one end stuck: bisect (Illinois-style safeguard)
            }
            let s = sl - rl * (sh - sl) / (rh - rl);
            return if s > sl && s < sh { s } else { mid };
        }
    }
    let (s1, r1) = points[points.len() - 2];
    let slope = (r2 - r1) / (s2 - s1);
    let step = if slope < 0.0 && slope.is_finite() {
        -r2 / slope
    } else {
        r2
    };
    s2 + step.clamp(-MAX_LOG_STEP, MAX_LOG_STEP)
}

// ---------------------------------------------------------------------------------------
// Solvers: one contact point on a mass (4.2), and a small dense system.
// ---------------------------------------------------------------------------------------

/// Relative amplitude change |a* − a|/a at which the iteration stops by default.
pub const DEFAULT_TOLERANCE: f64 = 1e-8;
/// Default cap on the number of linear solves (iterations, not counting the finite-difference
/// solves of the dense Newton step).
pub const DEFAULT_MAX_ITERATIONS: usize = 200;
/// Unbracketed steps of the default scheme before it gives up with [`IterateError::NoBracket`]:
/// each moves ln a by at most [`MAX_LOG_STEP`], so 64 steps span 64 decades.
const MAX_EXPANSIONS: usize = 64;
/// Finite-difference step in s = ln a for the dense Newton Jacobian: √ε-sized relative to the
/// O(1) curvature of r(s), so truncation (∝ h) and round-off (∝ ε/h) errors balance at ~1e-8.
const FD_STEP: f64 = 1.5e-8;
/// A direct-iteration 2-cycle is declared once a_k and a_{k−2} agree to this relative
/// accuracy while a_k and a_{k−1} still differ by more than the tolerance (Fig. 4.13).
const TWO_CYCLE_MATCH: f64 = 1e-9;
/// Amplitudes below this fraction of the largest stick-state amplitude are treated as this
/// floor, so ln a stays finite for a contact that does not move (e.g. by symmetry).
const AMPLITUDE_FLOOR: f64 = 1e-14;

/// Why the amplitude iteration returned no amplitude.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum IterateError {
    /// A mass held only by a friction contact is driven past the friction limit μF_N, so the
    /// contact must slide, but the drive F̂ is not above 4μF_N/π, the largest first harmonic a
    /// sliding contact's force can have (a square wave of height μF_N). A first-harmonic
    /// balance of a sliding mass then has no periodic solution: the motion is stick–slip with
    /// stops (model.md §8). `limit` = 4μF_N/π (∞ for a massless point: without inertia nothing
    /// balances the excess force).
    #[error(
        "no first-harmonic solution: forcing {forcing} exceeds the friction limit \
         {friction_limit} but not 4 mu F_N / pi = {limit}; the motion is stick-slip"
    )]
    NoFirstHarmonicSolution {
        forcing: f64,
        friction_limit: f64,
        limit: f64,
    },
    /// The iteration did not meet the tolerance within the allowed number of linear solves.
    #[error("no convergence after {iterations} iterations (last relative change {last_change:e})")]
    MaxIterations { iterations: usize, last_change: f64 },
    /// Direct iteration a ← a* alternates between two amplitudes (Fig. 4.13).
    #[error("direct iteration alternates between {a:e} and {b:e} (Fig. 4.13)")]
    TwoCycle { a: f64, b: f64 },
    /// Expanding the search in ln a found no sign change of r(s) = ln a*(e^s) − s between
    /// `low` and `high` (the response grows without bound, e.g. an unrestrained mass).
    #[error("no bracket: r(s) = ln a* - ln a keeps its sign for a in [{low:e}, {high:e}]")]
    NoBracket { low: f64, high: f64 },
    /// r(s) changes sign across an interval too short to resolve: the response jumps there
    /// (a discontinuity of a*(a)), so there is no consistent amplitude at that point.
    #[error("a*(a) jumps across a = {at:e}: no consistent amplitude there")]
    Jump { at: f64 },
    /// The dynamic stiffness is singular (undamped resonance) or the response overflows.
    #[error("singular dynamic stiffness (undamped resonance) or overflowing response")]
    Singular,
    /// The problem data are invalid (message names the input).
    #[error("invalid problem: {0}")]
    Invalid(&'static str),
    /// The linearization of a contact failed.
    #[error("linearization failed: {0}")]
    Linearize(#[from] Error),
}

/// Iteration settings shared by [`solve_point`] and [`solve_dense`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    pub scheme: Scheme,
    /// Quadrature of the linearization.
    pub method: Method,
    /// Stop when |a* − a| ≤ tolerance · a for every contact (relative amplitude change).
    pub tolerance: f64,
    /// Cap on linear solves (see [`DEFAULT_MAX_ITERATIONS`]).
    pub max_iterations: usize,
    /// First amplitude estimate a₁ (all contacts); None: the stick response, i.e. the
    /// linear solve with k* = k_T0, d* = 0 (the linearization at a = 0).
    pub initial: Option<f64>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            scheme: Scheme::default(),
            method: Method::default(),
            tolerance: DEFAULT_TOLERANCE,
            max_iterations: DEFAULT_MAX_ITERATIONS,
            initial: None,
        }
    }
}

impl Options {
    fn validate(&self) -> Result<(), IterateError> {
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(IterateError::Invalid("tolerance must lie in (0, 1)"));
        }
        if self.max_iterations == 0 {
            return Err(IterateError::Invalid("max_iterations must be > 0"));
        }
        if let Some(a) = self.initial {
            if !(a.is_finite() && a > 0.0) {
                return Err(IterateError::Invalid(
                    "initial amplitude must be finite and > 0",
                ));
            }
        }
        Ok(())
    }
}

mod dense;
mod point;

pub use dense::{solve_dense, ContactElement, DenseProblem, DenseSolution};
pub use point::{solve_point, PointProblem, PointSolution};

#[cfg(test)]
mod tests {
    use super::*;

    /// Iterates a ↦ a*(a) with a scheme from a₀; returns the iterates.
    fn run(scheme: Scheme, map: impl Fn(f64) -> f64, a0: f64, n: usize) -> Vec<f64> {
        let mut history = vec![];
        let mut a = a0;
        let mut out = vec![a];
        for _ in 0..n {
            history.push((a, map(a)));
            a = next_estimate(scheme, &history);
            out.push(a);
        }
        out
    }

    #[test]
    fn direct_iteration_two_cycles_where_secant_converges() {
        // a*(a) = 1/a² has the fixed point 1 and derivative −2 there: a ← a* diverges into
        // a 2-cycle-like oscillation (Fig. 4.13); the secant scheme converges.
        let map = |a: f64| 1.0 / (a * a);
        let direct = run(Scheme::Direct, map, 1.5, 6);
        assert!((direct[6] - 1.0).abs() > 0.5, "{direct:?}");
        let secant = run(Scheme::Secant, map, 1.5, 20);
        assert!((secant[20] - 1.0).abs() < 1e-12, "{secant:?}");
    }

    #[test]
    fn relaxation_converges_linearly_on_the_same_map() {
        let map = |a: f64| 1.0 / a.sqrt();
        let relaxed = run(Scheme::Relaxation, map, 3.0, 60);
        assert!((relaxed[60] - 1.0).abs() < 1e-10);
    }
}

#[cfg(test)]
mod solve_tests;
