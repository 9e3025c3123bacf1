//! The static preload step: K u + f_c(u) = f_pre by Newton's method with a line search
//! on the energy's slope ([`crate::solve::line_search`]), with the contact law of every point from
//! UINTER (LINPER = 0, KSTEP = 1, one increment), as Abaqus would call it; the Newton
//! matrices are factored with UMFPACK's symmetric strategy ([`Symbolic::symmetric`]). The converged pressures are the operating point of the steady-state
//! step; points open here stay open there.
//!
//! Per point, with δ = Qᵀ(u_upper − u_lower) = (δ_n, δ_t₁, δ_t₂): RDISP = S δ with
//! S = diag(−1, 1, 1) (overclosure h = −δ_n), the internal force on the upper node is
//! Q S STRESS · area (minus that on the lower one) and its tangent Q S DDSDDR S Qᵀ · area.
//!
//! With `normal_contact_nonlinearity` off there is no Newton and no C-API call: constant
//! normal springs (`normal_stiffness_per_area`) and stick springs k_T0, one linear solve,
//! pressure = k_N·h (a point in tension counts as open).

use nalgebra::Matrix3;
use thiserror::Error;

use crate::capi::{self, CapiError, UinterPoint, NSTATV};
use crate::model::subgrid::{refine_at_patch_edge, sample_value, EDGE_DEPTH};
use crate::model::{ContactPoint, Problem};
use crate::solve::contact::{interface_props, normal_stiffness};
use crate::solve::umfpack::{Symbolic, UmfpackError};

mod continuation;
mod newton;
use continuation::continuation;
use newton::{Newton, NewtonMatrix};

/// Newton stops when ‖R‖ ≤ this × ‖f_pre‖ (round-off of K u with cond(K) ~1e8 is far
/// below; penalty laws converge in a few steps).
pub const RESIDUAL_TOL: f64 = 1e-9;
/// Newton also stops when ‖R‖ ≤ this × ‖ |K||u| + |f_c| + |f_pre| ‖ (the normwise
/// backward error of the equilibrium, Oettli–Prager): the residual is then at the
/// round-off floor of its own evaluation, which lies above [`RESIDUAL_TOL`] ‖f_pre‖
/// when the interface is much stiffer than the load (k_N·A·|u| ≫ |f|: an interface of
/// 1e7 N/mm³ under a 1 MPa preload measured 2e-7 ‖f_pre‖ there, 5e-14 backward error,
/// iterations then only stirring the last bits). 1e-12 is about 5000 ε. The floor is
/// taken only while ‖R‖ ≤ [`FLOOR_CEILING`] ‖f_pre‖.
pub const BACKWARD_TOL: f64 = 1e-12;
/// The largest ‖R‖/‖f_pre‖ the round-off floor may stop at (measured at the floor:
/// 5e-8 … 1.6e-6 on stuck stacks of 1e6 … 2e8 N/mm³); Abaqus's default force residual
/// tolerance is 5e-3 of the average force.
pub const FLOOR_CEILING: f64 = 1e-5;
/// Most Newton iterations.
pub const MAX_NEWTON: usize = 60;
/// Probe overclosure (relative to the model's size) used for the first tangent: at u = 0
/// every point is just touching and Hertz has no stiffness, so the first Newton matrix
/// takes the points' tangent at this small penetration.
const PROBE_REL: f64 = 1e-7;

/// Newton matrix stand-in for an open point of an interface with an initial gap: this
/// fraction of its probe (just closed) tangent. Open points carry no force and no
/// stiffness, so a part held only by contact across a gap (a blade in a slot with play)
/// would make the Newton matrix singular until it touches; the stand-in keeps it
/// solvable and changes only the steps, never the residual, so the converged state is
/// the exact one. Interfaces without a gap keep the plain Newton matrix. It must stay
/// far below the structure's own stiffness against opening the gap, or the steps
/// that open or close it shrink to a fixed fraction: with 1e-3 the knife's jaws under
/// a screw spread over its bearing ring (a stand-in of ~1e3 N/mm per point against a
/// jaw's ~3e4 N/mm in bending) converged linearly, 0.885 per iteration, and stopped at
/// 60 iterations; with 1e-6 in 13.
const OPEN_STAND_IN: f64 = 1e-6;

/// Errors of the static step.
#[derive(Debug, Error)]
pub enum StaticError {
    #[error(transparent)]
    Capi(#[from] CapiError),
    #[error(transparent)]
    Umfpack(#[from] UmfpackError),
    #[error(
        "static Newton did not converge in {iterations} iterations (‖R‖/‖f‖ = {residual:.3e})"
    )]
    NotConverged { iterations: usize, residual: f64 },
    #[error(
        "static Newton did not converge, also not with the contact force raised gradually \
         from {start:.0e} of its value: it stalled at {alpha:.3e} of it after {iterations} \
         iterations (‖R‖/‖f‖ = {residual:.3e}); an interface far stiffer than the \
         elements beside it (normal or stick stiffness per area × element size ≫ E) \
         makes the pressure alternate from node to node on a non-conforming mesh"
    )]
    Stalled {
        start: f64,
        alpha: f64,
        iterations: usize,
        residual: f64,
    },
}

/// The converged preload state.
#[derive(Debug, Clone)]
pub struct StaticState {
    /// Displacements on the free DOFs.
    pub u: Vec<f64>,
    /// Contact pressure per point (force/length², ≥ 0).
    pub pressure: Vec<f64>,
    /// dp/dh per point at the operating point (force/length³), 0 when open.
    pub normal_stiffness: Vec<f64>,
    pub closed: Vec<bool>,
    /// STATEV per point after the step (p0, h0, closed flag, hysteresis).
    pub statev: Vec<[f64; NSTATV]>,
    /// Per sampled point: (area fraction, normal stress ≥ 0) of each of its area
    /// samples, refined where the final overclosure varies steeply
    /// ([`refine_at_patch_edge`]), for the friction law (empty for a node-based point);
    /// `pressure` is the area average over the unrefined samples.
    pub friction_samples: Vec<Vec<(f64, f64)>>,
    pub newton_iterations: usize,
    /// ‖R‖/‖f_pre‖ at the end.
    pub residual: f64,
    /// ‖R‖/‖ |K||u| + |f_c| + |f_pre| ‖ at the end: the residual against its round-off
    /// floor ([`BACKWARD_TOL`]).
    pub backward_error: f64,
    /// What ended the step: "load tolerance" ([`RESIDUAL_TOL`]), "round-off floor"
    /// ([`BACKWARD_TOL`]), "linear solve" (constant springs) or "nothing to solve".
    pub stopped_by: &'static str,
}

/// Local relative displacement (δ_n, δ_t₁, δ_t₂) of a point.
fn local(c: &ContactPoint, u: &[f64]) -> [f64; 3] {
    std::array::from_fn(|k| c.relative(k, u))
}

fn s_flip(v: [f64; 3]) -> [f64; 3] {
    [-v[0], v[1], v[2]]
}

/// RDISP of a point for local relative displacement δ: (h, δ_t₁, δ_t₂) with the
/// overclosure h = −δ_n − g₀ (g₀ the interface's initial gap).
pub fn overclosure(p: &Problem, c: &ContactPoint, delta: [f64; 3]) -> [f64; 3] {
    let mut r = s_flip(delta);
    r[0] -= p.interfaces[c.interface].initial_gap;
    r
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// A point as UINTER sees it.
pub fn uinter_point<'a>(p: &'a Problem, c: &ContactPoint, props: &'a [f64; 12]) -> UinterPoint<'a> {
    UinterPoint {
        name: &p.interfaces[c.interface].name,
        props,
        coords: c.position,
        area: c.area,
    }
}

struct Eval {
    residual: Vec<f64>,
    /// ‖ |K||u| + |f_c| + |f_pre| ‖: the size of the terms the residual sums.
    scale: f64,
    /// Local tangent (in δ coordinates) per point, × area.
    tangents: Vec<Matrix3<f64>>,
    /// Normal–normal tangent between sampled points: (k, j, ∂(σ_k A_k)/∂h_j).
    couplings: Vec<(usize, usize, f64)>,
    out: Vec<capi::UinterOut>,
    statev: Vec<[f64; NSTATV]>,
    /// Per sampled point: the area average of dσ/dh over its samples (its normal
    /// stiffness per area under a uniform closure).
    sample_stiffness: Vec<Option<f64>>,
}

/// UINTER at every area sample of point `k` (the normal law, linear or Hertz (2.31–2.35),
/// per sample): the overclosure interpolated from the points' overclosures `h`, the
/// tangential slip the point's own. The
/// point's stress and tangent are the area averages (tangent: the part through its own
/// overclosure; the parts through its neighbours' go to `couplings`, × α), and the area
/// average of dσ/dh.
fn sampled_point(
    pt: &UinterPoint,
    c: &ContactPoint,
    k: usize,
    h: &[f64],
    rdisp: [f64; 3],
    alpha: f64,
    couplings: &mut Vec<(usize, usize, f64)>,
) -> Result<(capi::UinterOut, f64), CapiError> {
    let mut mean = capi::UinterOut::default();
    let mut stiffness = 0.0;
    for s in &c.samples {
        let mut sv = [0.0; NSTATV];
        let r = [sample_value(s, h), rdisp[1], rdisp[2]];
        let o = capi::uinter_general(pt, &mut sv, r, r, 1, 1)?;
        for a in 0..3 {
            mean.stress[a] += s.fraction * o.stress[a];
            for b in 0..3 {
                let own = if a == 0 && b == 0 {
                    s.corners.iter().filter(|x| x.0 == k).map(|x| x.1).sum()
                } else {
                    1.0
                };
                mean.ddsddr[a][b] += s.fraction * own * o.ddsddr[a][b];
            }
        }
        mean.closed |= o.closed;
        stiffness += s.fraction * o.ddsddr[0][0];
        for &(j, w) in s.corners.iter().filter(|x| x.0 != k) {
            if o.ddsddr[0][0] != 0.0 {
                couplings.push((k, j, s.fraction * w * o.ddsddr[0][0] * c.area * alpha));
            }
        }
    }
    Ok((mean, stiffness))
}

/// Per point: (fraction, normal stress) at its area samples refined at the patch edge
/// for displacements `u` (UINTER per sample, as [`sampled_point`]); empty when the point
/// is node-based.
fn friction_samples(
    p: &Problem,
    props: &[[f64; 12]],
    u: &[f64],
) -> Result<Vec<Vec<(f64, f64)>>, CapiError> {
    let rdisps: Vec<[f64; 3]> = p
        .contacts
        .iter()
        .map(|c| overclosure(p, c, local(c, u)))
        .collect();
    let h: Vec<f64> = rdisps.iter().map(|r| r[0]).collect();
    let mut out = Vec::with_capacity(p.contacts.len());
    for (c, rdisp) in p.contacts.iter().zip(&rdisps) {
        let pt = uinter_point(p, c, &props[c.interface]);
        let mut list = Vec::new();
        for s in refine_at_patch_edge(&c.samples, &h, EDGE_DEPTH) {
            let mut sv = [0.0; NSTATV];
            let r = [sample_value(&s, &h), rdisp[1], rdisp[2]];
            let o = capi::uinter_general(&pt, &mut sv, r, r, 1, 1)?;
            list.push((s.fraction, o.stress[0].max(0.0)));
        }
        out.push(list);
    }
    Ok(out)
}

/// Residual K u + α f_c(u) − f and per-point tangents (× α), one UINTER call per point;
/// α = 1 is the model, α < 1 a softer contact on the continuation's path
/// ([`continuation::continuation()`]).
fn evaluate(
    p: &Problem,
    props: &[[f64; 12]],
    u: &[f64],
    probe: Option<f64>,
    alpha: f64,
) -> Result<Eval, CapiError> {
    let mut r = p.sys.k.mul_vec(u);
    let mut terms = p.sys.k.abs_mul_vec(u);
    for ((ri, ti), fi) in r.iter_mut().zip(terms.iter_mut()).zip(&p.preload) {
        *ri -= fi;
        *ti += fi.abs();
    }
    let mut tangents = Vec::with_capacity(p.contacts.len());
    let mut outs = Vec::with_capacity(p.contacts.len());
    let mut statevs = Vec::with_capacity(p.contacts.len());
    let mut couplings = Vec::new();
    let mut sample_stiffness = Vec::with_capacity(p.contacts.len());
    let rdisps: Vec<[f64; 3]> = p
        .contacts
        .iter()
        .map(|c| match probe {
            Some(h) => [h, 0.0, 0.0],
            None => overclosure(p, c, local(c, u)),
        })
        .collect();
    let h: Vec<f64> = rdisps.iter().map(|r| r[0]).collect();
    for (k, c) in p.contacts.iter().enumerate() {
        let pr = &props[c.interface];
        let pt = uinter_point(p, c, pr);
        let rdisp = rdisps[k];
        let mut sv = [0.0; NSTATV];
        // A sampled point keeps this call's STATEV (its node's state) and takes its
        // stress and tangent from the samples.
        let mut out = capi::uinter_general(&pt, &mut sv, rdisp, rdisp, 1, 1)?;
        if probe.is_none() && !c.samples.is_empty() {
            let (mean, kn) = sampled_point(&pt, c, k, &h, rdisp, alpha, &mut couplings)?;
            out.stress = mean.stress;
            out.ddsddr = mean.ddsddr;
            out.closed = mean.closed;
            sample_stiffness.push(Some(kn));
        } else {
            sample_stiffness.push(None);
        }
        if probe.is_none() {
            let f = s_flip(out.stress);
            for k in 0..3 {
                for &(i, w) in &c.rows[k] {
                    r[i] += w * f[k] * c.area * alpha;
                    terms[i] += (w * f[k] * c.area * alpha).abs();
                }
            }
        }
        let d = Matrix3::from_fn(|i, j| out.ddsddr[i][j]);
        let s = Matrix3::from_diagonal(&nalgebra::Vector3::new(-1.0, 1.0, 1.0));
        tangents.push(s * d * s * c.area * alpha);
        outs.push(out);
        statevs.push(sv);
    }
    Ok(Eval {
        residual: r,
        scale: norm(&terms),
        tangents,
        couplings,
        out: outs,
        statev: statevs,
        sample_stiffness,
    })
}

/// Solves the preload step.
pub fn solve(p: &Problem, nonlinear: bool) -> Result<StaticState, StaticError> {
    if p.contacts.is_empty() && p.preload.iter().all(|&f| f == 0.0) {
        // K u = 0: nothing to factor (a free structure's singular K included).
        return Ok(StaticState {
            u: vec![0.0; p.preload.len()],
            pressure: Vec::new(),
            normal_stiffness: Vec::new(),
            closed: Vec::new(),
            statev: Vec::new(),
            friction_samples: Vec::new(),
            newton_iterations: 0,
            residual: 0.0,
            backward_error: 0.0,
            stopped_by: "nothing to solve",
        });
    }
    let props: Vec<[f64; 12]> = p.interfaces.iter().map(interface_props).collect();
    let matrix = NewtonMatrix {
        p,
        sym: Symbolic::symmetric(p.sys.pattern.clone())?,
    };
    if !nonlinear {
        return constant_springs(p, &matrix);
    }
    // Size of the model, for the probe overclosure.
    let extent = p
        .model
        .nodes
        .iter()
        .flat_map(|x| x.iter().copied())
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(1.0);
    let newton = Newton {
        p,
        props: &props,
        matrix,
        fnorm: norm(&p.preload).max(f64::MIN_POSITIVE),
        probe: evaluate(
            p,
            &props,
            &vec![0.0; p.sys.dofs.n_free()],
            Some(PROBE_REL * extent),
            1.0,
        )?
        .tangents,
    };
    let start = vec![0.0; p.sys.dofs.n_free()];
    let done = match newton.run(
        start,
        1.0,
        newton.probe.clone(),
        Vec::new(),
        (RESIDUAL_TOL, MAX_NEWTON),
    ) {
        Err(StaticError::NotConverged { .. }) => continuation(&newton),
        other => other,
    }?;
    let ev = done.eval;
    let ev_scale = ev.scale.max(f64::MIN_POSITIVE);
    let pressure = ev.out.iter().map(|o| o.stress[0].max(0.0)).collect();
    let normal_stiffness = ev
        .out
        .iter()
        .zip(&ev.sample_stiffness)
        .map(|(o, s)| match (o.closed, s) {
            (false, _) => 0.0,
            (true, Some(kn)) => *kn,
            (true, None) => o.ddsddr[0][0],
        })
        .collect();
    let closed = ev.out.iter().map(|o| o.closed).collect();
    let friction_samples = friction_samples(p, &props, &done.u)?;
    Ok(StaticState {
        u: done.u,
        pressure,
        normal_stiffness,
        closed,
        statev: ev.statev,
        friction_samples,
        newton_iterations: done.iterations,
        residual: done.residual,
        backward_error: done.residual * newton.fnorm / ev_scale,
        stopped_by: done.stopped_by,
    })
}

/// Constant springs: k_N normal, k_T0 tangential (stick), one linear solve, no C-API call.
fn constant_springs(p: &Problem, matrix: &NewtonMatrix) -> Result<StaticState, StaticError> {
    let tangents: Vec<Matrix3<f64>> = p
        .contacts
        .iter()
        .map(|c| {
            let i = &p.interfaces[c.interface];
            let kn = normal_stiffness(i);
            Matrix3::from_diagonal(&nalgebra::Vector3::new(
                kn,
                i.contact.k_t0_per_area,
                i.contact.k_t0_per_area,
            )) * c.area
        })
        .collect();
    let (u, r, terms) = matrix.solve_checked(&tangents, &p.preload)?;
    let mut pressure = Vec::new();
    let mut closed = Vec::new();
    let mut kn = Vec::new();
    let mut statev = Vec::new();
    for c in &p.contacts {
        let i = &p.interfaces[c.interface];
        let h = -c.relative(0, &u) - i.initial_gap;
        let pr = (normal_stiffness(i) * h).max(0.0);
        pressure.push(pr);
        closed.push(pr > 0.0);
        kn.push(normal_stiffness(i));
        statev.push([0.0; NSTATV]);
    }
    Ok(StaticState {
        u,
        pressure,
        normal_stiffness: kn,
        closed,
        statev,
        friction_samples: vec![Vec::new(); p.contacts.len()],
        newton_iterations: 0,
        residual: r / norm(&p.preload).max(f64::MIN_POSITIVE),
        backward_error: r / terms.max(f64::MIN_POSITIVE),
        stopped_by: "linear solve",
    })
}

#[cfg(test)]
mod tests;
