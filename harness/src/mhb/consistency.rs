//! Consistency of the first-order method's element amplitudes: the amplitudes a that
//! the linearized response reproduces, a = g(a) (thesis §4.2.3: the linearization at
//! A must give back A). Solved by Newton on r(a) = a − g(a) with the caller's ∂g/∂a or a
//! forward-difference Jacobian (n + 1 evaluations of g per iteration), safeguarded
//! by backtracking on the weighted residual and, where the Newton direction does not
//! lower it, a relaxed fixed-point step (the thesis's relaxation). Amplitudes stay ≥ 0.
//!
//! The thesis's relaxation alone stalls where g is not a contraction (on a Jenkins
//! chain driven through its stick–slip transition, halving the factor down to 4e-16 left
//! the mismatch at 0.155); Newton converges there in a few iterations.

use nalgebra::{DMatrix, DVector};

/// The floor of the mismatch's scale, relative to the largest amplitude: below it an
/// element's amplitude counts absolutely (tolerance × 1e-4: about the round-off of the
/// largest).
pub const FLOOR: f64 = 1e-4;

/// A mismatch below this that no Newton step lowers, or lowers by less than half, is
/// g's round-off: converged (Newton gains far more per step where g is exact).
pub const ROUND_OFF: f64 = 1e-9;

/// The method, as named in messages.
pub const METHOD: &str = "Newton iteration (backtracking)";

/// A converged fixed point.
#[derive(Debug, Clone)]
pub struct Converged {
    pub x: Vec<f64>,
    pub iterations: usize,
}

/// The iteration ended without reaching the tolerance.
#[derive(Debug, Clone, Copy)]
pub struct Stalled {
    /// Largest relative mismatch |a − g(a)| / max(|a|, |g(a)|) at the end.
    pub mismatch: f64,
    pub iterations: usize,
}

/// Componentwise scale of the mismatch: the larger of |a| and |g(a)|, floored at
/// [`FLOOR`] of the largest amplitude of the same group (`groups[i]`; the entries of one
/// kind, e.g. amplitudes apart from a frequency): an element that hardly moves must not
/// dominate, and its g carries round-off of order 1e-16 of the largest (a symmetric
/// structure's elements that do not move at all), which the tolerance must be able to
/// pass.
fn weights(x: &[f64], g: &[f64], groups: &[usize]) -> Vec<f64> {
    // The largest |a|, |g(a)| per group, in one pass.
    let mut big = vec![0.0f64; groups.iter().max().map_or(0, |&k| k + 1)];
    for ((a, b), &k) in x.iter().zip(g).zip(groups) {
        big[k] = big[k].max(a.abs()).max(b.abs());
    }
    x.iter()
        .zip(g)
        .zip(groups)
        .map(|((a, b), &k)| {
            let floor = (FLOOR * big[k]).max(f64::MIN_POSITIVE);
            1.0 / a.abs().max(b.abs()).max(floor)
        })
        .collect()
}

fn merit(x: &[f64], g: &[f64], w: &[f64]) -> f64 {
    x.iter()
        .zip(g)
        .zip(w)
        .fold(0.0f64, |m, ((a, b), w)| m.max(((a - b) * w).abs()))
}

/// ∂g/∂a at a (n × n), when the caller has it.
pub type Derivative<'a, E> = &'a mut dyn FnMut(&[f64]) -> Result<DMatrix<f64>, E>;

/// Solves a = g(a) from `x0` to the relative mismatch `tol` with a forward-difference
/// Jacobian. `Err` passes g's errors on; `Ok(Err(_))` is an honest "not converged".
pub fn solve<E>(
    x0: &[f64],
    g: impl FnMut(&[f64]) -> Result<Vec<f64>, E>,
    tol: f64,
    max_iter: usize,
) -> Result<Result<Converged, Stalled>, E> {
    solve_with(x0, g, None, &vec![0; x0.len()], tol, max_iter)
}

/// As [`solve`], with ∂g/∂a from `derivative` when given, and the entries' groups for
/// the mismatch's scale (`weights`; one group: all zeros).
pub fn solve_with<E>(
    x0: &[f64],
    mut g: impl FnMut(&[f64]) -> Result<Vec<f64>, E>,
    mut derivative: Option<Derivative<'_, E>>,
    groups: &[usize],
    tol: f64,
    max_iter: usize,
) -> Result<Result<Converged, Stalled>, E> {
    let n = x0.len();
    let mut x: Vec<f64> = x0.iter().map(|v| v.abs()).collect();
    let mut gx = g(&x)?;
    let mut w = weights(&x, &gx, groups);
    let mut m = merit(&x, &gx, &w);
    for it in 0..max_iter {
        if m <= tol {
            return Ok(Ok(Converged { x, iterations: it }));
        }
        // J = I − ∂g/∂a, the caller's or by forward differences.
        let jac = match derivative.as_mut() {
            Some(d) => DMatrix::<f64>::identity(n, n) - d(&x)?,
            None => {
                let mut jac = DMatrix::<f64>::identity(n, n);
                for j in 0..n {
                    let h = 1e-7 * x[j].abs().max(1.0 / w[j]);
                    let mut xp = x.clone();
                    xp[j] += h;
                    let gp = g(&xp)?;
                    for i in 0..n {
                        jac[(i, j)] -= (gp[i] - gx[i]) / h;
                    }
                }
                jac
            }
        };
        let r = DVector::from_iterator(n, x.iter().zip(&gx).map(|(a, b)| a - b));
        let step = jac.lu().solve(&r);
        let mut accepted = false;
        if let Some(dx) = step.filter(|d| d.iter().all(|v| v.is_finite())) {
            let mut lambda = 1.0;
            for _ in 0..12 {
                // Positivity: a component may shrink to a tenth per step, not below.
                let trial: Vec<f64> = x
                    .iter()
                    .zip(dx.iter())
                    .map(|(a, d)| (a - lambda * d).max(0.1 * a))
                    .collect();
                let gt = g(&trial)?;
                if merit(&trial, &gt, &weights(&trial, &gt, groups)) < (1.0 - 1e-4 * lambda) * m {
                    x = trial;
                    gx = gt;
                    accepted = true;
                    break;
                }
                lambda *= 0.5;
            }
        }
        if !accepted && m <= ROUND_OFF {
            // No Newton step lowers a mismatch this small: g's own round-off (the
            // linear solve's, near a resonance) is reached; the fixed point is as exact
            // as g can be evaluated.
            return Ok(Ok(Converged { x, iterations: it }));
        }
        if !accepted {
            // Fixed-point steps a + c(g − a), c = 1, ½, ¼: the first that lowers the
            // mismatch, else c = ¼ regardless (the thesis's relaxation).
            for c in [1.0, 0.5, 0.25] {
                let trial: Vec<f64> = x.iter().zip(&gx).map(|(a, b)| a + c * (b - a)).collect();
                let gt = g(&trial)?;
                if c == 0.25 || merit(&trial, &gt, &weights(&trial, &gt, groups)) < m {
                    x = trial;
                    gx = gt;
                    break;
                }
            }
        }
        w = weights(&x, &gx, groups);
        let before = m;
        m = merit(&x, &gx, &w);
        if m <= ROUND_OFF && m > 0.5 * before {
            // Newton no longer gains: round-off as above.
            return Ok(Ok(Converged {
                x,
                iterations: it + 1,
            }));
        }
    }
    if m <= tol {
        return Ok(Ok(Converged {
            x,
            iterations: max_iter,
        }));
    }
    Ok(Err(Stalled {
        mismatch: m,
        iterations: max_iter,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newton_solves_a_map_relaxation_cannot() {
        // g(a) = 3 − 2a has the fixed point 1 and slope −2: plain and relaxed
        // iterations with factor ≥ 2/3 diverge; Newton lands in one step.
        let r = solve(&[0.5], |a| Ok::<_, ()>(vec![3.0 - 2.0 * a[0]]), 1e-12, 20)
            .unwrap()
            .unwrap();
        assert!((r.x[0] - 1.0).abs() < 1e-12 && r.iterations <= 3, "{r:?}");
    }

    #[test]
    fn a_map_without_fixed_point_is_reported() {
        // g(a) = a + 1 + a²: no fixed point; the mismatch stays finite and is named.
        let r = solve(
            &[1.0],
            |a| Ok::<_, ()>(vec![a[0] + 1.0 + a[0] * a[0]]),
            1e-12,
            30,
        )
        .unwrap()
        .unwrap_err();
        assert!(r.mismatch.is_finite() && r.mismatch > 1e-3, "{r:?}");
    }
}
