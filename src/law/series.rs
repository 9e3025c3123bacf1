//! Cancellation-free evaluation of the binomial remainders that appear in Mindlin's law
//! for small normalized slip u = s/δ* (where 1 − (1 − u)^p loses all digits).

/// Below this u the power series is used; above it the direct formula loses at most
/// ~1e-16/u² relative, i.e. < 1e-13 at u = 0.05.
pub const SERIES_BELOW: f64 = 0.05;

/// Terms of the series: the k-th binomial term of (1−u)^p is O(u^k/k^{p+1}); at u ≤ 0.05,
/// 16 terms leave < 1e-21 relative.
const TERMS: usize = 16;

/// Σ_{k ≥ k0} c_k u^k where (1 − u)^p = Σ c_k u^k; all c_k for k > p share one sign, so the
/// sum is accurate to rounding.
pub fn binomial_tail(p: f64, u: f64, k0: usize) -> f64 {
    let mut coeff = 1.0; // c_0
    let mut power = 1.0; // u^k
    let mut sum = 0.0;
    for k in 0..TERMS {
        if k >= k0 {
            sum += coeff * power;
        }
        // c_{k+1} = c_k · (p − k)/(k + 1) · (−1)
        coeff *= -(p - k as f64) / (k as f64 + 1.0);
        power *= u;
    }
    sum
}

/// 1 − (1 − u)^p for 0 ≤ u ≤ 1, accurate to rounding for every u.
pub fn one_minus_pow(p: f64, u: f64) -> f64 {
    if u >= 1.0 {
        return 1.0;
    }
    -(p * (-u).ln_1p()).exp_m1()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tail_matches_direct_formula_where_both_are_accurate() {
        // At u = 0.05 the direct form of (1−u)^1.5 − 1 + 1.5u has ≈ 1e-13 relative error.
        let u: f64 = 0.05;
        let direct = (1.0 - u).powf(1.5) - 1.0 + 1.5 * u;
        let series = binomial_tail(1.5, u, 2);
        assert!((direct - series).abs() <= 1e-12 * series.abs());
    }

    #[test]
    fn tail_is_exact_for_tiny_u() {
        // Leading term 3/8 u² dominates; next 1/16 u³.
        let u = 1e-9;
        let expect = 0.375 * u * u + u * u * u / 16.0;
        assert!((binomial_tail(1.5, u, 2) - expect).abs() <= 1e-15 * expect);
    }

    #[test]
    fn one_minus_pow_keeps_digits_at_tiny_u() {
        let u = 1e-14;
        assert!((one_minus_pow(1.5, u) - 1.5e-14).abs() <= 1e-28);
    }
}
