//! The thesis's single-point problem (4.2): a mass on one contact point, solved for the
//! consistent amplitude with the chosen scheme.

use super::*;

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
pub(super) struct LogRoot {
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
    pub(super) fn next(&mut self, s: f64, r: f64) -> Result<f64, IterateError> {
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
