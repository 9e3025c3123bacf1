//! The frequencies of a `[sweep]`: its range with the `refine` bands, spaced as
//! `spacing` and `bias` say, and divided at eigenfrequencies for
//! `interval = "eigenfrequency"`.

use super::study::{biased, Interval, Spacing, SweepSpec};

impl SweepSpec {
    /// The sweep's frequencies (1/time) with `interval = "eigenfrequency"`: the range and
    /// each band divided at the `eigen` frequencies inside them (Abaqus's
    /// INTERVAL=EIGENFREQUENCY), `count` points with `bias` in every piece, ends included;
    /// ascending, duplicates removed. With `interval = "range"` the same as
    /// [`SweepSpec::frequencies`].
    pub fn frequencies_between(&self, eigen: &[f64]) -> Vec<f64> {
        let s = self;
        if s.interval == Interval::Range {
            return self.frequencies();
        }
        let mut f = Vec::new();
        let lines = std::iter::once((s.f_min, s.f_max, s.count, s.bias, s.spacing)).chain(
            s.refine
                .iter()
                .map(|b| (b.f_min, b.f_max, b.count, b.bias, Spacing::Linear)),
        );
        for (lo, hi, count, bias, spacing) in lines {
            if count == 1 || lo == hi {
                f.push(lo);
                continue;
            }
            let mut ends = vec![lo];
            ends.extend(eigen.iter().copied().filter(|&e| e > lo && e < hi));
            ends.push(hi);
            ends.sort_by(f64::total_cmp);
            for w in ends.windows(2) {
                f.extend((0..count).map(|i| {
                    let t = biased(i as f64 / (count - 1) as f64, bias);
                    match spacing {
                        Spacing::Linear => w[0] + t * (w[1] - w[0]),
                        Spacing::Log => log_spaced(w[0], w[1], t),
                    }
                }));
            }
        }
        f.sort_by(f64::total_cmp);
        f.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs());
        f
    }

    /// The sweep's frequencies (1/time), ascending, duplicates (within 1e-12
    /// relative) removed; with `interval = "eigenfrequency"` the division of the whole
    /// range, before the eigenfrequencies are known ([`SweepSpec::frequencies_between`]).
    pub fn frequencies(&self) -> Vec<f64> {
        let s = self;
        let mut f: Vec<f64> = if s.count == 1 {
            vec![s.f_min]
        } else {
            (0..s.count)
                .map(|i| {
                    let t = biased(i as f64 / (s.count - 1) as f64, s.bias);
                    match s.spacing {
                        Spacing::Linear => s.f_min + t * (s.f_max - s.f_min),
                        Spacing::Log => log_spaced(s.f_min, s.f_max, t),
                    }
                })
                .collect()
        };
        for b in &s.refine {
            f.extend((0..b.count).map(|i| {
                let t = biased(i as f64 / (b.count.max(2) - 1) as f64, b.bias);
                b.f_min + (b.f_max - b.f_min) * t
            }));
        }
        f.sort_by(f64::total_cmp);
        f.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * b.abs());
        f
    }
}

/// The point at fraction `t` of a logarithmic scale from `lo` to `hi` (> 0): lo (hi/lo)^t,
/// in log space where hi/lo overflows or underflows.
fn log_spaced(lo: f64, hi: f64, t: f64) -> f64 {
    let ratio = hi / lo;
    if ratio.is_finite() && ratio > 0.0 {
        lo * ratio.powf(t)
    } else {
        (lo.ln() + t * (hi.ln() - lo.ln())).exp()
    }
}
