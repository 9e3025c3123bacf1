//! Amplitude consistency (4.2.3, Fig. 4.12–4.14): k*, d* depend on the amplitude a they
//! are linearized for, and the linear solve with them returns an amplitude a*; the
//! consistent amplitude is the fixed point a = a*(a).
//!
//! [`next_estimate`] is the one update rule shared by the single-point/dense solvers here and
//! the UEXTERNALDB-side [`crate::store`]: from the history of (estimate, computed) pairs it
//! proposes the next estimate.

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
