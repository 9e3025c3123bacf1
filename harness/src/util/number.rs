//! Numbers in messages and tables: a fixed number of significant digits, never the
//! 301 digits `{}` prints for 1e300; in CSV files every digit that round-trips.

/// Significant digits of printed numbers: 31718.04 Hz, 1.234568e-6 t.
const DIGITS: usize = 7;

/// `v` with `DIGITS` significant digits: fixed-point from 1e-3 to 1e7, else scientific.
pub fn sig(v: f64) -> String {
    sig_n(v, DIGITS)
}

/// `v` as every CSV writes a number: the shortest decimal (scientific) that reads back
/// to the same double, so a table loses no digit (−0 is written 0).
pub fn exact(v: f64) -> String {
    format!("{:e}", v + 0.0)
}

/// `v` with `digits` (≥ 1) significant digits, as [`sig`].
pub fn sig_n(v: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor() as i32;
    if (-3..7).contains(&mag) {
        let decimals = (digits as i32 - 1 - mag).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.*e}", digits - 1)
    }
}

/// `n` with its noun: `1 frequency`, `3 frequencies` (`one` for one, `many` otherwise).
pub fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

#[cfg(test)]
mod tests {
    use super::sig;

    #[test]
    fn huge_and_tiny_numbers_print_in_a_few_digits() {
        assert_eq!(sig(1e300), "1.000000e300");
        assert_eq!(sig(1e-310), "1.000000e-310");
        assert_eq!(sig(31718.038906265498), "31718.04");
        assert_eq!(sig(0.0), "0");
        assert_eq!(sig(f64::INFINITY), "inf");
        assert_eq!(super::sig_n(209.1622, 2), "209");
        assert_eq!(super::sig_n(0.6712165, 2), "0.67");
    }

    #[test]
    fn exact_numbers_read_back_to_the_same_double() {
        for v in [
            0.1,
            1.0 / 3.0,
            1e300,
            5e-324,
            -2.5e-7,
            f64::MAX,
            1157.4056009483932,
        ] {
            let text = super::exact(v);
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                v.to_bits(),
                "{text}"
            );
        }
        assert_eq!(super::exact(-0.0), "0e0");
        assert_eq!(super::exact(0.1), "1e-1");
    }
}
