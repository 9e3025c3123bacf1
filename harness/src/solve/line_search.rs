//! Line search along a Newton direction d on the slope g(s) = R(u + s d) · d of the
//! energy along d (R the residual K u + f_c(u) − f, the energy's gradient): Newton's
//! full step is kept when the slope there has fallen to `SLOPE_RATIO` of its start,
//! otherwise the zero of the slope is bracketed and found by regula falsi (Illinois).
//!
//! Contact with a penalty law is piecewise linear in u and its energy convex (½ k_N h²
//! on the closed part), so g is monotone and piecewise linear along d: the search lands
//! on the energy's minimum along d (the active set that d crosses is sorted out inside
//! one Newton step). Backtracking on the merit ‖R‖ instead rejects steps that close
//! many points at once (‖R‖ first grows): the knife's graded mesh took 19 Newton
//! iterations that way and takes 12 with this search.

/// Slope ratio |g(s)| ≤ this × |g(0)| that ends the search (Abaqus' line-search
/// tolerance is of this order; the Newton iterations, not the search, give the accuracy).
pub const SLOPE_RATIO: f64 = 0.25;
/// Most slope evaluations after the full step.
pub const MAX_EVALUATIONS: usize = 12;

/// A step length and what was evaluated there.
#[derive(Debug)]
pub struct Step<T> {
    pub length: f64,
    pub value: T,
}

/// Step length along d, from g(0) = `slope0` and `eval(s)` = (what to keep, g(s)).
/// Not a descent direction (g(0) ≥ 0, possible when friction makes the tangent
/// unsymmetric) or still descending at s = 1: the full step. Otherwise the zero of g
/// in (0, 1] to [`SLOPE_RATIO`], or after [`MAX_EVALUATIONS`] the last point before it
/// (g < 0 there: the energy is lower than at s = 0), or the bracket's far end when no
/// such point was found.
pub fn search<T, E>(
    slope0: f64,
    mut eval: impl FnMut(f64) -> Result<(T, f64), E>,
) -> Result<Step<T>, E> {
    let (full, g1) = eval(1.0)?;
    let descending = slope0 < 0.0;
    if !descending || g1 <= 0.0 || g1.abs() <= SLOPE_RATIO * slope0.abs() {
        return Ok(Step {
            length: 1.0,
            value: full,
        });
    }
    // Bracket [a, b] with g(a) < 0 < g(b); `previous_high` the high end before b.
    let (mut a, mut ga, mut low) = (0.0, slope0, None);
    let (mut b, mut gb, mut high) = (1.0, g1, full);
    let mut previous_high: Option<(f64, f64)> = None;
    // Bracket widths: initially and after each trial.
    let mut widths = vec![1.0];
    for _ in 0..MAX_EVALUATIONS {
        let s = next_trial((a, ga), (b, gb), previous_high, &widths);
        let (value, g) = eval(s)?;
        if g.abs() <= SLOPE_RATIO * slope0.abs() {
            return Ok(Step { length: s, value });
        }
        if g < 0.0 {
            (a, ga, low) = (s, g, Some(value));
        } else {
            previous_high = Some((b, gb));
            (b, gb, high) = (s, g, value);
        }
        widths.push(b - a);
    }
    Ok(match low {
        Some(value) => Step { length: a, value },
        None => Step {
            length: b,
            value: high,
        },
    })
}

/// Next trial inside the bracket (a, g_a < 0), (b, g_b > 0). The slope is piecewise
/// linear (a kink where a point closes or opens), so the secant through the two high
/// points nearest the zero is exact once both lie on the zero's piece; else regula
/// falsi. Bisection when the candidate is not inside the bracket or the bracket did not
/// halve over the last two trials (a kink far from the secant's guess).
fn next_trial(
    (a, ga): (f64, f64),
    (b, gb): (f64, f64),
    previous_high: Option<(f64, f64)>,
    widths: &[f64],
) -> f64 {
    let secant = |(s0, g0): (f64, f64), (s1, g1): (f64, f64)| s1 - g1 * (s1 - s0) / (g1 - g0);
    let candidate = match previous_high {
        Some(p) if p.1 > gb => secant(p, (b, gb)),
        _ => secant((a, ga), (b, gb)),
    };
    let margin = 1e-6 * (b - a);
    let inside = candidate > a + margin && candidate < b - margin;
    let halved = match widths {
        [.., two_ago, _, now] => *now <= 0.5 * two_ago,
        _ => true,
    };
    if inside && halved {
        candidate
    } else {
        0.5 * (a + b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(slope: impl Fn(f64) -> f64, g0: f64) -> (f64, usize) {
        let mut calls = 0;
        let step = search::<(), ()>(g0, |s| {
            calls += 1;
            Ok(((), slope(s)))
        })
        .unwrap();
        (step.length, calls)
    }

    #[test]
    fn full_step_on_a_quadratic_energy() {
        // Newton on a quadratic: g(s) = g0 (1 − s), zero at s = 1: one evaluation.
        assert_eq!(run(|s| -2.0 * (1.0 - s), -2.0), (1.0, 1));
    }

    #[test]
    fn lands_on_the_kink_of_a_piecewise_linear_slope() {
        // A penalty contact closing at s = 0.1 along d: slope −1 before, rising with
        // k_N/k = 1e4 after; the minimum is at s* = 0.1 + 1e-4. The search ends where
        // |g| ≤ SLOPE_RATIO·|g(0)|, i.e. within 0.25/1e4 of s* (closed form).
        let g = |s: f64| {
            if s < 0.1 {
                -1.0
            } else {
                -1.0 + 1e4 * (s - 0.1)
            }
        };
        let (s, calls) = run(g, -1.0);
        let exact = 0.1 + 1e-4;
        assert!((s - exact).abs() <= SLOPE_RATIO / 1e4, "{s} {calls}");
        assert!(g(s).abs() <= SLOPE_RATIO, "{}", g(s));
        assert!(calls <= MAX_EVALUATIONS + 1, "{calls}");
    }

    #[test]
    fn ascent_direction_and_still_descending_take_the_full_step() {
        assert_eq!(run(|_| 5.0, 1.0), (1.0, 1));
        assert_eq!(run(|_| -0.9, -1.0), (1.0, 1));
    }

    #[test]
    fn keeps_a_point_of_lower_energy_when_the_search_runs_out() {
        // A step function slope (zero never reached): the last point with g < 0.
        let (s, _) = run(|s| if s < 0.3 { -1.0 } else { 1.0 }, -1.0);
        assert!(s < 0.3 && s > 0.29, "{s}");
    }
}
