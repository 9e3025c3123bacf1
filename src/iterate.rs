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
    /// Default: secant on the residual r(s) = ln a*(e^s) − s in s = ln a, switching to
    /// bisection once a sign change brackets the root (so it cannot 2-cycle).
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

/// The thesis's single-point problem (4.2): a mass m on one contact point (the other body
/// fixed), driven by F̂ sin ωt, optionally with a linear spring k_g and damper d_g to ground
/// in parallel with the contact:
///
/// m ẍ + (d_g + d*) ẋ + (k_g + k*) x = F̂ sin ωt,  a* = F̂ / |k_g + k* − mω² + iω(d_g + d*)|.
///
/// Units are the caller's and consistent (e.g. N, mm, s, t).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointProblem {
    pub contact: Contact,
    /// Mass m ≥ 0.
    pub mass: f64,
    /// Force amplitude F̂ ≥ 0.
    pub forcing: f64,
    /// Angular frequency ω > 0.
    pub omega: f64,
    /// Extra linear spring to ground k_g ≥ 0 (0: the block of 4.2).
    pub ground_stiffness: f64,
    /// Extra linear damper to ground d_g ≥ 0.
    pub ground_damping: f64,
}

/// A consistent amplitude and how it was reached.
#[derive(Debug, Clone, PartialEq)]
pub struct PointSolution {
    /// a* of the last linear solve (length), within the tolerance of its estimate a.
    pub amplitude: f64,
    /// The estimate a the last linearization was made for.
    pub estimate: f64,
    /// The linearization at `estimate`.
    pub linearization: Linearization,
    /// Number of linearizations (= linear solves) made, including the initial stick one.
    pub linearizations: usize,
    /// (a, a*) pairs, oldest first.
    pub history: Vec<(f64, f64)>,
}

impl PointProblem {
    fn validate(&self) -> Result<(), IterateError> {
        let ok = |x: f64| x.is_finite() && x >= 0.0;
        if !ok(self.mass) || !ok(self.forcing) || !ok(self.ground_stiffness) {
            return Err(IterateError::Invalid(
                "mass, forcing and ground stiffness must be finite and >= 0",
            ));
        }
        if !ok(self.ground_damping) {
            return Err(IterateError::Invalid(
                "ground damping must be finite and >= 0",
            ));
        }
        if !(self.omega.is_finite() && self.omega > 0.0) {
            return Err(IterateError::Invalid("omega must be finite and > 0"));
        }
        Ok(())
    }

    /// One linear solve: the amplitude a* of (4.2) with k*, d* linearized for amplitude a.
    pub fn response(
        &self,
        amplitude: f64,
        method: Method,
    ) -> Result<(f64, Linearization), IterateError> {
        let lin = linearize(&self.contact, amplitude, self.omega, method)?;
        let re = self.ground_stiffness + lin.k_star - self.mass * self.omega * self.omega;
        let im = self.omega * (self.ground_damping + lin.d_star);
        let a_star = self.forcing / re.hypot(im); // (4.2), harmonic steady state
        if !a_star.is_finite() {
            return Err(IterateError::Singular);
        }
        Ok((a_star, lin))
    }

    /// The a-priori test of [`IterateError::NoFirstHarmonicSolution`].
    ///
    /// Tested condition: no ground spring or damper (the contact is the only load path),
    /// and μF_N < F̂ ≤ 4μF_N/π.
    ///
    /// Why: the contact force is bounded by μF_N at every instant, so with F̂ > μF_N the
    /// block cannot stick (the inertia term mω²x of a sticking block, x ≲ δ*, is far too small
    /// to take up the excess) and must slide. A sliding contact's force is at most a square
    /// wave of height μF_N, whose first harmonic is 4μF_N/π, 90° out of phase with the
    /// displacement; the first-harmonic balance of the sliding mass,
    /// F̂² = (mω²a)² + (4μF_N/π)², then needs F̂ > 4μF_N/π (4.2 with k* → 0,
    /// ωd* → 4μF_N/(πa), model.md §5 limits).
    ///
    /// The iteration itself would not notice: r(s) = ln a* − s does have a root at a small
    /// amplitude of a few δ*, where the first harmonic of the friction loop alone (its peak
    /// is μF_N, its harmonic up to 4/π times that) equals F̂ and the inertia is negligible.
    /// That root is spurious: it needs a contact force whose fundamental is F̂ > μF_N while the
    /// force itself never exceeds μF_N, i.e. a square-ish force, but the applied force is a
    /// sine whose peak exceeds μF_N; the excess accelerates the block, which travels by
    /// (F̂ − μF_N)/(mω²)-sized distances (tens of mm for the block, model.md §8), four
    /// orders of magnitude beyond that root.
    fn check_first_harmonic(&self) -> Result<(), IterateError> {
        if self.ground_stiffness > 0.0 || self.ground_damping > 0.0 {
            return Ok(());
        }
        let Some(point) = self.contact.point()? else {
            return Ok(());
        };
        let friction_limit = point.backbone.friction_limit();
        let limit = if self.mass > 0.0 {
            4.0 * friction_limit / std::f64::consts::PI
        } else {
            f64::INFINITY
        };
        if self.forcing > friction_limit && self.forcing <= limit {
            return Err(IterateError::NoFirstHarmonicSolution {
                forcing: self.forcing,
                friction_limit,
                limit,
            });
        }
        Ok(())
    }
}

/// Finds the consistent amplitude a = a*(a) of the single-point problem (4.2, 4.2.3).
///
/// Schemes: [`Scheme::Relaxation`] a ← (a + a*)/2 (Fig. 4.14); [`Scheme::Direct`] a ← a*,
/// with a detected 2-cycle reported as [`IterateError::TwoCycle`] (Fig. 4.13);
/// [`Scheme::Secant`] (default): the root of r(s) = ln a*(e^s) − s, s = ln a, found by
/// expanding a bracket with secant/direct steps of at most a decade, then Illinois false
/// position inside the bracket (the stateful form of the shared rule [`next_estimate`]); it
/// never leaves a sign-change bracket once it has one, so it cannot 2-cycle.
///
/// Stops when |a* − a| ≤ tolerance · a. A zero force gives a = 0 at once.
pub fn solve_point(
    problem: &PointProblem,
    options: &Options,
) -> Result<PointSolution, IterateError> {
    problem.validate()?;
    options.validate()?;
    problem.check_first_harmonic()?;
    let method = options.method;
    let mut history = Vec::new();
    let mut count = 0;
    let mut eval = |a: f64, history: &mut Vec<(f64, f64)>| {
        count += 1;
        let (a_star, lin) = problem.response(a, method)?;
        history.push((a, a_star));
        Ok::<_, IterateError>((a_star, lin))
    };
    let (stick, stick_lin) = eval(0.0, &mut history)?;
    history.clear(); // (0, a*(0)) carries no log-residual; it only seeds the estimate
    if stick == 0.0 {
        return Ok(PointSolution {
            amplitude: 0.0,
            estimate: 0.0,
            linearization: stick_lin,
            linearizations: 1,
            history: vec![(0.0, 0.0)],
        });
    }
    let mut a = options.initial.unwrap_or(stick);
    let mut root = LogRoot::default();
    let mut last_change = f64::INFINITY;
    for _ in 0..options.max_iterations {
        let (a_star, lin) = eval(a, &mut history)?;
        if a_star == 0.0 {
            return Err(IterateError::Singular);
        }
        last_change = (a_star - a).abs() / a;
        if last_change <= options.tolerance {
            return Ok(PointSolution {
                amplitude: a_star,
                estimate: a,
                linearization: lin,
                linearizations: count,
                history,
            });
        }
        a = match options.scheme {
            Scheme::Direct => {
                if let Some((x, y)) = two_cycle(&history, options.tolerance) {
                    return Err(IterateError::TwoCycle { a: x, b: y });
                }
                next_estimate(Scheme::Direct, &history)
            }
            Scheme::Relaxation => next_estimate(Scheme::Relaxation, &history),
            Scheme::Secant => root.next(a.ln(), a_star.ln() - a.ln())?.exp(),
        };
        if !(a.is_finite() && a > 0.0) {
            return Err(IterateError::NoBracket {
                low: root.low().min(a),
                high: root.high().max(a),
            });
        }
    }
    Err(IterateError::MaxIterations {
        iterations: options.max_iterations,
        last_change,
    })
}

/// Direct iteration (a_{k+1} = a*_k) has settled into a 2-cycle: the last three estimates
/// satisfy a_k ≈ a_{k−2} (to [`TWO_CYCLE_MATCH`]) while a_k and a_{k−1} differ by more
/// than the tolerance.
fn two_cycle(history: &[(f64, f64)], tolerance: f64) -> Option<(f64, f64)> {
    let n = history.len();
    if n < 2 {
        return None;
    }
    // Estimates a_{k−2} = history[n−2].0, a_{k−1} = history[n−1].0, a_k = history[n−1].1.
    let (a0, a1, a2) = (history[n - 2].0, history[n - 1].0, history[n - 1].1);
    let settled = (a2 - a0).abs() <= TWO_CYCLE_MATCH * a2;
    let apart = (a2 - a1).abs() > tolerance * a2;
    (settled && apart).then_some((a1, a2))
}

/// The default scheme's root finder on r(s) = ln a*(e^s) − s: bracket expansion, then
/// Illinois false position.
#[derive(Debug, Default)]
struct LogRoot {
    /// Latest point with r > 0 and latest with r < 0.
    pos: Option<(f64, f64)>,
    neg: Option<(f64, f64)>,
    /// Previous point (for the unbracketed secant).
    prev: Option<(f64, f64)>,
    /// Which end the last bracketed step replaced (+1 pos, −1 neg), for the Illinois rule.
    last_side: i8,
    expansions: usize,
    range: Option<(f64, f64)>,
}

impl LogRoot {
    fn low(&self) -> f64 {
        self.range.map_or(f64::NAN, |r| r.0.exp())
    }
    fn high(&self) -> f64 {
        self.range.map_or(f64::NAN, |r| r.1.exp())
    }

    /// Records (s, r) and proposes the next s.
    fn next(&mut self, s: f64, r: f64) -> Result<f64, IterateError> {
        self.range = Some(self.range.map_or((s, s), |(l, h)| (l.min(s), h.max(s))));
        let bracketed = self.pos.is_some() && self.neg.is_some();
        let side: i8 = if r > 0.0 { 1 } else { -1 };
        if side > 0 {
            self.pos = Some((s, r));
        } else {
            self.neg = Some((s, r));
        }
        let prev = self.prev.replace((s, r));
        if let (Some(mut p), Some(mut q)) = (self.pos, self.neg) {
            if bracketed && side == self.last_side {
                // Illinois: the other end was retained twice, halve its residual.
                if side > 0 {
                    q.1 *= 0.5;
                    self.neg = Some(q);
                } else {
                    p.1 *= 0.5;
                    self.pos = Some(p);
                }
            }
            self.last_side = side;
            let (lo, hi) = (p.0.min(q.0), p.0.max(q.0));
            if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(1.0) {
                return Err(IterateError::Jump { at: s.exp() });
            }
            let x = (p.0 * q.1 - q.0 * p.1) / (q.1 - p.1);
            return Ok(if x > lo && x < hi { x } else { 0.5 * (lo + hi) });
        }
        // Unbracketed: move towards the sign of r (r > 0 ⇒ root at larger s, as r → +∞ for
        // s → −∞ where a* → a*(0) > 0), by a secant step when the slope is negative,
        // else by the direct step r; at most a decade per step.
        self.expansions += 1;
        if self.expansions > MAX_EXPANSIONS {
            return Err(IterateError::NoBracket {
                low: self.low(),
                high: self.high(),
            });
        }
        let step = match prev {
            Some((s1, r1)) if s1 != s => {
                let slope = (r - r1) / (s - s1);
                if slope < 0.0 && slope.is_finite() {
                    -r / slope
                } else {
                    r
                }
            }
            _ => r,
        };
        Ok(s + step.clamp(-MAX_LOG_STEP, MAX_LOG_STEP))
    }
}

/// One contact element of a dense system, acting in the direction of its DOFs: between
/// DOF `dof` and DOF `other`, or between `dof` and ground when `other` is None. Its
/// amplitude is |u_dof − u_other| (|u_dof| to ground).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactElement {
    pub contact: Contact,
    pub dof: usize,
    pub other: Option<usize>,
}

/// A small dense linear system with contact elements:
/// (K + K_c(k*) + iω(D + D_c(d*)) − ω²M) u = f, n ≤ ~50 DOF.
#[derive(Debug, Clone, PartialEq)]
pub struct DenseProblem {
    /// Mass matrix M (n × n).
    pub mass: DMatrix<f64>,
    /// Stiffness K without the contacts (n × n).
    pub stiffness: DMatrix<f64>,
    /// Viscous damping D without the contacts (n × n).
    pub damping: DMatrix<f64>,
    /// Complex force amplitudes f (n).
    pub force: DVector<Complex64>,
    /// Angular frequency ω > 0.
    pub omega: f64,
    pub contacts: Vec<ContactElement>,
}

/// The consistent state of a dense problem.
#[derive(Debug, Clone, PartialEq)]
pub struct DenseSolution {
    /// Contact amplitudes a* of the last solve, one per contact element.
    pub amplitudes: Vec<f64>,
    /// The estimates the last linearizations were made for.
    pub estimates: Vec<f64>,
    /// Complex displacement amplitudes u of the last solve.
    pub displacement: DVector<Complex64>,
    pub linearizations: Vec<Linearization>,
    /// Linear solves made (iterations plus finite-difference solves).
    pub solves: usize,
    /// Contact linearizations made, over all contacts.
    pub linearization_count: usize,
    /// Outer iterations (one per full residual evaluation).
    pub iterations: usize,
}

impl DenseProblem {
    fn validate(&self) -> Result<(), IterateError> {
        let n = self.force.len();
        let square = |m: &DMatrix<f64>| m.nrows() == n && m.ncols() == n;
        if !square(&self.mass) || !square(&self.stiffness) || !square(&self.damping) {
            return Err(IterateError::Invalid(
                "M, K, D must be n x n with n = len(f)",
            ));
        }
        if !(self.omega.is_finite() && self.omega > 0.0) {
            return Err(IterateError::Invalid("omega must be finite and > 0"));
        }
        let finite = self
            .mass
            .iter()
            .chain(self.stiffness.iter())
            .chain(self.damping.iter());
        if !finite.clone().all(|x| x.is_finite())
            || !self
                .force
                .iter()
                .all(|z| z.re.is_finite() && z.im.is_finite())
        {
            return Err(IterateError::Invalid("non-finite matrix or force entry"));
        }
        for c in &self.contacts {
            if c.dof >= n || c.other.is_some_and(|j| j >= n || j == c.dof) {
                return Err(IterateError::Invalid(
                    "contact DOF out of range or tied to itself",
                ));
            }
        }
        Ok(())
    }

    /// The linear solve for given contact linearizations: u and the contact amplitudes.
    pub fn solve_linear(
        &self,
        lins: &[Linearization],
    ) -> Result<(DVector<Complex64>, Vec<f64>), IterateError> {
        let w = self.omega;
        let n = self.force.len();
        let mut z = DMatrix::<Complex64>::from_fn(n, n, |i, j| {
            Complex64::new(
                self.stiffness[(i, j)] - w * w * self.mass[(i, j)],
                w * self.damping[(i, j)],
            )
        });
        for (c, lin) in self.contacts.iter().zip(lins) {
            // Spring k* and damper d* between the two DOFs (4.2 per contact, Fig. 4.5).
            let y = Complex64::new(lin.k_star, w * lin.d_star);
            let i = c.dof;
            z[(i, i)] += y;
            if let Some(j) = c.other {
                z[(j, j)] += y;
                z[(i, j)] -= y;
                z[(j, i)] -= y;
            }
        }
        let u = z.lu().solve(&self.force).ok_or(IterateError::Singular)?;
        if !u.iter().all(|v| v.re.is_finite() && v.im.is_finite()) {
            return Err(IterateError::Singular);
        }
        let amps = self
            .contacts
            .iter()
            .map(|c| (u[c.dof] - c.other.map_or(Complex64::new(0.0, 0.0), |j| u[j])).norm())
            .collect();
        Ok((u, amps))
    }
}

/// State of the dense iteration: linearize, solve, and count.
struct DenseEval<'p> {
    problem: &'p DenseProblem,
    method: Method,
    solves: usize,
    lin_count: usize,
    floor: f64,
}

impl DenseEval<'_> {
    fn linearize(&mut self, c: usize, a: f64) -> Result<Linearization, IterateError> {
        self.lin_count += 1;
        let p = self.problem;
        Ok(linearize(&p.contacts[c].contact, a, p.omega, self.method)?)
    }

    fn solve(
        &mut self,
        lins: &[Linearization],
    ) -> Result<(DVector<Complex64>, Vec<f64>), IterateError> {
        self.solves += 1;
        self.problem.solve_linear(lins)
    }

    /// Residual r_c = ln a*_c − ln a_c for estimates a (floored), with everything used.
    fn residual(&mut self, a: &[f64]) -> Result<Residual, IterateError> {
        let lins = (0..a.len())
            .map(|c| self.linearize(c, a[c]))
            .collect::<Result<Vec<_>, _>>()?;
        let (u, a_star) = self.solve(&lins)?;
        let r = self.log_residual(a, &a_star);
        Ok(Residual { lins, u, a_star, r })
    }

    fn log_residual(&self, a: &[f64], a_star: &[f64]) -> DVector<f64> {
        DVector::from_fn(a.len(), |c, _| {
            a_star[c].max(self.floor).ln() - a[c].max(self.floor).ln()
        })
    }
}

struct Residual {
    lins: Vec<Linearization>,
    u: DVector<Complex64>,
    a_star: Vec<f64>,
    r: DVector<f64>,
}

/// Finds consistent contact amplitudes a_c = |u_i − u_j| of a small dense system (4.2.3 for
/// several points at once).
///
/// [`Scheme::Secant`] (default): Newton on s = ln a with a forward-difference Jacobian (one
/// extra linearization and solve per contact: perturbing s_c changes only contact c's k*,
/// d*), steps limited to a decade (or to the largest |r_c|), backtracking on ‖r‖₂; when the Jacobian is singular or
/// backtracking fails, one relaxation step a ← (a + a*)/2 (the scalar rule
/// [`next_estimate`] per contact) and Newton again. [`Scheme::Direct`] and
/// [`Scheme::Relaxation`] apply [`next_estimate`] per contact; Direct reports a 2-cycle.
///
/// Stops when |a*_c − a_c| ≤ tolerance · a_c for every contact. Amplitudes below
/// 1e-14 × the largest stick amplitude are floored there (a contact that does not move).
pub fn solve_dense(
    problem: &DenseProblem,
    options: &Options,
) -> Result<DenseSolution, IterateError> {
    problem.validate()?;
    options.validate()?;
    let nc = problem.contacts.len();
    let mut ev = DenseEval {
        problem,
        method: options.method,
        solves: 0,
        lin_count: 0,
        floor: 0.0,
    };
    let zeros = vec![0.0; nc];
    let stick = ev.residual(&zeros)?;
    let scale = stick.a_star.iter().fold(0.0_f64, |m, &x| m.max(x));
    if nc == 0 || scale == 0.0 {
        return Ok(DenseSolution {
            amplitudes: stick.a_star,
            estimates: zeros,
            displacement: stick.u,
            linearizations: stick.lins,
            solves: ev.solves,
            linearization_count: ev.lin_count,
            iterations: 0,
        });
    }
    ev.floor = AMPLITUDE_FLOOR * scale;
    let mut a: Vec<f64> = match options.initial {
        Some(x) => vec![x; nc],
        None => stick.a_star.iter().map(|&x| x.max(ev.floor)).collect(),
    };
    let mut histories: Vec<Vec<(f64, f64)>> = vec![Vec::new(); nc];
    let mut last_change = f64::INFINITY;
    let mut cur = ev.residual(&a)?;
    for iteration in 1..=options.max_iterations {
        for c in 0..nc {
            histories[c].push((a[c].max(ev.floor), cur.a_star[c].max(ev.floor)));
        }
        last_change = (0..nc)
            .map(|c| (cur.a_star[c].max(ev.floor) - a[c].max(ev.floor)).abs() / a[c].max(ev.floor))
            .fold(0.0, f64::max);
        if last_change <= options.tolerance {
            return Ok(DenseSolution {
                amplitudes: cur.a_star,
                estimates: a,
                displacement: cur.u,
                linearizations: cur.lins,
                solves: ev.solves,
                linearization_count: ev.lin_count,
                iterations: iteration,
            });
        }
        if iteration == options.max_iterations {
            break;
        }
        let scalar = |scheme: Scheme, h: &[Vec<(f64, f64)>]| -> Vec<f64> {
            h.iter().map(|hc| next_estimate(scheme, hc)).collect()
        };
        match options.scheme {
            Scheme::Direct => {
                if let Some((x, y)) = dense_two_cycle(&histories, options.tolerance) {
                    return Err(IterateError::TwoCycle { a: x, b: y });
                }
                a = scalar(Scheme::Direct, &histories);
                cur = ev.residual(&a)?;
            }
            Scheme::Relaxation => {
                a = scalar(Scheme::Relaxation, &histories);
                cur = ev.residual(&a)?;
            }
            Scheme::Secant => match newton_step(&mut ev, &a, &cur)? {
                Some((a_new, next)) => {
                    a = a_new;
                    cur = next;
                }
                None => {
                    a = scalar(Scheme::Relaxation, &histories);
                    cur = ev.residual(&a)?;
                }
            },
        }
    }
    Err(IterateError::MaxIterations {
        iterations: options.max_iterations,
        last_change,
    })
}

/// One damped Newton step on r(s) = 0, s = ln a; None when it cannot make progress.
fn newton_step(
    ev: &mut DenseEval,
    a: &[f64],
    cur: &Residual,
) -> Result<Option<(Vec<f64>, Residual)>, IterateError> {
    let nc = a.len();
    let s: Vec<f64> = a.iter().map(|&x| x.max(ev.floor).ln()).collect();
    let mut jac = DMatrix::<f64>::zeros(nc, nc);
    for c in 0..nc {
        let a_c = (s[c] + FD_STEP).exp();
        let mut lins = cur.lins.clone();
        lins[c] = ev.linearize(c, a_c)?;
        let (_, a_star) = ev.solve(&lins)?;
        let mut a_pert = a.to_vec();
        a_pert[c] = a_c;
        let r = ev.log_residual(&a_pert, &a_star);
        jac.set_column(c, &((r - &cur.r) / FD_STEP));
    }
    let Some(mut step) = jac.lu().solve(&(-&cur.r)) else {
        return Ok(None);
    };
    let biggest = step.amax();
    if !biggest.is_finite() {
        return Ok(None);
    }
    // At most a decade, or as far as the direct update a ← a* would go (a contact that
    // starts at the floor, e.g. one at rest in the stick state by symmetry, may need many).
    let limit = MAX_LOG_STEP.max(cur.r.amax());
    if biggest > limit {
        step *= limit / biggest;
    }
    let norm0 = cur.r.norm();
    let mut lambda = 1.0;
    for _ in 0..8 {
        let a_new: Vec<f64> = (0..nc).map(|c| (s[c] + lambda * step[c]).exp()).collect();
        let next = ev.residual(&a_new)?;
        // Armijo-type sufficient decrease of ‖r‖₂ (coefficient 1e-4, halving λ).
        if next.r.norm() <= (1.0 - 1e-4 * lambda) * norm0 {
            return Ok(Some((a_new, next)));
        }
        lambda *= 0.5;
    }
    Ok(None)
}

/// [`two_cycle`] for every contact at once: each has settled (a_k ≈ a_{k−2}) and at least
/// one still swings by more than the tolerance; reports the contact with the largest swing.
fn dense_two_cycle(histories: &[Vec<(f64, f64)>], tolerance: f64) -> Option<(f64, f64)> {
    let mut worst: Option<(f64, f64, f64)> = None;
    for h in histories {
        let n = h.len();
        if n < 2 {
            return None;
        }
        let (a0, a1, a2) = (h[n - 2].0, h[n - 1].0, h[n - 1].1);
        if (a2 - a0).abs() > TWO_CYCLE_MATCH * a2 {
            return None;
        }
        let swing = (a2 - a1).abs() / a2;
        if swing > tolerance && worst.map_or(true, |w| swing > w.0) {
            worst = Some((swing, a1, a2));
        }
    }
    worst.map(|w| (w.1, w.2))
}

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
mod solve_tests {
    use super::*;
    use crate::hysteresis::Rule;
    use crate::law::TangentialLaw;

    /// The block of 4.2 / Appendix C in N, mm, s, t (model.md §8), stick case F̂ = 0.5 N.
    fn block() -> PointProblem {
        PointProblem {
            contact: Contact {
                law: TangentialLaw::Mindlin,
                rule: Rule::Thesis,
                mu: 0.3,
                normal_force: 2.0,
                k_t0: 1282.7,
            },
            mass: 0.002,
            forcing: 0.5,
            omega: 1.3,
            ground_stiffness: 0.0,
            ground_damping: 0.0,
        }
    }

    fn opts(scheme: Scheme, tolerance: f64) -> Options {
        Options {
            scheme,
            tolerance,
            ..Options::default()
        }
    }

    /// d ln a* / d ln a at a (central difference, step 1e-5 in ln a: error ~1e-10).
    fn log_slope(p: &PointProblem, a: f64) -> f64 {
        let h: f64 = 1e-5;
        let up = p.response(a * h.exp(), Method::default()).unwrap().0;
        let down = p.response(a * (-h).exp(), Method::default()).unwrap().0;
        (up.ln() - down.ln()) / (2.0 * h)
    }

    #[test]
    fn default_and_relaxation_reach_the_same_amplitude_default_with_fewer_linearizations() {
        let p = block();
        let reference = solve_point(&p, &opts(Scheme::Secant, 1e-14))
            .unwrap()
            .amplitude;
        let tol = 1e-10;
        let secant = solve_point(&p, &opts(Scheme::Secant, tol)).unwrap();
        let relaxed = solve_point(&p, &opts(Scheme::Relaxation, tol)).unwrap();
        // A stop at |a* − a| ≤ tol·a leaves a within tol·a/|1 − g'| of the fixed point,
        // g' = d a*/d a there (a* − a_fix ≈ g'(a − a_fix)); the returned a* is within
        // |g'| times that. Allow twice the bound for the linearized slope.
        let g = log_slope(&p, reference);
        assert!(g > 0.0 && g < 1.0, "g' = {g}");
        let bound = 2.0 * tol * reference / (1.0 - g);
        for (name, s) in [("secant", &secant), ("relaxation", &relaxed)] {
            let err = (s.amplitude - reference).abs();
            assert!(err <= bound, "{name}: error {err:e} > {bound:e}");
        }
        // Measured: 6 linearizations (default) vs 39 (relaxation, rate (1 + g')/2 per step).
        assert!(secant.linearizations <= 8, "{}", secant.linearizations);
        assert!(relaxed.linearizations >= 30, "{}", relaxed.linearizations);
        assert!(4 * secant.linearizations < relaxed.linearizations);
        // The initial estimate only changes the path: from 1e-6 and 1e6 times the answer
        // the bracket expansion (a decade per step at most) still lands on it.
        for factor in [1e-6, 1e6] {
            let o = Options {
                initial: Some(factor * reference),
                ..opts(Scheme::Secant, tol)
            };
            let far = solve_point(&p, &o).unwrap();
            assert!(
                (far.amplitude - reference).abs() <= bound,
                "{factor}: {far:?}"
            );
            assert!(far.linearizations <= 20, "{factor}: {}", far.linearizations);
        }
        // The amplitude is the response of (4.2) with the returned linearization.
        let lin = secant.linearization;
        let z = (lin.k_star - p.mass * p.omega.powi(2)).hypot(p.omega * lin.d_star);
        assert!((p.forcing / z - secant.amplitude).abs() <= 1e-15 * secant.amplitude);
    }

    #[test]
    fn direct_two_cycles_near_the_contact_resonance_where_the_default_converges() {
        // The block driven at ω = 700 rad/s with F̂ = 0.2 N, below its stick resonance
        // √(k_T0/m) = 801 rad/s: softening makes a* fall steeply with a (Fig. 4.13's
        // situation; measured g' = d ln a*/d ln a = −2.13 at the fixed point).
        let p = PointProblem {
            omega: 700.0,
            forcing: 0.2,
            ..block()
        };
        let err = solve_point(&p, &opts(Scheme::Direct, 1e-8)).unwrap_err();
        let IterateError::TwoCycle { a, b } = err else {
            panic!("{err:?}");
        };
        assert!((a - b).abs() > 0.5 * a.max(b), "a real cycle: {a:e} {b:e}");
        let s = solve_point(&p, &opts(Scheme::Secant, 1e-10)).unwrap();
        assert!(s.linearizations <= 15, "{}", s.linearizations);
        // Fixed point check and why Direct fails: slope d a*/d a < −1 there.
        let (again, _) = p.response(s.amplitude, Method::default()).unwrap();
        assert!((again - s.amplitude).abs() <= 1e-9 * s.amplitude);
        let g = log_slope(&p, s.amplitude);
        assert!(g < -1.0, "g' = {g}");
        // The cycle straddles the fixed point.
        assert!(a.min(b) < s.amplitude && s.amplitude < a.max(b));
        // Relaxation converges there too (|1 + g'|/2 = 0.57 < 1), slowly: measured 36 vs 7.
        let r = solve_point(&p, &opts(Scheme::Relaxation, 1e-10)).unwrap();
        assert!((r.amplitude - s.amplitude).abs() <= 1e-8 * s.amplitude);
        assert!(r.linearizations > 3 * s.linearizations);
        // At ω = 750 rad/s, g' = −3.16 < −3: even the relaxation overshoots forever, the
        // default still converges.
        let q = PointProblem { omega: 750.0, ..p };
        assert!(matches!(
            solve_point(&q, &opts(Scheme::Relaxation, 1e-10)),
            Err(IterateError::MaxIterations { .. })
        ));
        let s = solve_point(&q, &opts(Scheme::Secant, 1e-10)).unwrap();
        let (again, _) = q.response(s.amplitude, Method::default()).unwrap();
        assert!((again - s.amplitude).abs() <= 1e-9 * s.amplitude);
        assert!(log_slope(&q, s.amplitude) < -3.0);
    }

    #[test]
    fn sliding_block_below_four_over_pi_has_no_first_harmonic_solution() {
        let p = PointProblem {
            forcing: 0.75,
            ..block()
        };
        for scheme in [Scheme::Secant, Scheme::Relaxation, Scheme::Direct] {
            let err = solve_point(&p, &opts(scheme, 1e-8)).unwrap_err();
            let IterateError::NoFirstHarmonicSolution {
                forcing,
                friction_limit,
                limit,
            } = err
            else {
                panic!("{err:?}");
            };
            assert_eq!(forcing, 0.75);
            assert!((friction_limit - 0.6).abs() < 1e-15);
            assert!((limit - 0.763_943_726_841_097_6).abs() < 1e-12);
        }
        // The spurious root the a-priori test guards against: r = ln a* − ln a changes sign
        // at a few δ* (δ* = 7.0e-4 mm), where only the friction harmonic balances F̂.
        let delta = 1.5 * 0.6 / 1282.7;
        let r = |a: f64| p.response(a, Method::default()).unwrap().0.ln() - a.ln();
        assert!(r(delta) > 0.0 && r(100.0 * delta) < 0.0);
        // Above 4μF_N/π the sliding mass has a first-harmonic solution near
        // a = √(F̂² − (4μF_N/π)²)/(mω²) (k* → 0, ωd* a → 4μF_N/π); the measured 1 % excess
        // comes from k* and the finite-δ* part of d* at a/δ* ~ 1e5.
        let q = PointProblem {
            forcing: 0.8,
            ..block()
        };
        let s = solve_point(&q, &Options::default()).unwrap();
        let limit = 4.0 * 0.6 / std::f64::consts::PI;
        let rigid = (0.8f64.powi(2) - limit * limit).sqrt() / (q.mass * q.omega.powi(2));
        assert!(
            ((s.amplitude - rigid) / rigid).abs() < 0.02,
            "{} vs {rigid}",
            s.amplitude
        );
        assert_eq!(s.linearization.regime, crate::linearize::Regime::Sliding);
        // With a ground spring the contact is not the only load path: no a-priori verdict.
        let g = PointProblem {
            ground_stiffness: 10.0,
            ..p
        };
        assert!(solve_point(&g, &Options::default()).is_ok());
    }

    #[test]
    fn open_contact_is_the_linear_oscillator_and_undamped_resonance_is_singular() {
        let mut p = block();
        p.contact.normal_force = 0.0; // open: k* = d* = 0
        p.ground_stiffness = 3.0;
        p.ground_damping = 0.1;
        let s = solve_point(&p, &Options::default()).unwrap();
        let exact = p.forcing / (3.0 - p.mass * 1.69f64).hypot(0.13);
        assert!((s.amplitude - exact).abs() <= 1e-15 * exact);
        assert_eq!(s.linearizations, 2); // stick solve + one check
        p.ground_damping = 0.0;
        p.ground_stiffness = p.mass * p.omega * p.omega;
        assert_eq!(
            solve_point(&p, &Options::default()).unwrap_err(),
            IterateError::Singular
        );
        p.forcing = f64::NAN;
        assert!(matches!(
            solve_point(&p, &Options::default()),
            Err(IterateError::Invalid(_))
        ));
    }

    #[test]
    fn bracket_search_reports_no_bracket_and_jumps() {
        // r > 0 everywhere (a* = 2a): no root.
        let mut root = LogRoot::default();
        let mut s = 0.0;
        let err = loop {
            match root.next(s, std::f64::consts::LN_2) {
                Ok(x) => s = x,
                Err(e) => break e,
            }
        };
        assert!(matches!(err, IterateError::NoBracket { .. }), "{err:?}");
        // r jumps from +1 to −1 at s = 0.3: the bracket shrinks onto the jump.
        let mut root = LogRoot::default();
        let mut s = -2.0;
        let err = (0..400)
            .find_map(|_| match root.next(s, if s < 0.3 { 1.0 } else { -1.0 }) {
                Ok(x) => {
                    s = x;
                    None
                }
                Err(e) => Some(e),
            })
            .unwrap();
        let IterateError::Jump { at } = err else {
            panic!("{err:?}");
        };
        assert!((at.ln() - 0.3).abs() < 1e-14);
    }

    /// The block as a 1-DOF dense problem (contact to ground), with ground spring/damper.
    fn dense_block(p: &PointProblem) -> DenseProblem {
        DenseProblem {
            mass: DMatrix::from_element(1, 1, p.mass),
            stiffness: DMatrix::from_element(1, 1, p.ground_stiffness),
            damping: DMatrix::from_element(1, 1, p.ground_damping),
            force: DVector::from_element(1, Complex64::new(0.0, -p.forcing)),
            omega: p.omega,
            contacts: vec![ContactElement {
                contact: p.contact,
                dof: 0,
                other: None,
            }],
        }
    }

    #[test]
    fn dense_one_dof_equals_solve_point() {
        let tol = 1e-11;
        for p in [
            block(),
            PointProblem {
                omega: 700.0,
                forcing: 0.2,
                ..block()
            },
            PointProblem {
                forcing: 0.7,
                ground_stiffness: 0.5,
                ground_damping: 1e-3,
                ..block()
            },
        ] {
            let point = solve_point(&p, &opts(Scheme::Secant, tol)).unwrap();
            for scheme in [Scheme::Secant, Scheme::Relaxation] {
                // The sliding case with a weak ground spring has g' ≈ 0.86: relaxation
                // contracts by (1 + g')/2 ≈ 0.93 per step and needs ~350 steps.
                let o = Options {
                    max_iterations: 5000,
                    ..opts(scheme, tol)
                };
                let dense = solve_dense(&dense_block(&p), &o).unwrap();
                // Both stop within tol·a/|1 − g'| of the same fixed point (|g'| ≤ 2.2 and
                // 1/|1 − g'| ≤ 7 here).
                let diff = (dense.amplitudes[0] - point.amplitude).abs() / point.amplitude;
                assert!(diff < 20.0 * tol, "{scheme:?} ω={}: {diff:e}", p.omega);
                assert!((dense.displacement[0].norm() - dense.amplitudes[0]).abs() < 1e-18);
            }
        }
    }

    #[test]
    fn dense_three_dof_chain_converges_to_a_consistent_state() {
        // ground –c0– m0 –k– m1 –k– m2, contact c1 between m0 and m2 (a shear lap), c2 to
        // ground at m2; force on m1. Units N, mm, s, t.
        let contact = |normal_force: f64, k_t0: f64| Contact {
            law: TangentialLaw::Mindlin,
            rule: Rule::Thesis,
            mu: 0.3,
            normal_force,
            k_t0,
        };
        let k = 400.0;
        let stiffness = DMatrix::from_row_slice(3, 3, &[k, -k, 0.0, -k, 2.0 * k, -k, 0.0, -k, k]);
        let p = DenseProblem {
            mass: DMatrix::from_diagonal(&DVector::from_vec(vec![0.002, 0.001, 0.002])),
            damping: stiffness.scale(1e-5),
            stiffness,
            force: DVector::from_vec(vec![
                Complex64::new(0.0, 0.0),
                Complex64::new(0.0, -0.8),
                Complex64::new(0.0, 0.0),
            ]),
            omega: 200.0,
            contacts: vec![
                ContactElement {
                    contact: contact(2.0, 1000.0),
                    dof: 0,
                    other: None,
                },
                ContactElement {
                    contact: contact(0.5, 600.0),
                    dof: 0,
                    other: Some(2),
                },
                ContactElement {
                    contact: contact(1.5, 800.0),
                    dof: 2,
                    other: None,
                },
            ],
        };
        let tol = 1e-10;
        let newton = solve_dense(&p, &opts(Scheme::Secant, tol)).unwrap();
        let relaxed = solve_dense(&p, &opts(Scheme::Relaxation, tol)).unwrap();
        // Measured: 5 iterations (quadratic: changes 0.16, 1.3e-2, 4.9e-5, 3.7e-10) vs 46.
        assert!(newton.iterations <= 6, "{}", newton.iterations);
        assert!(relaxed.iterations > newton.iterations);
        // Consistency: linearizing at the returned amplitudes reproduces them.
        let lins: Vec<_> = p
            .contacts
            .iter()
            .zip(&newton.amplitudes)
            .map(|(c, &a)| linearize(&c.contact, a, p.omega, Method::default()).unwrap())
            .collect();
        let (_, again) = p.solve_linear(&lins).unwrap();
        for (c, (&a, &recomputed)) in newton.amplitudes.iter().zip(&again).enumerate() {
            assert!(
                (recomputed - a).abs() <= 1e-8 * a,
                "contact {c}: {recomputed} vs {a}"
            );
            // The relaxation agrees within its stopping bound (|g'| < 1 here, measured).
            assert!((relaxed.amplitudes[c] - a).abs() <= 1e-8 * a);
            // Nonlinear: every contact softened by more than 1 % (measured 1.6–13 %).
            let lin = newton.linearizations[c];
            assert!(lin.k_star < 0.99 * p.contacts[c].contact.k_t0, "{lin:?}");
        }
    }

    #[test]
    fn dense_input_errors_are_reported() {
        let mut p = dense_block(&block());
        p.contacts[0].dof = 1;
        assert!(matches!(
            solve_dense(&p, &Options::default()),
            Err(IterateError::Invalid(_))
        ));
        let mut p = dense_block(&block());
        p.contacts[0].other = Some(0);
        assert!(matches!(
            solve_dense(&p, &Options::default()),
            Err(IterateError::Invalid(_))
        ));
    }
}
