//! Axis ticks of the plots: labels of log-axis ticks and log ranges wide enough to
//! carry labelled ticks.

/// `[lo, hi]` widened about its geometric middle to span at least a decade.
pub fn at_least_a_decade(lo: f64, hi: f64) -> (f64, f64) {
    if hi >= 10.0 * lo {
        return (lo, hi);
    }
    // √lo·√hi: lo·hi underflows for amplitudes near 1e-300.
    let mid = lo.sqrt() * hi.sqrt();
    (mid / 10f64.sqrt(), mid * 10f64.sqrt())
}

/// `[lo, hi]` (> 0) widened to a decade at least ([`at_least_a_decade`]) and then out to
/// the power of ten below (plotters' log ticks start at a power of ten: from 2e-3 the
/// first were 0.01) and the nearest 1, 2 or 5 times a power of ten above, so the axis's
/// first and last ticks carry labels ([`log_tick`]).
pub fn labelled_log_range(lo: f64, hi: f64) -> (f64, f64) {
    let (lo, hi) = at_least_a_decade(lo, hi);
    let steps = |e: f64| [1.0, 2.0, 5.0, 10.0].map(|m| m * 10f64.powf(e));
    let down = steps(lo.log10().floor())
        .into_iter()
        .rev()
        .step_by(3)
        .find(|&v| v <= lo * (1.0 + 1e-12))
        .unwrap_or(lo);
    let up = steps(hi.log10().floor())
        .into_iter()
        .find(|&v| v >= hi * (1.0 - 1e-12))
        .unwrap_or(hi);
    (down, up)
}

/// The axis range to give plotters for [`labelled_log_range`]: its ends nudged outward by
/// 1e-9 relative, because plotters' log key points start at 10^⌈ln lo / ln 10⌉ (for
/// lo = 1e-3 that quotient is −2.9999999999999996: the first decade lost its ticks) and
/// stop where repeated ×10 passes hi (0.001·10·10 > 0.1: the top tick lost).
pub fn plotted_log_range(lo: f64, hi: f64) -> std::ops::Range<f64> {
    let (lo, hi) = labelled_log_range(lo, hi);
    lo * (1.0 - 1e-9)..hi * (1.0 + 1e-9)
}

/// Decades a log axis may span and still carry a tick at every 1…9 times a power of
/// ten; wider ones carry the powers of ten only.
const FINE_DECADES: f64 = 3.0;
/// Most powers of ten a log axis carries besides its top one (wider axes take every
/// second, third, …).
const MAX_DECADE_TICKS: usize = 12;

/// The ticks of a log axis over `range` (from [`plotted_log_range`]): each 1…9 times a
/// power of ten inside it where it spans at most [`FINE_DECADES`], else the powers of ten
/// (at most [`MAX_DECADE_TICKS`] and the top one); each computed as m·10^k and present once. Given to
/// plotters as the axis's key points, because its own log key points may hold two values
/// within round-off of each other, and both were labelled (a bold double "0.1").
pub fn log_ticks(range: &std::ops::Range<f64>) -> Vec<f64> {
    let (lo, hi) = (range.start, range.end);
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return Vec::new();
    }
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let fine = hi <= lo * 10f64.powf(FINE_DECADES) * (1.0 + 1e-9);
    let mantissas: &[f64] = if fine {
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]
    } else {
        &[1.0]
    };
    let inside: Vec<f64> = (k0..=k1)
        .flat_map(|k| mantissas.iter().map(move |m| m * 10f64.powi(k)))
        .filter(|v| (lo..=hi).contains(v))
        .collect();
    // Wide axes: every `every`-th power of ten counted from the first inside the range,
    // and the last one, so both ends of the axis keep a labelled tick.
    let every = if fine {
        1
    } else {
        inside
            .len()
            .saturating_sub(1)
            .div_ceil(MAX_DECADE_TICKS)
            .max(1)
    };
    let last = inside.last().copied();
    let mut ticks: Vec<f64> = inside.into_iter().step_by(every).collect();
    if ticks.last().copied() != last {
        ticks.extend(last);
    }
    ticks
}

/// Label of a log-axis tick at `v`: only 1, 2 and 5 times a power of ten are labelled
/// (plain digits from 0.001 to 9999, else `2e-5`); the other ticks get no label, so no
/// label is printed twice and none crowds its neighbour.
pub fn log_tick(v: f64) -> String {
    if !(v > 0.0 && v.is_finite()) {
        return String::new();
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    let (m, e) = match m.round() {
        r if (m - r).abs() > 1e-6 * m => return String::new(),
        10.0 => (1.0, e + 1.0),
        r => (r, e),
    };
    if ![1.0, 2.0, 5.0].contains(&m) {
        return String::new();
    }
    let e = e as i32;
    if (-3..=3).contains(&e) {
        let decimals = (-e).max(0) as usize;
        format!("{:.decimals$}", m * 10f64.powi(e))
    } else {
        format!("{m}e{e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_one_two_five_are_labelled_and_each_once() {
        assert_eq!(log_tick(1.0), "1");
        assert_eq!(log_tick(0.999_999_999_999), "1");
        assert_eq!(log_tick(2e-3), "0.002");
        assert_eq!(log_tick(5000.0), "5000");
        assert_eq!(log_tick(2e-5), "2e-5");
        assert_eq!(log_tick(1e12), "1e12");
        for v in [0.9, 3.0, 7e-4, 1.5, 0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(log_tick(v), "", "{v}");
        }
        // A decade's ticks 1..9 × 10^k label 1, 2, 5 once each.
        let labels: Vec<String> = (1..=9).map(|m| log_tick(m as f64 * 1e-1)).collect();
        let shown: Vec<&String> = labels.iter().filter(|l| !l.is_empty()).collect();
        assert_eq!(shown, ["0.1", "0.2", "0.5"]);
    }

    /// plotters' key points of the plotted range include both ends where they are powers
    /// of ten (for 1e-3…0.1 they had neither the first decade nor the top tick).
    #[test]
    fn plotted_log_ranges_carry_ticks_at_both_ends() {
        use plotters::coord::combinators::{IntoLogRange, LogCoord};
        use plotters::coord::ranged1d::Ranged;
        // Ranges ending on powers of ten, where the rounding of ln(lo)/ln 10 bit.
        let cases = [
            (1.2e-3, 0.09),
            (1e-3, 1.0),
            (1.5e-7, 8e-3),
            (1.5e-12, 8e-9),
            (2.53e-3, 0.047),
            (6e-5, 3e-3),
        ];
        for (lo, hi) in cases {
            let (a, b) = labelled_log_range(lo, hi);
            let coord = LogCoord::from(plotted_log_range(lo, hi).log_scale());
            let keys: Vec<f64> = coord.key_points(30);
            let near = |x: f64| keys.iter().any(|k| (k / x - 1.0).abs() < 1e-6);
            assert!(near(a) && near(b), "{lo} {hi}: ends {a} {b}, keys {keys:?}");
        }
    }

    /// No label is drawn twice: plotters' own key points of a plotted range hold two
    /// values within round-off of each other (both labelled "0.1" draw a bold label);
    /// [`log_ticks`] holds each once, both ends included.
    #[test]
    fn plotted_log_ranges_label_each_tick_once() {
        use plotters::coord::combinators::{IntoLogRange, LogCoord};
        use plotters::coord::ranged1d::Ranged;
        let mut twice = false;
        for (lo, hi) in [
            (1.8e-3, 0.088),
            (1.2e-3, 0.09),
            (1e-3, 1.0),
            (2.53e-3, 0.047),
        ] {
            for n in [10, 30] {
                let coord = LogCoord::from(plotted_log_range(lo, hi).log_scale());
                let plotters_own: Vec<String> = (coord.key_points(n).into_iter())
                    .map(log_tick)
                    .filter(|l| !l.is_empty())
                    .collect();
                twice |= plotters_own.windows(2).any(|w| w[0] == w[1]);
                let labels: Vec<String> = (log_ticks(&plotted_log_range(lo, hi)).into_iter())
                    .map(log_tick)
                    .filter(|l| !l.is_empty())
                    .collect();
                let mut once = labels.clone();
                once.dedup();
                assert_eq!(labels, once, "{lo} {hi} ({n} labels)");
                let (a, b) = labelled_log_range(lo, hi);
                assert_eq!(labels.first(), Some(&log_tick(a)), "{lo} {hi}");
                assert_eq!(labels.last(), Some(&log_tick(b)), "{lo} {hi}");
            }
        }
        assert!(twice, "plotters' own key points no longer repeat a label");
        // Wide ranges: powers of ten, at most a dozen.
        let wide = log_ticks(&plotted_log_range(1e-300, 1e300));
        assert!(wide.len() <= 13 && wide.len() >= 10, "{wide:?}");
        // Both ends of a 13-decade axis (the block-stick ladder's errors) are ticks.
        let range = plotted_log_range(1e-13, 1.0);
        let ends = log_ticks(&range);
        assert_eq!(ends.len(), 8, "{ends:?}");
        assert!(
            (ends[0] / 1e-13 - 1.0).abs() < 1e-12 && ends[7] == 1.0,
            "{ends:?}"
        );
        assert_eq!(log_ticks(&plotted_log_range(1e-5, 1.0)).len(), 6);
        // Up to three decades: every 1…9 × 10^k (1e-4 … 0.01: 19 ticks).
        assert_eq!(log_ticks(&plotted_log_range(1e-4, 1e-2)).len(), 19);
    }

    #[test]
    fn log_ranges_end_on_labelled_ticks() {
        assert_eq!(labelled_log_range(1.3e-7, 6.8e-3), (1e-7, 1e-2));
        let (lo, hi) = labelled_log_range(0.064, 2.6);
        assert!(
            (lo - 0.01).abs() < 1e-15 && (hi - 5.0).abs() < 1e-12,
            "{lo} {hi}"
        );
        let (lo, hi) = labelled_log_range(1e-3, 1.0);
        assert!((lo - 1e-3).abs() < 1e-18 && (hi - 1.0).abs() < 1e-15);
        for (lo, hi) in [(3e-300, 4e-300), (0.7, 0.9), (123.0, 9e7)] {
            let (a, b) = labelled_log_range(lo, hi);
            assert!(
                a <= lo && b >= hi && b >= 10.0 * a * (1.0 - 1e-12),
                "{lo} {hi}: {a} {b}"
            );
            assert!(
                !log_tick(a).is_empty() && !log_tick(b).is_empty(),
                "{a} {b}"
            );
        }
    }

    #[test]
    fn a_narrow_range_is_widened_to_a_decade() {
        let (lo, hi) = at_least_a_decade(4.0, 5.0);
        assert!((hi / lo - 10.0).abs() < 1e-12);
        assert!((lo * hi - 20.0).abs() < 1e-12);
        let (lo, hi) = at_least_a_decade(3e-300, 4e-300);
        assert!(lo > 0.0 && (hi / lo - 10.0).abs() < 1e-9, "{lo:e} {hi:e}");
        assert_eq!(at_least_a_decade(1.0, 100.0), (1.0, 100.0));
    }
}

/// Label of a linear-axis tick at `v`: at most four significant digits, plain from 0.001
/// to 9999 (trailing zeros dropped), else as `2.5e-5`.
pub fn linear_tick(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{}", if v.is_finite() { 0.0 } else { v });
    }
    let trim = |s: String| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if (1e-3..1e4).contains(&v.abs()) {
        let decimals = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        trim(format!("{v:.decimals$}"))
    } else {
        let s = format!("{v:.3e}");
        let (m, e) = s.split_once('e').expect("exponent");
        format!("{}e{e}", trim(m.to_string()))
    }
}

/// [`linear_tick`] of a tick on an axis from `lo` to `hi`: a tick within 1e-9 of the
/// span from zero is zero (the axis's own round-off, e.g. −6.8e-21 for 0).
pub fn linear_tick_on(v: f64, (lo, hi): (f64, f64)) -> String {
    linear_tick(if v.abs() <= 1e-9 * (hi - lo).abs() {
        0.0
    } else {
        v
    })
}

#[cfg(test)]
mod linear_tick_tests {
    use super::{linear_tick, linear_tick_on};

    #[test]
    fn round_off_at_zero_is_labelled_zero() {
        assert_eq!(linear_tick_on(-6.776e-21, (-4e-5, 4e-5)), "0");
        assert_eq!(linear_tick_on(2e-5, (-4e-5, 4e-5)), "2e-5");
        assert_eq!(linear_tick_on(1e-12, (0.0, 1e-9)), "1e-12");
    }

    #[test]
    fn ticks_carry_four_significant_digits_at_most() {
        let cases = [
            (0.0, "0"),
            (0.2, "0.2"),
            (-0.05, "-0.05"),
            (1234.5678, "1235"),
            (0.123456, "0.1235"),
            (2.5e-5, "2.5e-5"),
            (-3.0e7, "-3e7"),
        ];
        for (v, want) in cases {
            assert_eq!(linear_tick(v), want, "{v}");
        }
    }
}
