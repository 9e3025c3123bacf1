//! The EPMC backbone followed in ln q by pseudo-arclength continuation (Keller 1977;
//! Seydel, *Practical Bifurcation and Stability Analysis*, 2010, §4.4), so it passes
//! turning points: with H > 1 harmonics the backbone of a chain with Jenkins joints
//! turns back in q where a second joint starts to slip, and the balance of sampled
//! stick–slip forces is only piecewise smooth, so a turning point may be a corner.
//!
//! y = (ψ, ω/ω₀, ξ/ω₀, ln q); the tangent t solves [G_y; t_prevᵀ] t = e (normalized);
//! predictor y + h t, corrector Newton on (G(y) = 0, tᵀ(y − y_p) = 0). A step is
//! repeated at half length when the corrector fails, when the corrected point lies
//! behind the predictor's direction, when the tangent turns by more than 45° or ω
//! changes by more than a fifth (the step jumped across the branch or to another
//! mode), or when a requested amplitude inside it cannot be solved near the path.
//! Below [`CORNER_STEP`] a turn of the tangent is accepted: that is a corner of the
//! piecewise smooth branch. Where even the shortest step fails, the branch ends in a
//! corner that turns back: the direction beyond it is the kernel of G_y just past the
//! corner, taken in the orientation that does not return along the old branch; where
//! that fails too, the balance has no solution to the tolerance over a short range of q
//! (its sampled forces jump) and the path jumps over it by Newton at fixed q a little
//! further ([`past_end::jump`]), reporting the range.
//!
//! The requested amplitudes are solved at fixed q wherever the path crosses them, in
//! path order: past a turning point an amplitude is met again.

use nalgebra::{DMatrix, DVector};

mod past_end;

use super::super::BackboneError;
use super::equations::{damped_step, Epmc, Evaluated, State, FLOOR_RTOL, RTOL, STAGNATION};
use crate::linalg;

/// Arclength steps (in y).
const STEP_START: f64 = 0.02;
const STEP_MAX: f64 = 0.3;
const STEP_MIN: f64 = 1e-7;
/// Below this step a turn of the tangent is a corner, not a jump.
const CORNER_STEP: f64 = 1e-4;
/// Points kept to recognize a return along the path.
const BEHIND: usize = 16;
/// Steps along one backbone before it counts as lost.
const MAX_STEPS: usize = 20_000;
/// Steps in a row that reach no farther in ln q (by [`STALL_LNQ`]) before the path is
/// given up as wandering (a rough balance, or modes that exchange energy): the caller
/// then steps in q alone.
const STALL_STEPS: usize = 400;
const STALL_LNQ: f64 = 1e-6;
const WANDERS: &str =
    "the path wanders: many continuation steps in a row reached no farther in the modal amplitude";
const MAX_CORRECTOR: usize = 20;
/// Full steps that raise |F| (at most tenfold) allowed per correction.
const MAX_NONMONOTONE: usize = 3;
/// cos 45°: the largest turn of the tangent per step above [`CORNER_STEP`].
const MIN_TURN_COS: f64 = 0.7;
/// Largest relative change of ω per step above [`CORNER_STEP`].
const MAX_OMEGA_CHANGE: f64 = 0.2;

/// A requested amplitude solved on the path: ln q, the state, the energy per element.
pub type Crossing = (f64, State, Vec<f64>);

/// A converged point of the path.
#[derive(Clone)]
pub struct Node {
    pub y: DVector<f64>,
    pub dissipated: Vec<f64>,
}

/// What the path found: the solutions at the requested amplitudes in path order (ln q
/// of each), the turning points and gaps (modal amplitudes) and why it stopped early, if
/// it did.
pub struct Followed {
    pub crossings: Vec<Crossing>,
    pub turning_points: Vec<f64>,
    /// Ranges of q jumped over (no solution to the tolerance inside) and the requested
    /// amplitudes in them.
    pub gaps: Vec<(f64, f64)>,
    pub skipped: Vec<f64>,
    pub stopped: Option<BackboneError>,
    /// The last point of the path (where it ended or stopped).
    pub end: Crossing,
    /// The largest ln q the path reached.
    pub farthest: f64,
}

struct Path<'e, 'a> {
    ep: &'e mut Epmc<'a>,
    w0: f64,
    /// ‖ψ‖ at the start: ψ enters y as ψ/ψ_s, so every block of y is O(1) (a
    /// mass-normalized FE shape has entries of order 1/√mass).
    psi_scale: f64,
    dim: usize,
}

impl Path<'_, '_> {
    fn to_y(&self, st: &State, lq: f64) -> DVector<f64> {
        let mut y = DVector::zeros(self.dim + 3);
        for (v, p) in y.rows_mut(0, self.dim).iter_mut().zip(&st.psi) {
            *v = p / self.psi_scale;
        }
        y[self.dim] = st.omega / self.w0;
        y[self.dim + 1] = st.xi / self.w0;
        y[self.dim + 2] = lq;
        y
    }

    fn state(&self, y: &DVector<f64>) -> State {
        State {
            psi: y
                .rows(0, self.dim)
                .iter()
                .map(|v| v * self.psi_scale)
                .collect(),
            omega: y[self.dim] * self.w0,
            xi: y[self.dim + 1] * self.w0,
        }
    }

    fn lnq(&self, y: &DVector<f64>) -> f64 {
        y[self.dim + 2]
    }

    fn eval(&mut self, y: &DVector<f64>) -> Option<Evaluated> {
        let st = self.state(y);
        if !(st.omega > 0.0 && y.iter().all(|v| v.is_finite())) {
            return None;
        }
        self.ep.eval(&st, self.lnq(y).exp()).ok()
    }

    /// [G_y; bᵀ] for the border row b.
    fn bordered(&self, ev: &Evaluated, b: &DVector<f64>) -> DMatrix<f64> {
        let d = self.dim;
        let mut a = DMatrix::zeros(d + 3, d + 3);
        a.view_mut((0, 0), (d + 2, d))
            .copy_from(&(ev.jac.columns(0, d) * self.psi_scale));
        for i in 0..d + 2 {
            a[(i, d)] = ev.jac[(i, d)] * self.w0;
            a[(i, d + 1)] = ev.jac[(i, d + 1)] * self.w0;
            a[(i, d + 2)] = ev.d_lnq[i];
        }
        a.view_mut((d + 2, 0), (1, d + 3)).copy_from(&b.transpose());
        a
    }

    /// The unit kernel vector of G_y with bᵀt > 0.
    fn tangent(&self, ev: &Evaluated, b: &DVector<f64>) -> Option<DVector<f64>> {
        let mut e = DVector::zeros(self.dim + 3);
        e[self.dim + 2] = 1.0;
        let t = linalg::solve(&self.bordered(ev, b), &e)?;
        let n = t.norm();
        (n.is_finite() && n > 0.0).then(|| t / n)
    }

    /// Corrector on the hyperplane through `yp` normal to `t`: the point, its
    /// evaluation and the number of evaluations.
    fn correct(&mut self, yp: &DVector<f64>, t: &DVector<f64>) -> Option<(Node, Evaluated, usize)> {
        let mut y = yp.clone();
        let mut ev = self.eval(&y)?;
        let mut res = self.ep.scaled(&ev.f);
        let mut nonmonotone = 0;
        for it in 1..=MAX_CORRECTOR {
            // Any point with F = 0 is on the branch; the hyperplane only makes the
            // system square.
            if res <= RTOL {
                let dissipated = ev.dissipated.clone();
                return Some((Node { y, dissipated }, ev, it));
            }
            let mut g = DVector::zeros(self.dim + 3);
            g.rows_mut(0, self.dim + 2).copy_from(&ev.f);
            g[self.dim + 2] = t.dot(&(&y - yp));
            let dy = linalg::solve(&self.bordered(&ev, t), &g)?;
            if res <= FLOOR_RTOL && dy.norm() <= STAGNATION * y.norm() {
                let dissipated = ev.dissipated.clone();
                return Some((Node { y, dissipated }, ev, it));
            }
            let path = &mut *self;
            let step = damped_step(
                res,
                &mut nonmonotone,
                MAX_NONMONOTONE,
                |lambda| &y - lambda * &dy,
                |trial| {
                    let e2 = path.eval(trial)?;
                    let r2 = path.ep.scaled(&e2.f);
                    Some((e2, r2))
                },
            );
            match step {
                Some(next) => (y, ev, res) = next,
                None => return None,
            }
        }
        None
    }

    /// Newton at fixed ln q = `lq` from the point `guess` of the path.
    fn at_amplitude(&mut self, guess: &DVector<f64>, lq: f64) -> Option<(DVector<f64>, Vec<f64>)> {
        let (st, diss) = self.ep.solve(self.state(guess), lq.exp()).ok()?;
        Some((self.to_y(&st, lq), diss))
    }
}

/// Follows the backbone from `start` (ψ, ω, ξ converged at ln q = `lq0`) up to the
/// largest of `targets` (ln q, ascending, none below `lq0`).
pub fn follow(
    ep: &mut Epmc,
    start: &State,
    lq0: f64,
    dissipated: Vec<f64>,
    w0: f64,
    targets: &[f64],
) -> Followed {
    let dim = start.psi.len();
    let psi_scale = DVector::from_column_slice(&start.psi)
        .norm()
        .max(f64::MIN_POSITIVE);
    let mut p = Path {
        ep,
        w0,
        psi_scale,
        dim,
    };
    let start = Node {
        y: p.to_y(start, lq0),
        dissipated,
    };
    let lq_end = targets.last().copied().unwrap_or(p.lnq(&start.y));
    let mut out = Followed {
        crossings: Vec::new(),
        turning_points: Vec::new(),
        gaps: Vec::new(),
        skipped: Vec::new(),
        stopped: None,
        end: (lq0, p.state(&start.y), start.dissipated.clone()),
        farthest: lq0,
    };
    for &l in targets.iter().filter(|l| **l <= lq0) {
        out.crossings
            .push((l, p.state(&start.y), start.dissipated.clone()));
    }
    let stop = |q: f64, why: &str| BackboneError::PathStopped {
        modal_amplitude: q,
        reason: why.to_string(),
    };
    let mut e_s = DVector::zeros(dim + 3);
    e_s[dim + 2] = 1.0;
    let Some(ev0) = p.eval(&start.y) else {
        out.stopped = Some(stop(lq0.exp(), "the start does not evaluate"));
        return out;
    };
    let Some(mut t) = p.tangent(&ev0, &e_s) else {
        out.stopped = Some(stop(lq0.exp(), "singular Jacobian at the start"));
        return out;
    };
    let mut node = start;
    // The last points passed, so that a corner switch does not return along them.
    let mut behind: Vec<DVector<f64>> = Vec::new();
    let mut step = STEP_START;
    let mut stalled = 0;
    for _ in 0..MAX_STEPS {
        if stalled >= STALL_STEPS {
            out.stopped = Some(stop(p.lnq(&node.y).exp(), WANDERS));
            return out;
        }
        if p.lnq(&node.y) >= lq_end {
            return out;
        }
        let next = match advance(&mut p, &node, &t, step, targets) {
            Some(n) => Some(n),
            None if step * 0.5 >= STEP_MIN => {
                step *= 0.5;
                continue;
            }
            None => past_end::corner(&mut p, &node, &t, &behind, targets)
                .or_else(|| past_end::jump(&mut p, &node, &t, &behind, targets)),
        };
        let Some(adv) = next else {
            out.stopped = Some(stop(
                p.lnq(&node.y).exp(),
                "no branch beyond this point at the shortest step (a corner with no continuation)",
            ));
            return out;
        };
        let (from, reached) = (p.lnq(&node.y), p.lnq(&adv.node.y));
        step = next_step(step, &adv);
        // A turning point: ln q reverses between the two tangents (the step's ends
        // bracket it; the extreme one is reported).
        if t[dim + 2] * adv.t[dim + 2] < 0.0 {
            let q = if t[dim + 2] > 0.0 {
                from.max(reached)
            } else {
                from.min(reached)
            };
            out.turning_points.push(q.exp());
        }
        p.ep.passed(reached.exp());
        out.crossings.extend(adv.crossings);
        if adv.jumped {
            out.gaps
                .push((from.min(reached).exp(), from.max(reached).exp()));
            out.skipped.extend(adv.skipped.iter().map(|l| l.exp()));
        }
        if reached < lq0 - 1.0 {
            out.stopped = Some(stop(
                p.lnq(&adv.node.y).exp(),
                "the backbone turns back below its start",
            ));
            return out;
        }
        // Counts the steps in a row that reach no farther.
        stalled = (stalled + 1) * usize::from(reached <= out.farthest + STALL_LNQ);
        out.farthest = out.farthest.max(reached);
        out.end = (reached, p.state(&adv.node.y), adv.node.dissipated.clone());
        behind.push(std::mem::replace(&mut node, adv.node).y);
        if behind.len() > BEHIND {
            behind.remove(0);
        }
        t = adv.t;
    }
    out.stopped = Some(stop(p.lnq(&node.y).exp(), "too many continuation steps"));
    out
}

/// The step after `adv`: longer after an easy correction, shorter after a hard one,
/// short again after a corner switch.
fn next_step(step: f64, adv: &Advanced) -> f64 {
    let step = if adv.corrector_steps <= 3 {
        (step * 1.5).min(STEP_MAX)
    } else if adv.corrector_steps > 6 {
        (step * 0.7).max(STEP_MIN)
    } else {
        step
    };
    if adv.switched {
        STEP_START.min(step.max(CORNER_STEP))
    } else {
        step
    }
}

/// An accepted step: the new point, its tangent, the requested amplitudes solved on
/// the way.
struct Advanced {
    node: Node,
    t: DVector<f64>,
    crossings: Vec<Crossing>,
    corrector_steps: usize,
    /// Reached by the corner switch.
    switched: bool,
    /// Reached by a jump over a gap ([`past_end::jump`]), with the requested amplitudes in the gap
    /// that have no solution.
    jumped: bool,
    skipped: Vec<f64>,
}

/// One predictor–corrector step of length `step`, or `None` where it is rejected.
fn advance(
    p: &mut Path,
    node: &Node,
    t: &DVector<f64>,
    step: f64,
    targets: &[f64],
) -> Option<Advanced> {
    let yp = &node.y + step * t;
    let (new, ev, its) = p.correct(&yp, t)?;
    let tn = p.tangent(&ev, t)?;
    let d = &new.y - &node.y;
    if t.dot(&d) <= 0.0 {
        return None;
    }
    let dim = p.dim;
    let omega_change = (new.y[dim] / node.y[dim] - 1.0).abs();
    if step > CORNER_STEP && (tn.dot(t) < MIN_TURN_COS || omega_change > MAX_OMEGA_CHANGE) {
        return None;
    }
    let crossings = crossings(p, node, &new, targets)?;
    Some(Advanced {
        node: new,
        t: tn,
        crossings,
        corrector_steps: its,
        switched: false,
        jumped: false,
        skipped: Vec::new(),
    })
}

/// The requested amplitudes between `a` and `b` (in path order), each solved at fixed q
/// from the linear interpolation of the two; `None` if one cannot be solved or its
/// solution lies farther from the interpolation than the step is long (it belongs to
/// another part of the branch).
fn crossings(p: &mut Path, a: &Node, b: &Node, targets: &[f64]) -> Option<Vec<Crossing>> {
    let (found, missed) = crossings_or_missed(p, a, b, targets);
    missed.is_empty().then_some(found)
}

/// [`crossings`] keeping the amplitudes that could not be solved near the path apart.
fn crossings_or_missed(
    p: &mut Path,
    a: &Node,
    b: &Node,
    targets: &[f64],
) -> (Vec<Crossing>, Vec<f64>) {
    let (la, lb) = (p.lnq(&a.y), p.lnq(&b.y));
    let mut hit: Vec<f64> = targets
        .iter()
        .copied()
        .filter(|&l| {
            if lb > la {
                la < l && l <= lb
            } else {
                lb <= l && l < la
            }
        })
        .collect();
    if lb < la {
        hit.reverse();
    }
    let len = (&b.y - &a.y).norm();
    let (mut found, mut missed) = (Vec::with_capacity(hit.len()), Vec::new());
    for l in hit {
        let f = (l - la) / (lb - la);
        let guess = &a.y + f * (&b.y - &a.y);
        match p.at_amplitude(&guess, l) {
            Some((y, diss)) if (&y - &guess).norm() <= len => {
                found.push((l, p.state(&y), diss));
            }
            _ => missed.push(l),
        }
    }
    (found, missed)
}
