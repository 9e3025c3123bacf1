//! Aitken extrapolation of a marched loop to its closed state (module docs of
//! [`super::aft`]): where consecutive periods' force differences shrink geometrically,
//! F_p = F_∞ + c q^p, the period-end state is jumped to its limit
//! s_∞ = s_p + (s_p − s_{p−1}) q/(1 − q) over the slots that drift (the history
//! variables), q the ratio of the last two force differences. Where the slots relax
//! independently at rates of their own (the parallel cells of a three-direction point,
//! each forgetting its sideways position at a rate set by its own slip limit),
//! [`Aitken::per_slot`] takes each slot's own ratio of its last two changes instead. The
//! closure test after the jump is the caller's, so a jump is verified, never assumed.

use std::ops::Range;

/// A contraction ratio below this is extrapolated (above it the drift is round-off or not
/// geometric).
const MAX_RATIO: f64 = 0.999_999;

/// Period-end states and force differences since the last jump.
pub struct Aitken {
    /// The state slots to extrapolate.
    slots: Range<usize>,
    /// Each slot its own ratio (else the force differences' ratio for all).
    own_ratio: bool,
    ends: Vec<Vec<f64>>,
    diffs: Vec<f64>,
}

impl Aitken {
    /// One ratio for all `slots`: that of the force differences.
    pub fn new(slots: Range<usize>) -> Self {
        Aitken {
            slots,
            own_ratio: false,
            ends: Vec::with_capacity(3),
            diffs: Vec::with_capacity(2),
        }
    }

    /// Each of `slots` extrapolated with the ratio of its own last two changes (Aitken's
    /// Δ² per slot); a slot that did not change, or whose changes do not contract, is
    /// left where it is.
    pub fn per_slot(slots: Range<usize>) -> Self {
        Aitken {
            own_ratio: true,
            ..Aitken::new(slots)
        }
    }

    /// No period recorded since the start or the last jump: the next period's end is
    /// [`Aitken::first`] (its force difference compares across the jump).
    pub fn starting(&self) -> bool {
        self.ends.is_empty()
    }

    /// Records the end of the first period (its force difference is not meaningful).
    pub fn first(&mut self, state: &[f64]) {
        self.ends.push(state.to_vec());
    }

    /// Records a period's end `state` and its force difference to the period before;
    /// after two such periods returns the extrapolated state, if the drift contracts.
    /// The caller marches on from it if the library accepts it, else calls
    /// [`Aitken::rejected`].
    pub fn after(&mut self, state: &[f64], diff: f64) -> Option<Vec<f64>> {
        self.ends.push(state.to_vec());
        self.diffs.push(diff);
        let [d1, d2] = self.diffs[..] else {
            return None;
        };
        let (s0, s1, s2) = (&self.ends[0], &self.ends[1], &self.ends[2]);
        let jump = if self.own_ratio {
            let mut x = state.to_vec();
            for i in self.slots.clone() {
                let (c1, c2) = (s1[i] - s0[i], s2[i] - s1[i]);
                let q = c2 / c1;
                if q.is_finite() && q.abs() < MAX_RATIO {
                    x[i] = s2[i] + c2 * q / (1.0 - q);
                }
            }
            Some(x)
        } else {
            let q = d2 / d1;
            (q < MAX_RATIO).then(|| {
                let w = q / (1.0 - q);
                let mut x = state.to_vec();
                for i in self.slots.clone() {
                    x[i] = s2[i] + (s2[i] - s1[i]) * w;
                }
                x
            })
        };
        self.ends.clear();
        self.diffs.clear();
        if jump.is_none() {
            self.ends.push(state.to_vec());
        }
        jump
    }

    /// The extrapolated state was not usable: start again from `state`.
    pub fn rejected(&mut self, state: &[f64]) {
        self.ends.clear();
        self.ends.push(state.to_vec());
    }
}
