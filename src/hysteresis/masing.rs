//! Masing's rule (Mindlin–Deresiewicz) with memory: a stack of reversal points.
//!
//! Virgin curve: F = sgn(δ − δ₀) g(|δ − δ₀|). After the n-th reversal at (δ_n, F_n), with
//! the motion in direction d_n: F = F_n + d_n · 2 g(d_n (δ − δ_n)/2) (model.md §4).
//! Memory: the branch from the first reversal rejoins the virgin curve at the mirror point
//! 2δ₀ − δ₁; the branch from r_n (n ≥ 2) that reaches δ_{n−1} closes the inner loop and
//! the branch from r_{n−2} continues. A branch that reaches Coulomb sliding has erased all
//! memory, so the stack collapses to a virgin curve shifted to the sliding point.

use super::{sign, StepResult, Tangents, FORCE_SLOT as FORCE, SLIP_SLOT as SLIP};
use crate::error::Error;
use crate::law::Backbone;

/// Depth of the reversal memory kept per direction. Deeper nesting (rare: it needs more
/// than this many unclosed reversals without sliding) forgets the innermost pending loop,
/// i.e. treats it as closed; continuity of the force is kept.
pub const MAX_REVERSALS: usize = 6;

/// Slots of the stored state (tag at 0, [`MasingState::write`] from 1): the origin and
/// reversal i's slip and force.
const ORIGIN: usize = 3;
const fn rev_slip(i: usize) -> usize {
    5 + 3 * i
}
const fn rev_force(i: usize) -> usize {
    6 + 3 * i
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MasingState {
    pub slip: f64,
    pub force: f64,
    /// Centre δ₀ of the virgin curve.
    pub origin: f64,
    /// Number of stored reversals.
    pub depth: usize,
    /// Reversal points (δ_i, F_i, d_i) with d_i the direction of the branch starting there.
    pub reversals: [(f64, f64, f64); MAX_REVERSALS],
}

impl MasingState {
    pub fn virgin(origin: f64) -> Self {
        Self {
            slip: origin,
            force: 0.0,
            origin,
            depth: 0,
            reversals: [(0.0, 0.0, 0.0); MAX_REVERSALS],
        }
    }

    pub(super) fn write(&self, out: &mut [f64]) {
        out[0] = self.slip;
        out[1] = self.force;
        out[2] = self.origin;
        // depth is stored in the count of filled triples: slot 3 holds it explicitly.
        for (i, r) in self.reversals.iter().enumerate() {
            out[4 + 3 * i..7 + 3 * i].copy_from_slice(&[r.0, r.1, r.2]);
        }
        out[3] = self.depth as f64;
    }

    pub(super) fn read(s: &[f64]) -> Result<Self, Error> {
        let depth = s[3];
        if !(0.0..=MAX_REVERSALS as f64).contains(&depth) || depth.fract() != 0.0 {
            return Err(Error::OutOfRange("stored Masing state is corrupt"));
        }
        let mut st = Self::virgin(s[2]);
        st.slip = s[0];
        st.force = s[1];
        st.depth = depth as usize;
        for i in 0..MAX_REVERSALS {
            st.reversals[i] = (s[4 + 3 * i], s[5 + 3 * i], s[6 + 3 * i]);
        }
        Ok(st)
    }

    /// Direction of the branch the point is on (0 at the virgin origin).
    fn branch_dir(&self) -> f64 {
        match self.depth {
            0 => sign(self.slip - self.origin),
            n => self.reversals[n - 1].2,
        }
    }

    /// Force on the active branch at slip δ, and the distance Δ travelled along it.
    fn on_branch(&self, b: &Backbone, slip: f64) -> f64 {
        self.branch_force(b, self.depth, slip)
    }

    /// Force at slip δ on the branch that starts at reversal `depth` (0: the virgin curve).
    fn branch_force(&self, b: &Backbone, depth: usize, slip: f64) -> f64 {
        match depth {
            0 => sign(slip - self.origin) * b.force((slip - self.origin).abs()),
            n => {
                let (ds, fs, d) = self.reversals[n - 1];
                fs + d * 2.0 * b.force((d * (slip - ds)).max(0.0) / 2.0)
            }
        }
    }

    /// Derivative of [`Self::branch_force`] on branch `depth` at slip δ (stored in slot
    /// `at`), clipped at ±μF_N like the force (then zero): g'(s)(dδ − dδ₀) on the virgin
    /// curve, dF_n + g'(Δ/2)(dδ − dδ_n) on the branch from reversal n.
    fn branch_terms(&self, b: &Backbone, depth: usize, slip: f64, at: usize) -> [(usize, f64); 3] {
        let limit = b.friction_limit();
        if self.branch_force(b, depth, slip).abs() > limit {
            return [(at, 0.0); 3];
        }
        match depth {
            0 => {
                let k = b.tangent((slip - self.origin).abs());
                [(at, k), (ORIGIN, -k), (ORIGIN, 0.0)]
            }
            n => {
                let (ds, _, d) = self.reversals[n - 1];
                let k = b.tangent((d * (slip - ds)).max(0.0) / 2.0);
                [(rev_force(n - 1), 1.0), (at, k), (rev_slip(n - 1), -k)]
            }
        }
    }

    /// The force on the active branch at the current slip, clipped, with its derivative.
    fn set_force(&mut self, b: &Backbone, t: &mut impl Tangents) {
        let limit = b.friction_limit();
        self.force = self.on_branch(b, self.slip).clamp(-limit, limit);
        t.set(
            FORCE,
            &self.branch_terms(b, self.depth, self.slip, SLIP),
            0.0,
        );
    }

    /// Re-derives every stored force from the slips with the current backbone: each reversal
    /// lies on the branch before it. With a constant friction limit this reproduces the
    /// stored values; when the normal load changed since the last step it makes the force a
    /// continuous function of the load at fixed slip history (no jump between continuing
    /// and reversing at a zero increment).
    fn sync(&mut self, b: &Backbone, t: &mut impl Tangents) {
        let limit = b.friction_limit();
        for i in 0..self.depth {
            let slip = self.reversals[i].0;
            let f = self.branch_force(b, i, slip).clamp(-limit, limit);
            t.set(
                rev_force(i),
                &self.branch_terms(b, i, slip, rev_slip(i)),
                0.0,
            );
            self.reversals[i].1 = f;
        }
        self.set_force(b, t);
    }

    /// Iwan dissipation accumulated along the active branch up to slip δ (see
    /// `Backbone::iwan_dissipation`): H(|δ − δ₀|) on the virgin curve, 2H(Δ/2) on a branch.
    fn branch_dissipation(&self, b: &Backbone, slip: f64) -> f64 {
        match self.depth {
            0 => b.iwan_dissipation((slip - self.origin).abs()),
            n => {
                let (ds, _, d) = self.reversals[n - 1];
                2.0 * b.iwan_dissipation((d * (slip - ds)).max(0.0) / 2.0)
            }
        }
    }

    /// Slip at which the active branch closes (rejoins its parent), if any, and its
    /// derivative.
    fn closure(&self) -> Option<(f64, [(usize, f64); 2])> {
        match self.depth {
            0 => None,
            1 => Some((
                2.0 * self.origin - self.reversals[0].0,
                [(ORIGIN, 2.0), (rev_slip(0), -1.0)],
            )),
            n => Some((
                self.reversals[n - 2].0,
                [(rev_slip(n - 2), 1.0), (SLIP, 0.0)],
            )),
        }
    }

    fn push_reversal(&mut self, dir: f64, t: &mut impl Tangents) {
        if self.depth == MAX_REVERSALS {
            // Forget the innermost pending loop (r_{n-1}, r_n): the new branch then heads
            // for r_{n-2}, as if the small loop had closed. Force stays continuous.
            self.depth -= 2;
        }
        self.reversals[self.depth] = (self.slip, self.force, dir);
        t.set(rev_slip(self.depth), &[(SLIP, 1.0)], 0.0);
        t.set(rev_force(self.depth), &[(FORCE, 1.0)], 0.0);
        self.depth += 1;
    }

    /// Collapses the memory once the active branch is in Coulomb sliding: every slider
    /// has slipped, so the point behaves as a virgin curve centred δ* behind it.
    fn collapse_if_sliding(&mut self, b: &Backbone, t: &mut impl Tangents) {
        let d = self.branch_dir();
        let delta_star = b.slip_limit();
        let sliding = match self.depth {
            0 => (self.slip - self.origin).abs() >= delta_star,
            n => d * (self.slip - self.reversals[n - 1].0) >= 2.0 * delta_star,
        };
        if sliding && d != 0.0 {
            self.depth = 0;
            self.origin = self.slip - d * delta_star;
            t.set(ORIGIN, &[(SLIP, 1.0)], 0.0);
            // Rounding may leave |δ − δ₀| a few ulps below δ*, where a Jenkins backbone would
            // report the stick tangent k_T0 although the point slides: step δ₀ back by ulps.
            for _ in 0..8 {
                if (self.slip - self.origin).abs() >= delta_star {
                    break;
                }
                self.origin -= d * f64::EPSILON * self.origin.abs().max(delta_star);
            }
        }
    }

    pub(super) fn advance(
        &mut self,
        b: &Backbone,
        target: f64,
        t: &mut impl Tangents,
    ) -> StepResult {
        self.sync(b, t);
        let motion = sign(target - self.slip);
        if motion == 0.0 {
            return StepResult {
                force: self.force,
                tangent: self.tangent(b),
                dissipated: 0.0,
            };
        }
        let dir = self.branch_dir();
        if dir != 0.0 && motion != dir {
            let at_branch_start = self.depth > 0 && self.slip == self.reversals[self.depth - 1].0;
            if at_branch_start {
                self.depth -= 1; // reversing exactly at a reversal point: back on its parent
            } else {
                self.push_reversal(motion, t);
            }
        }
        let mut dissipated = 0.0;
        loop {
            let closes = match self.closure() {
                Some((c, terms)) if motion * (target - c) >= 0.0 => Some((c, terms)),
                _ => None,
            };
            // The slip ends at the target whether or not a loop closes exactly there, so
            // its derivative is the target's; an intermediate closure point moves with
            // the slips it came from.
            let (stop, terms, d_target) = match closes {
                Some((c, terms)) if c != target => (c, terms, 0.0),
                _ => (target, [(SLIP, 0.0); 2], 1.0),
            };
            dissipated +=
                (self.branch_dissipation(b, stop) - self.branch_dissipation(b, self.slip)).max(0.0);
            self.slip = stop;
            t.set(SLIP, &terms, d_target);
            if closes.is_some() {
                // The branch reached its parent (at the target too: a loop closed exactly
                // there is closed, so a periodic path keeps a periodic memory): drop the
                // closed loop; the force is the parent's, equal there by continuity.
                self.depth = if self.depth == 1 { 0 } else { self.depth - 2 };
            }
            self.set_force(b, t);
            if stop == target {
                break;
            }
        }
        self.collapse_if_sliding(b, t);
        StepResult {
            force: self.force,
            tangent: self.tangent(b),
            dissipated,
        }
    }

    /// dF/dδ on the active branch: zero where the branch force is clipped at ±μF_N (a
    /// reversal stored under a larger normal load can put it there before Δ = 2δ*), as in
    /// [`Self::branch_terms`].
    fn tangent(&self, b: &Backbone) -> f64 {
        if self.on_branch(b, self.slip).abs() > b.friction_limit() {
            return 0.0;
        }
        match self.depth {
            0 => b.tangent((self.slip - self.origin).abs()),
            n => {
                let (ds, _, d) = self.reversals[n - 1];
                b.tangent((d * (self.slip - ds)).max(0.0) / 2.0)
            }
        }
    }
}
