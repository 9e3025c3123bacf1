//! Graded grid lines of a box axis: element sizes in geometric progression, small at
//! one end, the other, or both, so a mesh can be fine where a field varies steeply (the
//! edge of a contact patch) and coarse elsewhere.

/// Where an axis's smallest elements are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Toward {
    /// At the axis's smallest coordinate.
    Min,
    /// At its largest coordinate.
    Max,
    /// At both ends, the largest elements in the middle.
    Both,
}

/// Grading of one axis: `ratio` = largest / smallest element (1 = uniform), neighbouring
/// elements differ by a constant factor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grading {
    pub ratio: f64,
    pub toward: Toward,
}

impl Grading {
    /// Equal elements.
    pub const UNIFORM: Grading = Grading {
        ratio: 1.0,
        toward: Toward::Both,
    };

    /// Whether `ratio` is usable (finite, ≥ 1).
    pub fn is_valid(&self) -> bool {
        self.ratio.is_finite() && self.ratio >= 1.0
    }

    /// Relative sizes of the `n` elements (the smallest is 1).
    fn sizes(&self, n: usize) -> Vec<f64> {
        let steps = match self.toward {
            Toward::Min | Toward::Max => n.saturating_sub(1),
            Toward::Both => n.saturating_sub(1) / 2,
        };
        if steps == 0 || self.ratio == 1.0 {
            return vec![1.0; n];
        }
        let q = self.ratio.powf(1.0 / steps as f64);
        (0..n)
            .map(|j| {
                let e = match self.toward {
                    Toward::Min => j,
                    Toward::Max => n - 1 - j,
                    Toward::Both => j.min(n - 1 - j),
                };
                q.powi(e as i32)
            })
            .collect()
    }

    /// The `n + 1` grid lines of `n` elements as fractions of the axis: 0 first, exactly
    /// 1 last, increasing.
    pub fn fractions(&self, n: usize) -> Vec<f64> {
        let sizes = self.sizes(n);
        let total: f64 = sizes.iter().sum();
        let mut out = Vec::with_capacity(n + 1);
        let mut acc = 0.0;
        out.push(0.0);
        for s in &sizes[..n.saturating_sub(1)] {
            acc += s;
            out.push(acc / total);
        }
        out.push(1.0);
        out
    }

    /// The smallest element of `n` as a fraction of the axis.
    pub fn smallest_fraction(&self, n: usize) -> f64 {
        let sizes = self.sizes(n);
        1.0 / sizes.iter().sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steps(g: Grading, n: usize) -> Vec<f64> {
        g.fractions(n).windows(2).map(|w| w[1] - w[0]).collect()
    }

    #[test]
    fn uniform_grading_gives_equal_elements() {
        for s in steps(Grading::UNIFORM, 7) {
            assert!((s - 1.0 / 7.0).abs() < 1e-15);
        }
    }

    /// Largest/smallest is the ratio, neighbours differ by one factor, the ends are
    /// where asked; round-off only (1e-12).
    #[test]
    fn graded_elements_grow_geometrically_to_the_ratio() {
        for (toward, n) in [
            (Toward::Min, 6),
            (Toward::Max, 6),
            (Toward::Both, 9),
            (Toward::Both, 8),
        ] {
            let g = Grading {
                ratio: 20.0,
                toward,
            };
            let s = steps(g, n);
            let (lo, hi) = s
                .iter()
                .fold((f64::MAX, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
            assert!(
                (hi / lo - 20.0).abs() < 1e-12,
                "{toward:?} {n}: {}",
                hi / lo
            );
            assert!((lo - g.smallest_fraction(n)).abs() < 1e-15);
            assert!((s.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            let smallest = |i: usize| (s[i] - lo).abs() < 1e-15;
            match toward {
                Toward::Min => assert!(smallest(0)),
                Toward::Max => assert!(smallest(n - 1)),
                Toward::Both => assert!(smallest(0) && smallest(n - 1)),
            }
            for w in s.windows(3) {
                // One factor between neighbours on each monotone stretch.
                let (a, b) = (w[1] / w[0], w[2] / w[1]);
                assert!(
                    (a - b).abs() < 1e-12
                        || (a * b - 1.0).abs() < 1e-12
                        || (a - 1.0).abs() < 1e-12
                        || (b - 1.0).abs() < 1e-12,
                    "{toward:?} {n}: {a} {b}"
                );
            }
            let f = g.fractions(n);
            assert_eq!((f[0], f[n]), (0.0, 1.0));
        }
        // One element: nothing to grade.
        assert_eq!(
            Grading {
                ratio: 5.0,
                toward: Toward::Min
            }
            .fractions(1),
            vec![0.0, 1.0]
        );
    }
}
