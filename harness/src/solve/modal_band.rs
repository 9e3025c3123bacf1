//! All modes of K φ = λ M φ below a frequency limit. The Lanczos run of
//! [`lowest_modes`] finds the p lowest pairs (shift-invert about a shift at or below the
//! spectrum, so the lowest converge first): p starts at the minimum count and doubles
//! until the p-th frequency reaches the limit (then every mode below the limit is among
//! the p found), the DOF count or a cap.

use crate::fe::csc::Csc;
use crate::solve::modal::{lowest_modes, ModalError, ModalOptions, Modes};

/// What [`modes_below`] found.
#[derive(Debug, Clone)]
pub struct BandModes {
    /// The modes below the limit, at least `min_count` of them (fewer only if the
    /// system has fewer DOFs), ascending.
    pub modes: Modes,
    /// True if the limit was reached: every mode below it is in `modes`. False if the
    /// cap stopped the search first (`modes` then holds the cap's count).
    pub complete: bool,
}

/// The modes with f = √λ / 2π below `f_limit` (1/time), at least `min_count`, at most
/// `max_count`; `opts.n_modes` is ignored. A limit that is not a positive finite
/// number asks for `min_count` modes.
pub fn modes_below(
    k: &Csc<f64>,
    m: &Csc<f64>,
    f_limit: f64,
    min_count: usize,
    max_count: usize,
    opts: &ModalOptions,
) -> Result<BandModes, ModalError> {
    let n = k.n();
    let min_count = min_count.clamp(1, n);
    let max_count = max_count.clamp(min_count, n);
    let limited = f_limit.is_finite() && f_limit > 0.0;
    let mut p = min_count;
    loop {
        let modes = lowest_modes(
            k,
            m,
            &ModalOptions {
                n_modes: p,
                ..*opts
            },
        )?;
        let f = modes.frequencies_hz();
        let reached = !limited || f[p - 1] >= f_limit || p == n;
        if reached || p == max_count {
            let below = if limited {
                f.iter().filter(|&&v| v < f_limit).count()
            } else {
                0
            };
            return Ok(BandModes {
                modes: first(modes, below.max(min_count)),
                complete: reached,
            });
        }
        p = (2 * p).min(max_count);
    }
}

/// The first `count` pairs of `modes`.
fn first(mut modes: Modes, count: usize) -> Modes {
    modes.eigenvalues.truncate(count);
    modes.shapes.truncate(count);
    modes.residuals.truncate(count);
    modes
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fixed–fixed chain of the modal tests with its exact frequencies (1/time).
    fn chain(n: usize) -> (Csc<f64>, Csc<f64>, Vec<f64>) {
        let (k, m, lambdas) = crate::solve::modal::tests::chain(n);
        let f = lambdas
            .iter()
            .map(|l| l.sqrt() / (2.0 * std::f64::consts::PI))
            .collect();
        (k, m, f)
    }

    #[test]
    fn finds_every_mode_below_the_limit() {
        let (k, m, exact) = chain(120);
        // Between modes 29 and 30: more than the first try's 6 and its doubling 12, 24.
        let limit = 0.5 * (exact[28] + exact[29]);
        let b = modes_below(&k, &m, limit, 6, 200, &ModalOptions::default()).unwrap();
        assert!(b.complete);
        let f = b.modes.frequencies_hz();
        assert_eq!(f.len(), 29);
        for (a, e) in f.iter().zip(&exact) {
            approx::assert_relative_eq!(*a, *e, max_relative = 1e-9);
        }
    }

    #[test]
    fn keeps_the_minimum_count_below_a_low_limit() {
        let (k, m, exact) = chain(40);
        let b = modes_below(&k, &m, 0.5 * exact[0], 6, 200, &ModalOptions::default()).unwrap();
        assert!(b.complete);
        assert_eq!(b.modes.eigenvalues.len(), 6);
        // A limit that is no number asks for the minimum too.
        let b = modes_below(&k, &m, f64::NAN, 6, 200, &ModalOptions::default()).unwrap();
        assert_eq!(b.modes.eigenvalues.len(), 6);
    }

    #[test]
    fn cap_stops_the_search_and_says_so() {
        let (k, m, exact) = chain(60);
        let b = modes_below(&k, &m, exact[50], 4, 10, &ModalOptions::default()).unwrap();
        assert!(!b.complete);
        assert_eq!(b.modes.eigenvalues.len(), 10);
        // A limit above the whole spectrum ends at the DOF count.
        let (k, m, _) = chain(8);
        let b = modes_below(&k, &m, 1e9, 3, 100, &ModalOptions::default()).unwrap();
        assert!(b.complete);
        assert_eq!(b.modes.eigenvalues.len(), 8);
    }
}
