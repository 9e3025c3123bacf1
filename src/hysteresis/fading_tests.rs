//! The thesis rule's fading memory (`thesis.rs` module docs; model.md §4 "Shallow
//! excursions"): continuous where the force changes sign, the thesis rule itself for
//! every excursion of a quarter of the branch before it, and exact derivatives on the
//! branches in between.

use super::*;
use crate::law::{Backbone, TangentialLaw};

fn mindlin() -> Backbone {
    Backbone::new(TangentialLaw::Mindlin, 0.6, 1282.7).unwrap()
}

/// Forces along `path` (each leg in `substeps` steps) from a virgin point.
fn forces(p: &Point, path: &[f64], substeps: usize) -> Vec<f64> {
    let mut st = PointState::virgin(p.rule, 0.0);
    let mut out = Vec::new();
    for w in path.windows(2) {
        for i in 1..=substeps {
            let target = w[0] + (w[1] - w[0]) * i as f64 / substeps as f64;
            let (next, r) = p.step(&st, target).unwrap();
            st = next;
            out.push(r.force);
        }
    }
    out
}

/// Loaded to 0.8 δ* and unloaded: a turn ε before the elastic line's zero-force point runs
/// back up the line; one ε past it (the force has changed sign) keeps the memory of the
/// branch it left, so the rest of the path differs by O(k_T0 ε), not by the k_T0 d²/4δ*
/// of a fresh virgin branch (model.md §4).
#[test]
fn a_turn_just_past_zero_force_continues_as_one_just_before_it() {
    let b = mindlin();
    let p = Point::new(b, Rule::Thesis);
    let d = b.slip_limit();
    let top = 0.8 * d;
    let zero = top - b.force(top) / b.k_t0();
    for eps in [1e-6 * d, 1e-9 * d] {
        let run = |turn: f64| forces(&p, &[0.0, top, turn, 0.9 * d, -0.5 * d, 0.3 * d], 40);
        let (before, after) = (run(zero + eps), run(zero - eps));
        let jump = (0..before.len()).fold(0.0, |m: f64, k| m.max((before[k] - after[k]).abs()));
        assert!(
            jump <= 10.0 * b.k_t0() * eps,
            "ε = {eps:e}: {jump:e} against k_T0 ε = {:e}",
            b.k_t0() * eps
        );
    }
}

/// An excursion past zero force that spans at least a quarter of the branch before it
/// reloads as the thesis rule: elastically to zero force, then along g from there; a
/// shallower one reloads stiffer, between that and the elastic line.
#[test]
fn an_excursion_of_a_quarter_of_the_branch_before_follows_the_thesis_rule() {
    let b = mindlin();
    let (p, k0) = (Point::new(b, Rule::Thesis), b.k_t0());
    let d = b.slip_limit();
    let top = 0.8 * d;
    let zero = top - b.force(top) / k0;
    // The first branch spans `top` (virgin from 0); the excursion from `zero` is `depth`.
    let reload = |depth: f64| {
        let turn = zero - depth;
        let next_zero = turn + b.force(depth) / k0;
        let at = next_zero + 0.3 * d;
        let f = *forces(&p, &[0.0, top, turn, at], 30).last().unwrap();
        (f, b.force(0.3 * d), k0 * 0.3 * d)
    };
    for depth in [0.25 * top, 0.3 * top, 0.9 * top] {
        let (f, thesis, _) = reload(depth);
        assert!(
            (f - thesis).abs() <= 1e-12 * thesis,
            "{depth:e}: {f} {thesis}"
        );
    }
    for depth in [0.01 * top, 0.1 * top, 0.2 * top] {
        let (f, thesis, line) = reload(depth);
        assert!(
            f > thesis * (1.0 + 1e-6) && f <= line * (1.0 + 1e-12),
            "{depth:e}: {f} {thesis} {line}"
        );
    }
}

/// d(slot)/dp of a stored state, one parameter.
struct Column {
    d: [f64; STATE_LEN],
    d_slip: f64,
}

impl Tangents for Column {
    fn set(&mut self, dst: usize, terms: &[(usize, f64)], target: f64) {
        self.d[dst] = terms.iter().fold(target * self.d_slip, |acc, &(slot, k)| {
            acc + k * self.d[slot]
        });
    }
}

/// Slips (units of δ*) of loops ±0.6 δ* whose every unloading turns back just past the
/// zero-force point (by `depths[i]` × 1.2 δ*, a few per cent of the branch before) and
/// reloads to 0.7 δ* before the next half loop, sub-stepped; built by marching `p`.
fn shallow_turns(p: &Point, depths: &[f64]) -> Vec<f64> {
    let (d, k0) = (p.backbone.slip_limit(), p.backbone.k_t0());
    let mut st = PointState::virgin(Rule::Thesis, 0.0);
    let mut path = Vec::new();
    let mut go = |to: f64, st: &mut PointState| {
        let from = st.slip();
        for i in 1..=12 {
            let s = from + (to - from) * i as f64 / 12.0;
            *st = p.step(st, s).unwrap().0;
            path.push(s / d);
        }
    };
    for (i, depth) in depths.iter().enumerate() {
        let dir = if i % 2 == 0 { 1.0 } else { -1.0 };
        go(dir * 0.6 * d, &mut st);
        let zero = st.slip() - st.force() / k0;
        let turn = zero - dir * depth * 1.2 * d;
        go(turn, &mut st);
        go(dir * 0.7 * d, &mut st);
    }
    path
}

/// The tangent-linear step on a path whose minor reversals enter faded branches (an
/// origin strictly between the zero-force point and the memory's) equals central
/// differences of the marched forces.
#[test]
fn derivatives_through_faded_branches_equal_central_differences() {
    let b = mindlin();
    let (p, k0) = (Point::new(b, Rule::Thesis), b.k_t0());
    let d = b.slip_limit();
    let path = shallow_turns(&p, &[0.02, 0.05, 0.1, 0.15, 0.2, 0.03, 0.08, 0.3]);
    let wiggle = |k: usize| (path[k], (0.37 * k as f64).cos());
    let steps = path.len();
    let march = |h: f64| {
        let mut st = PointState::virgin(Rule::Thesis, 0.0);
        (0..steps)
            .map(|k| {
                let (s, dir) = wiggle(k);
                let (next, r) = p.step(&st, d * (s + h * dir)).unwrap();
                st = next;
                r.force
            })
            .collect::<Vec<_>>()
    };
    let mut st = PointState::virgin(Rule::Thesis, 0.0);
    let mut col = Column {
        d: [0.0; STATE_LEN],
        d_slip: 0.0,
    };
    let (mut exact, mut faded) = (Vec::new(), 0);
    for k in 0..steps {
        let (s, dir) = wiggle(k);
        col.d_slip = d * dir;
        let (next, _) = p.step_with_tangents(&st, d * s, &mut col).unwrap();
        if let (PointState::Thesis(a), PointState::Thesis(n)) = (&st, &next) {
            let zero = n.rev_slip - n.rev_force / k0;
            if a.unloading && !n.unloading && n.dir != a.dir && (n.origin - zero).abs() > 1e-9 * d {
                faded += 1;
            }
        }
        st = next;
        exact.push(col.d[FORCE_SLOT]);
    }
    let h = 1e-7;
    let (plus, minus) = (march(h), march(-h));
    let worst = (0..steps)
        .map(|k| ((plus[k] - minus[k]) / (2.0 * h) - exact[k]).abs())
        .fold(0.0, f64::max);
    assert!(faded >= 3, "{faded} faded branches");
    assert!(worst <= 1e-6 * 0.6, "{worst:e} μF_N per δ*");
}
