//! Quadrature rules: Gauss–Legendre (nodes by Newton on P_n, cached per n) and the
//! thesis's composite Simpson rule.

use std::sync::OnceLock;

/// Largest Gauss–Legendre order offered.
pub const MAX_GAUSS_POINTS: usize = 128;

static TABLES: [OnceLock<Vec<(f64, f64)>>; MAX_GAUSS_POINTS + 1] =
    [const { OnceLock::new() }; MAX_GAUSS_POINTS + 1];

/// Gauss–Legendre nodes and weights on [−1, 1] for 1 ≤ n ≤ [`MAX_GAUSS_POINTS`]. Computed
/// once per n (Newton on the three-term recurrence, |Δx| < 1e-15), then shared by all threads.
pub fn gauss_legendre(n: usize) -> &'static [(f64, f64)] {
    assert!(
        (1..=MAX_GAUSS_POINTS).contains(&n),
        "Gauss order checked by the caller"
    );
    TABLES[n].get_or_init(|| {
        (0..n)
            .map(|i| {
                // Tricomi's initial guess, then Newton.
                let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
                for _ in 0..100 {
                    let (p, d) = legendre(n, x);
                    let dx = p / d;
                    x -= dx;
                    if dx.abs() < 1e-16 {
                        break;
                    }
                }
                let (_, d) = legendre(n, x);
                (x, 2.0 / ((1.0 - x * x) * d * d))
            })
            .collect()
    })
}

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=n {
        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    if n == 0 {
        return (1.0, 0.0);
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
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

    #[test]
    fn simpson_error_is_fourth_order() {
        // ∫₀^π sin = 2; Simpson's error ≈ (π⁵/180) h⁴/… halves by 16 per halving of h.
        let e1 = (simpson(16, 0.0, std::f64::consts::PI, f64::sin) - 2.0).abs();
        let e2 = (simpson(32, 0.0, std::f64::consts::PI, f64::sin) - 2.0).abs();
        assert!((e1 / e2 - 16.0).abs() < 0.2, "ratio {}", e1 / e2);
    }
}
