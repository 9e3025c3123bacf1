//! Products and quotients of doubles over the whole double range: a value m·2^e with
//! 0.5 ≤ |m| < 1 and an exponent that cannot overflow, so that μF_N·δ*, A/δ* or
//! A_hys/(πωA²) keep every digit when a factor or an intermediate product lies beyond
//! the double range (F_N = 1e308, A = 1e-300, a subnormal δ*). Each product or quotient
//! rounds its mantissa as an f64 operation does; [`Wide::to_f64`] rounds only when the
//! result is not a normal double (to ±∞, or to a subnormal/zero).

use std::ops::{Div, Mul};

/// m·2^e, m = 0 or 0.5 ≤ |m| < 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wide {
    m: f64,
    e: i64,
}

/// Exponent bits of an f64.
const EXP_MASK: u64 = 0x7ff << 52;

impl Wide {
    /// `x` exactly; `x` must be finite.
    pub fn new(x: f64) -> Self {
        debug_assert!(x.is_finite());
        let (m, e) = frexp(x);
        Self { m, e }
    }

    /// Whether the value is 0.
    pub fn is_zero(self) -> bool {
        self.m == 0.0
    }

    /// The nearest double (one rounding): ±∞ beyond the largest double, subnormal or ±0
    /// below the smallest normal one.
    pub fn to_f64(self) -> f64 {
        if self.m == 0.0 {
            return 0.0;
        }
        if self.e > 1024 {
            return self.m.signum() * f64::INFINITY;
        }
        if self.e < -1100 {
            // |m·2^e| < 2^-1100, far below half the smallest subnormal 2^-1075.
            return self.m.signum() * 0.0;
        }
        let e = self.e as i32;
        if e >= -1021 {
            // m·2^e = (2m)·2^(e−1): exact while normal; only the overflow to ∞ rounds.
            (2.0 * self.m) * pow2(e - 1)
        } else {
            // First step exact (the result stays normal), the second rounds once.
            (self.m * pow2(e + 1022)) * pow2(-1022)
        }
    }
}

impl Wide {
    /// The sum of non-negative values, rounded as an f64 sum of the values scaled to the
    /// largest one (terms below its rounding vanish, as they would in f64).
    pub fn sum_non_negative(values: &[Wide]) -> Wide {
        let Some(top) = values.iter().filter(|v| !v.is_zero()).map(|v| v.e).max() else {
            return Wide::new(0.0);
        };
        let scaled: f64 = values
            .iter()
            .map(|v| {
                debug_assert!(v.m >= 0.0);
                Wide {
                    m: v.m,
                    e: v.e - top,
                }
                .to_f64()
            })
            .sum();
        let (m, e) = frexp(scaled);
        Wide { m, e: e + top }
    }
}

impl From<f64> for Wide {
    fn from(x: f64) -> Self {
        Wide::new(x)
    }
}

impl Mul for Wide {
    type Output = Wide;
    fn mul(self, o: Wide) -> Wide {
        // 0.25 ≤ |m₁m₂| < 1: the product of two 53-bit mantissas rounds once, as an f64 product.
        let (m, e) = frexp(self.m * o.m);
        Wide {
            m,
            e: if m == 0.0 { 0 } else { self.e + o.e + e },
        }
    }
}

impl Mul<f64> for Wide {
    type Output = Wide;
    fn mul(self, o: f64) -> Wide {
        self * Wide::new(o)
    }
}

impl Div for Wide {
    type Output = Wide;
    /// `o` must not be 0.
    fn div(self, o: Wide) -> Wide {
        debug_assert!(!o.is_zero());
        let (m, e) = frexp(self.m / o.m);
        Wide {
            m,
            e: if m == 0.0 { 0 } else { self.e - o.e + e },
        }
    }
}

impl Div<f64> for Wide {
    type Output = Wide;
    fn div(self, o: f64) -> Wide {
        self / Wide::new(o)
    }
}

/// 2^k for −1022 ≤ k ≤ 1023, exactly.
fn pow2(k: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&k));
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// (m, e) with x = m·2^e, 0.5 ≤ |m| < 1 (m = 0, e = 0 for x = 0); subnormals included.
fn frexp(x: f64) -> (f64, i64) {
    if x == 0.0 {
        return (0.0, 0);
    }
    let bits = x.to_bits();
    let biased = ((bits & EXP_MASK) >> 52) as i64;
    if biased == 0 {
        // Subnormal: scale into the normal range first (exact).
        let (m, e) = frexp(x * pow2(64));
        return (m, e - 64);
    }
    let m = f64::from_bits((bits & !EXP_MASK) | (1022 << 52));
    (m, biased - 1022)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_every_kind_of_double() {
        for x in [
            1.0,
            -3.5,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            2.2e-308,
            1e-310,
            0.1,
            1e300,
        ] {
            assert_eq!(Wide::new(x).to_f64(), x, "{x:e}");
        }
        assert_eq!(Wide::new(0.0).to_f64(), 0.0);
    }

    #[test]
    fn products_beyond_the_range_keep_their_digits() {
        let big = Wide::new(1e300) * Wide::new(1e300);
        assert_eq!((big / Wide::new(1e300)).to_f64(), 1e300);
        assert_eq!(big.to_f64(), f64::INFINITY);
        let tiny = Wide::new(1e-300) * Wide::new(1e-300);
        assert_eq!(tiny.to_f64(), 0.0);
        assert_eq!((tiny * 1e300).to_f64(), 1e-300);
        // A subnormal divisor keeps its exact value (not a rounded quotient).
        let q = Wide::new(3.0) / Wide::new(1e-310);
        assert_eq!((q * 1e-310).to_f64(), 3.0);
        // Into the subnormal range: the f64 product's value (here no double rounding).
        let x = Wide::new(1.234_567_890_123e-200) * Wide::new(3.3e-110);
        assert_eq!(x.to_f64(), 1.234_567_890_123e-200 * 3.3e-110);
        assert_eq!((Wide::new(f64::MAX) * 0.5 * 2.0).to_f64(), f64::MAX);
        assert_eq!((Wide::new(-2.0) * 4.0).to_f64(), -8.0);
    }

    #[test]
    fn sums_keep_the_largest_terms() {
        let w = |x: f64| Wide::new(x);
        let huge = Wide::sum_non_negative(&[w(1e300) * w(1e300), w(1e300) * w(1e300), w(1.0)]);
        assert_eq!((huge / w(1e300)).to_f64(), 2e300);
        let tiny = Wide::sum_non_negative(&[w(5e-324) * 0.16, w(5e-324) * w(5e-324)]);
        assert!(!tiny.is_zero());
        let back = (tiny * w(1e300) * w(1e30)).to_f64();
        assert!(
            (back / (5e-324 * 0.16e300 * 1e30) - 1.0).abs() < 1e-15,
            "{back}"
        );
        assert!(Wide::sum_non_negative(&[w(0.0), w(0.0)]).is_zero());
        assert_eq!(Wide::sum_non_negative(&[w(0.5), w(0.25)]).to_f64(), 0.75);
    }
}
