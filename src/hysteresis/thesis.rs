//! The thesis's unloading rule (§2.3.3, phases 1–3; model.md §4).

use super::{sign, StepResult, Tangents, FORCE_SLOT as FORCE, SLIP_SLOT as SLIP};
use crate::error::Error;
use crate::law::Backbone;

/// State of the thesis rule. Phase 1/2: on the virgin curve from `origin` in direction
/// `dir`. Phase 3 (`unloading`): on the elastic line through the reversal point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThesisState {
    pub slip: f64,
    pub force: f64,
    /// Slip where the current virgin branch started (the last zero-force point).
    pub origin: f64,
    /// Direction of the current virgin branch: +1, −1, or 0 before any motion.
    pub dir: f64,
    /// Phase 3: elastic unloading from (rev_slip, rev_force).
    pub unloading: bool,
    pub rev_slip: f64,
    pub rev_force: f64,
}

/// Slots of the stored state (tag at 0, [`ThesisState::write`] from 1).
const ORIGIN: usize = 3;
const REV_SLIP: usize = 6;
const REV_FORCE: usize = 7;

/// Derivative of the zero-force point δ_r − F_r/k_T0 of the elastic line.
fn zero_terms(b: &Backbone) -> [(usize, f64); 2] {
    [(REV_SLIP, 1.0), (REV_FORCE, -1.0 / b.k_t0())]
}

impl ThesisState {
    pub fn virgin(origin: f64) -> Self {
        Self {
            slip: origin,
            force: 0.0,
            origin,
            dir: 0.0,
            unloading: false,
            rev_slip: origin,
            rev_force: 0.0,
        }
    }

    pub(super) fn write(&self, out: &mut [f64]) {
        out[..7].copy_from_slice(&[
            self.slip,
            self.force,
            self.origin,
            self.dir,
            f64::from(u8::from(self.unloading)),
            self.rev_slip,
            self.rev_force,
        ]);
    }

    pub(super) fn read(s: &[f64]) -> Result<Self, Error> {
        if ![-1.0, 0.0, 1.0].contains(&s[3]) || ![0.0, 1.0].contains(&s[4]) {
            return Err(Error::OutOfRange("stored thesis-rule state is corrupt"));
        }
        Ok(Self {
            slip: s[0],
            force: s[1],
            origin: s[2],
            dir: s[3],
            unloading: s[4] == 1.0,
            rev_slip: s[5],
            rev_force: s[6],
        })
    }

    /// Re-derives the forces from the slips with the current backbone (the reversal point
    /// lies on the virgin branch from `origin`). With a constant friction limit this
    /// reproduces the stored values; after a change of normal load it keeps the force a
    /// continuous function of the load at fixed slip history. If the elastic line has
    /// already crossed zero at the new load, phase 1 in the other direction has begun.
    fn sync(&mut self, b: &Backbone, t: &mut impl Tangents) {
        if self.dir == 0.0 {
            self.force = 0.0;
            t.set(FORCE, &[], 0.0);
            return;
        }
        if !self.unloading {
            self.force = self.on_virgin(b, self.slip);
            t.set(FORCE, &self.virgin_terms(b, self.slip, SLIP), 0.0);
            return;
        }
        self.rev_force = self.on_virgin(b, self.rev_slip);
        t.set(
            REV_FORCE,
            &self.virgin_terms(b, self.rev_slip, REV_SLIP),
            0.0,
        );
        let zero_slip = self.rev_slip - self.rev_force / b.k_t0();
        if self.dir * (self.slip - zero_slip) < 0.0 {
            self.unloading = false;
            self.origin = zero_slip;
            t.set(ORIGIN, &zero_terms(b), 0.0);
            self.dir = -self.dir;
            self.force = self.on_virgin(b, self.slip);
            t.set(FORCE, &self.virgin_terms(b, self.slip, SLIP), 0.0);
        } else {
            self.set_elastic(b, self.slip, t);
        }
    }

    /// Force on the virgin branch from `origin` at slip δ: dir·g(dir·(δ − δ₀)) (2.49).
    fn on_virgin(&self, b: &Backbone, slip: f64) -> f64 {
        self.dir * b.force((self.dir * (slip - self.origin)).max(0.0))
    }

    /// Derivative of [`Self::on_virgin`] at `slip` (stored in slot `at`): g'(s)(dδ − dδ₀),
    /// zero where s = 0.
    fn virgin_terms(&self, b: &Backbone, slip: f64, at: usize) -> [(usize, f64); 2] {
        let s = self.dir * (slip - self.origin);
        let k = if s > 0.0 { b.tangent(s) } else { 0.0 };
        [(at, k), (ORIGIN, -k)]
    }

    /// The force on the elastic line F = F_r + k_T0 (δ − δ_r) (2.38) at the current slip
    /// (slot SLIP), clipped at ±μF_N (then its derivative is zero).
    fn set_elastic(&mut self, b: &Backbone, slip: f64, t: &mut impl Tangents) {
        let (k0, limit) = (b.k_t0(), b.friction_limit());
        let line = self.rev_force + k0 * (slip - self.rev_slip);
        self.force = line.clamp(-limit, limit);
        if self.force == line {
            t.set(FORCE, &[(REV_FORCE, 1.0), (SLIP, k0), (REV_SLIP, -k0)], 0.0);
        } else {
            t.set(FORCE, &[], 0.0);
        }
    }

    /// Walks from `self.slip` to `target` through as many phase changes as it takes,
    /// moving the derivatives `t` along.
    pub(super) fn advance(
        &mut self,
        b: &Backbone,
        target: f64,
        t: &mut impl Tangents,
    ) -> StepResult {
        self.sync(b, t);
        let k0 = b.k_t0();
        let motion = sign(target - self.slip);
        let mut dissipated = 0.0;
        if motion == 0.0 {
            return StepResult {
                force: self.force,
                tangent: self.tangent(b),
                dissipated,
            };
        }
        if self.dir == 0.0 {
            self.dir = motion; // first motion starts phase 1 in its direction
        }
        if !self.unloading && motion != self.dir {
            // Reversal on the virgin curve: phase 3 begins.
            self.unloading = true;
            self.rev_slip = self.slip;
            self.rev_force = self.force;
            t.set(REV_SLIP, &[(SLIP, 1.0)], 0.0);
            t.set(REV_FORCE, &[(FORCE, 1.0)], 0.0);
        }
        if self.unloading {
            // Elastic line F = F_r + k_T0 (δ − δ_r) (2.38); leaves it at F = 0 or back at δ_r.
            let zero_slip = self.rev_slip - self.rev_force / k0;
            let back_past_reversal = self.dir * (target - self.rev_slip) > 0.0;
            let past_zero = self.dir * (target - zero_slip) < 0.0;
            if back_past_reversal {
                self.unloading = false; // rejoins the virgin branch it left
                self.slip = self.rev_slip;
                t.set(SLIP, &[(REV_SLIP, 1.0)], 0.0);
            } else if past_zero {
                self.unloading = false; // force changed sign: phase 1 in the other direction
                self.origin = zero_slip;
                t.set(ORIGIN, &zero_terms(b), 0.0);
                self.dir = -self.dir;
                self.slip = zero_slip;
                t.set(SLIP, &[(ORIGIN, 1.0)], 0.0);
            } else {
                self.slip = target;
                t.set(SLIP, &[], 1.0);
                self.set_elastic(b, target, t);
                return StepResult {
                    force: self.force,
                    tangent: k0,
                    dissipated,
                };
            }
        }
        // Phases 1 and 2 on the virgin curve from `origin`, (2.49) then (2.39).
        let s_from = (self.dir * (self.slip - self.origin)).max(0.0);
        let s_to = (self.dir * (target - self.origin)).max(0.0);
        dissipated +=
            (b.elastic_split_dissipation(s_to) - b.elastic_split_dissipation(s_from)).max(0.0);
        self.slip = target;
        t.set(SLIP, &[], 1.0);
        self.force = self.dir * b.force(s_to);
        t.set(FORCE, &self.virgin_terms(b, target, SLIP), 0.0);
        StepResult {
            force: self.force,
            tangent: self.tangent(b),
            dissipated,
        }
    }

    fn tangent(&self, b: &Backbone) -> f64 {
        if self.unloading || self.dir == 0.0 {
            b.k_t0()
        } else {
            b.tangent((self.dir * (self.slip - self.origin)).max(0.0))
        }
    }
}
