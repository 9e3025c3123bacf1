//! Quadrature rules: Gauss–Legendre (from the `gauss-quad` crate, cached per n) and the
//! thesis's composite Simpson rule.

use std::num::NonZeroUsize;
use std::sync::OnceLock;

use gauss_quad::GaussLegendre;

/// Largest Gauss–Legendre order offered.
pub const MAX_GAUSS_POINTS: usize = 128;

static TABLES: [OnceLock<Vec<(f64, f64)>>; MAX_GAUSS_POINTS + 1] =
    [const { OnceLock::new() }; MAX_GAUSS_POINTS + 1];

/// Gauss–Legendre nodes and weights on [−1, 1] for 1 ≤ n ≤ [`MAX_GAUSS_POINTS`], nodes in
/// descending order. Computed once per n by `gauss-quad` (Bogaert's iteration-free
/// asymptotic formulas: weights to a few 1e-16 relative up to n = 128, where Newton on
/// the three-term recurrence reached only 3e-13), then shared by all threads.
pub fn gauss_legendre(n: usize) -> &'static [(f64, f64)] {
    assert!(
        (1..=MAX_GAUSS_POINTS).contains(&n),
        "Gauss order checked by the caller"
    );
    TABLES[n].get_or_init(|| {
        let order = NonZeroUsize::new(n).expect("n ≥ 1 asserted above");
        let mut rule = GaussLegendre::new(order)
            .into_node_weight_pairs()
            .into_vec();
        rule.sort_by(|a, b| b.0.total_cmp(&a.0));
        rule
    })
}

/// ∫_a^b f by n-point Gauss–Legendre.
pub fn gauss(n: usize, a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    half * gauss_legendre(n)
        .iter()
        .map(|&(x, w)| w * f(mid + half * x))
        .sum::<f64>()
}

/// ∫_a^b f by composite Simpson with `n` intervals (`simpson_rule`) or n-point Gauss.
pub fn simpson_or_gauss(
    simpson_rule: bool,
    n: usize,
    a: f64,
    b: f64,
    f: impl FnMut(f64) -> f64,
) -> f64 {
    if simpson_rule {
        simpson(n, a, b, f)
    } else {
        gauss(n, a, b, f)
    }
}

/// ∫_a^b f by the composite Simpson rule with `intervals` (even, ≥ 2) sub-intervals.
pub fn simpson(intervals: usize, a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
    let h = (b - a) / intervals as f64;
    let mut acc = f(a) + f(b);
    for i in 1..intervals {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        acc += w * f(a + h * i as f64);
    }
    acc * h / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_is_exact_for_polynomials_of_degree_2n_minus_1() {
        for n in [1, 2, 5, 12, 40, MAX_GAUSS_POINTS] {
            // ∫_{-1}^{1} x^{2n−2} = 2/(2n−1), exact for an n-point rule; plus an odd term.
            let deg = 2 * n - 2;
            let got = gauss(n, -1.0, 1.0, |x| {
                x.powi(deg as i32) + x.powi(deg as i32 + 1)
            });
            assert!(
                (got - 2.0 / (deg as f64 + 1.0)).abs() < 1e-13,
                "n = {n}: {got}"
            );
        }
    }

    /// Nodes and weights against 40-digit references (Newton on P_n in 40-digit arithmetic):
    /// nodes to 2ε absolute on [−1, 1] (what the integral feels: f′·δx), weights to 1e-15
    /// relative, at the largest order too.
    #[test]
    fn nodes_and_weights_are_at_double_precision() {
        // 25 digits each, rounded to the nearest double when parsed.
        let reference: [(usize, usize, &str, &str); 6] = [
            (
                12,
                0,
                "0.9815606342467192506905491",
                "0.04717533638651182719461596",
            ),
            (
                12,
                1,
                "0.9041172563704748566784659",
                "0.1069393259953184309602547",
            ),
            (
                12,
                5,
                "0.1252334085114689154724414",
                "0.2491470458134027850005624",
            ),
            (
                128,
                0,
                "0.9998248879471319144736081",
                "0.0004493809602920903763942922",
            ),
            (
                128,
                1,
                "0.9990774599773758950119878",
                "0.001045812679340348779312852",
            ),
            (
                128,
                63,
                "0.01222369896061576419805212",
                "0.02444618019626251821132585",
            ),
        ];
        for (n, i, x, w) in reference {
            let (x, w): (f64, f64) = (x.parse().unwrap(), w.parse().unwrap());
            let (gx, gw) = gauss_legendre(n)[i];
            assert!(
                (gx - x).abs() <= 2.0 * f64::EPSILON,
                "n = {n}, node {i}: {gx} vs {x}"
            );
            assert!(
                (gw - w).abs() <= 1e-15 * w,
                "n = {n}, weight {i}: {gw} vs {w}"
            );
        }
    }

    #[test]
    fn simpson_error_is_fourth_order() {
        // ∫₀^π sin = 2; Simpson's error ≈ (π⁵/180) h⁴/… halves by 16 per halving of h.
        let e1 = (simpson(16, 0.0, std::f64::consts::PI, f64::sin) - 2.0).abs();
        let e2 = (simpson(32, 0.0, std::f64::consts::PI, f64::sin) - 2.0).abs();
        assert!((e1 / e2 - 16.0).abs() < 0.2, "ratio {}", e1 / e2);
    }
}
