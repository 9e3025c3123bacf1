//! The EPMC backbone continued in the modal amplitude alone, where the arclength path
//! ([`super::arclength`]) stops: each requested ln q is solved by Newton at fixed q from
//! the previous solution (a secant predictor in ln q after two points). The step in ln q
//! adapts: it is halved where Newton fails and doubled after each success, and the
//! stepping stops after [`MAX_HALVINGS`] failures in a row, so a range where no nearby
//! solution exists costs a bounded number of solves. This does not follow turning
//! points — it steps over a rough range of the sampled stick–slip balance on whichever
//! branch Newton finds — so the range it covers is reported.

use super::arclength::Crossing;
use super::equations::{Epmc, State};

/// Failed solves in a row (each halving the step in ln q) before the stepping stops.
pub const MAX_HALVINGS: usize = 5;

/// What the stepping reached: the requested amplitudes solved (ascending), the last
/// converged point and the scaled residual where it stopped, if it did.
pub struct Stepped {
    pub crossings: Vec<Crossing>,
    pub last: Crossing,
    pub failed: Option<f64>,
}

/// Steps from `start` (ln q, state, energy per element) to each of `targets` (ln q,
/// ascending, all above the start).
pub fn toward(ep: &mut Epmc, start: Crossing, targets: &[f64]) -> Stepped {
    // (ln q, state) of the last two converged points, for the secant predictor.
    let mut recent: Vec<(f64, State)> = vec![(start.0, start.1.clone())];
    let mut last = start;
    let mut crossings = Vec::with_capacity(targets.len());
    // The step in ln q; unbounded until the first failure.
    let mut step = f64::INFINITY;
    let mut failures = 0;
    for &target in targets {
        while last.0 < target {
            let lq = (last.0 + step).min(target);
            match ep.solve(predict(&recent, lq), lq.exp()) {
                Ok((st, diss)) => {
                    ep.passed(lq.exp());
                    recent.push((lq, st.clone()));
                    if recent.len() > 2 {
                        recent.remove(0);
                    }
                    step = 2.0 * (lq - last.0);
                    failures = 0;
                    last = (lq, st, diss);
                }
                Err(res) => {
                    failures += 1;
                    if failures > MAX_HALVINGS {
                        return Stepped {
                            crossings,
                            last,
                            failed: Some(res),
                        };
                    }
                    step = 0.5 * (lq - last.0);
                }
            }
        }
        crossings.push(last.clone());
    }
    Stepped {
        crossings,
        last,
        failed: None,
    }
}

/// Secant extrapolation in ln q from the last two points (or the last state).
fn predict(recent: &[(f64, State)], lq: f64) -> State {
    let (l1, s1) = recent.last().expect("at least the start");
    let Some((l0, s0)) = recent.len().checked_sub(2).map(|i| &recent[i]) else {
        return s1.clone();
    };
    if (l1 - l0).abs() < 1e-14 {
        return s1.clone();
    }
    let c = (lq - l1) / (l1 - l0);
    State {
        psi: s1
            .psi
            .iter()
            .zip(&s0.psi)
            .map(|(b, a)| b + c * (b - a))
            .collect(),
        omega: s1.omega + c * (s1.omega - s0.omega),
        xi: s1.xi + c * (s1.xi - s0.xi),
    }
}
