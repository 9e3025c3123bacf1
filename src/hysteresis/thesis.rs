//! The thesis's unloading rule (§2.3.3, phases 1–3; model.md §4), with a fading memory
//! for shallow excursions that keeps its closed loops continuous in the motion.
//!
//! Phase 3 runs down the elastic line from the reversal point until it meets the virgin
//! branch of the new direction from the origin o* ([`ThesisState::target_origin`]). For a
//! branch that spans at least [`FADE_DEPTH`] of the branch before it (every loop of a
//! harmonic motion, and of a decaying one that keeps a quarter of its span per half
//! cycle), o* is the elastic line's zero-force point: phase 3 meets
//! the branch at zero force, the thesis rule exactly. A shallower excursion (a minor
//! reversal just past zero force) keeps part of the memory of the branch before it: o*
//! lies between the zero-force point and that branch's origin, so the way back runs up
//! the elastic line towards the branch it left, continuously in the excursion's depth
//! (model.md §4, "Shallow excursions").

use super::{sign, StepResult, Tangents, FORCE_SLOT as FORCE, SLIP_SLOT as SLIP};
use crate::error::Error;
use crate::law::Backbone;

/// A branch that spans less slip than this fraction of the branch before it keeps part of
/// that branch's memory (weight (1 − ρ/FADE_DEPTH)², ρ the ratio of the spans).
pub const FADE_DEPTH: f64 = 0.25;

/// State of the thesis rule. Phase 1/2: on the virgin curve from `origin` in direction
/// `dir`. Phase 3 (`unloading`): on the elastic line through the reversal point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThesisState {
    pub slip: f64,
    pub force: f64,
    /// Slip where the current virgin branch started (the last zero-force point, or an
    /// origin between it and `memory_origin` after a shallow excursion).
    pub origin: f64,
    /// Direction of the current virgin branch: +1, −1, or 0 before any motion.
    pub dir: f64,
    /// Phase 3: elastic unloading from (rev_slip, rev_force).
    pub unloading: bool,
    pub rev_slip: f64,
    pub rev_force: f64,
    /// Origin of the branch before the current one (direction −dir).
    pub memory_origin: f64,
    /// Slip that branch spanned from where it was entered to its reversal (≥ 0; 0: no
    /// memory).
    pub memory_span: f64,
    /// Slip where the current branch was entered (left the elastic line).
    pub entry: f64,
}

/// Slots of the stored state (tag at 0, [`ThesisState::write`] from 1).
const ORIGIN: usize = 3;
const REV_SLIP: usize = 6;
const REV_FORCE: usize = 7;
const MEMORY_ORIGIN: usize = 8;
const MEMORY_SPAN: usize = 9;
const ENTRY: usize = 10;
/// Not stored: holds the derivative of the new origin while a branch is entered.
const NEXT_ORIGIN: usize = 11;

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
            memory_origin: origin,
            memory_span: 0.0,
            entry: origin,
        }
    }

    pub(super) fn write(&self, out: &mut [f64]) {
        out[..10].copy_from_slice(&[
            self.slip,
            self.force,
            self.origin,
            self.dir,
            f64::from(u8::from(self.unloading)),
            self.rev_slip,
            self.rev_force,
            self.memory_origin,
            self.memory_span,
            self.entry,
        ]);
    }

    /// Reads [`Self::write`]'s slots; a state stored without the memory slots (zeros
    /// there) has no memory and continues as the thesis rule.
    pub(super) fn read(s: &[f64]) -> Result<Self, Error> {
        if ![-1.0, 0.0, 1.0].contains(&s[3]) || ![0.0, 1.0].contains(&s[4]) || s[8] < 0.0 {
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
            memory_origin: s[7],
            memory_span: s[8],
            entry: s[9],
        })
    }

    /// Origin o* of the branch that phase 3 leads to (direction −dir) and its derivative
    /// terms: the elastic line's zero-force point z = δ_r − F_r/k_T0, moved towards the
    /// origin of the branch before the current one by the weight w = (1 − ρ/FADE_DEPTH)²,
    /// ρ = |δ_r − entry| / memory_span (0 for ρ ≥ FADE_DEPTH, or without memory), and only
    /// if that origin lies behind z for the new direction (model.md §4).
    fn target_origin(&self, b: &Backbone) -> (f64, Vec<(usize, f64)>) {
        let k0 = b.k_t0();
        let zero = self.rev_slip - self.rev_force / k0;
        let mut terms = vec![(REV_SLIP, 1.0), (REV_FORCE, -1.0 / k0)];
        let shift = self.memory_origin - zero;
        let travel = -self.dir;
        if self.memory_span <= 0.0 || travel * shift > 0.0 {
            return (zero, terms);
        }
        let excursion = self.rev_slip - self.entry;
        let rho = excursion.abs() / self.memory_span;
        if rho >= FADE_DEPTH {
            return (zero, terms);
        }
        let w = (1.0 - rho / FADE_DEPTH).powi(2);
        // dw = w'(ρ) dρ, dρ = sign(excursion) (dδ_r − d entry)/span − ρ dspan/span.
        let dw_drho = -2.0 * (1.0 - rho / FADE_DEPTH) / FADE_DEPTH;
        let e = sign(excursion) / self.memory_span;
        let dw = |c: f64| dw_drho * c * shift;
        // o* = z + w (o_m − z): do* = (1 − w) dz + w do_m + (o_m − z) dw.
        for term in terms.iter_mut() {
            term.1 *= 1.0 - w;
        }
        terms[0].1 += dw(e);
        terms.extend([
            (MEMORY_ORIGIN, w),
            (ENTRY, dw(-e)),
            (MEMORY_SPAN, dw(-rho / self.memory_span)),
        ]);
        (zero + w * shift, terms)
    }

    /// Leaves phase 3 onto the branch from `next_origin` in direction −dir where the elastic
    /// line meets it (s_x with k_T0 s_x − g(s_x) = k_T0 |z − o*|), the current branch
    /// becoming the memory; sets `slip` there.
    fn enter_branch(
        &mut self,
        b: &Backbone,
        next_origin: (f64, Vec<(usize, f64)>),
        t: &mut impl Tangents,
    ) {
        let k0 = b.k_t0();
        let travel = -self.dir;
        let (o_next, o_terms) = next_origin;
        t.set(NEXT_ORIGIN, &o_terms, 0.0);
        let zero = self.rev_slip - self.rev_force / k0;
        let s_x = meeting_depth(b, k0 * travel * (zero - o_next));
        let entry = o_next + travel * s_x;
        // ds_x = k0 travel (dz − do*) / h'(s_x), h' = k0 − g'(s_x) (0 where s_x = 0).
        let h1 = k0 - b.tangent(s_x);
        let q = if s_x > 0.0 && h1 > 0.0 { k0 / h1 } else { 0.0 };
        t.set(
            MEMORY_SPAN,
            &[
                (REV_SLIP, sign(self.rev_slip - self.entry)),
                (ENTRY, -sign(self.rev_slip - self.entry)),
            ],
            0.0,
        );
        t.set(
            ENTRY,
            &[(NEXT_ORIGIN, 1.0 - q), (REV_SLIP, q), (REV_FORCE, -q / k0)],
            0.0,
        );
        t.set(MEMORY_ORIGIN, &[(ORIGIN, 1.0)], 0.0);
        t.set(ORIGIN, &[(NEXT_ORIGIN, 1.0)], 0.0);
        self.memory_span = (self.rev_slip - self.entry).abs();
        self.entry = entry;
        self.memory_origin = self.origin;
        self.origin = o_next;
        self.dir = travel;
        self.unloading = false;
        self.slip = entry;
    }

    /// Whether the elastic line at `slip` has met the branch from `next_origin` (direction
    /// −dir): past its zero-force point, with |line| ≥ g(|δ − o*|).
    fn past_meeting(&self, b: &Backbone, slip: f64, next_origin: f64) -> bool {
        let travel = -self.dir;
        let line = self.rev_force + b.k_t0() * (slip - self.rev_slip);
        let zero = self.rev_slip - self.rev_force / b.k_t0();
        travel * (slip - zero) > 0.0
            && travel * line >= b.force((travel * (slip - next_origin)).max(0.0))
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
        let next = self.target_origin(b);
        if self.past_meeting(b, self.slip, next.0) {
            let slip = self.slip;
            self.enter_branch(b, next, t);
            self.slip = slip;
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
            // Elastic line F = F_r + k_T0 (δ − δ_r) (2.38); leaves it where it meets the
            // next branch (at F = 0 unless a memory holds) or back at δ_r.
            let next = self.target_origin(b);
            if self.dir * (target - self.rev_slip) > 0.0 {
                self.unloading = false; // rejoins the virgin branch it left
                self.slip = self.rev_slip;
                t.set(SLIP, &[(REV_SLIP, 1.0)], 0.0);
            } else if self.past_meeting(b, target, next.0) {
                // phase 1 in the other direction
                self.enter_branch(b, next, t);
                t.set(SLIP, &[(ENTRY, 1.0)], 0.0);
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

/// The depth s ≥ 0 on a virgin branch where an elastic line k_T0 (s − s₀) meets it,
/// h(s) = k_T0 s − g(s) = c (c = k_T0 s₀ ≥ 0; h is nondecreasing): Newton's method kept
/// inside a bracket, bisecting where it leaves it.
fn meeting_depth(b: &Backbone, c: f64) -> f64 {
    if c <= 0.0 || !c.is_finite() {
        return 0.0;
    }
    let k0 = b.k_t0();
    let h = |s: f64| k0 * s - b.force(s) - c;
    let (mut lo, mut hi) = (0.0, (c + b.friction_limit()) / k0);
    let mut s = hi;
    for _ in 0..200 {
        let r = h(s);
        if r == 0.0 {
            return s;
        }
        if r > 0.0 {
            hi = s;
        } else {
            lo = s;
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let slope = k0 - b.tangent(s);
        let newton = s - r / slope;
        s = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
    }
    hi
}
