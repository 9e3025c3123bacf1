//! Extended periodic motion concept (Krack, "Nonlinear modal analysis of nonconservative
//! systems: extension of the periodic motion concept", Computers & Structures 154, 2015):
//! the free system with an artificial term −ξMẋ,
//!
//!   M ẍ + (D − ξM) ẋ + K x + Σ_e Pₑᵀ Fₑ(Pₑ x) = 0,
//!
//! has periodic solutions; ξ is the energy the mode loses per cycle. With x = q ψ
//! (harmonic balance at H harmonics, forces by the AFT of [`crate::mhb::aft`]), the
//! unknowns (ψ, ω, ξ) solve the equations of [`equations`]: normalization ψ₁ᴴMψ₁ = 1
//! (first harmonic, so q is the modal amplitude of [`super`]) and phase φ_rᵀMb₁ = 0.
//! Damping ratio ζ = ξ/(2ω) (Krack 2015, eq. 14). At H = 1 with the loop's own first
//! harmonic this is the first-order backbone up to the O(ζ²) difference between |λ| and
//! the frequency of the damping-compensated motion.
//!
//! Three-direction points (`mhb::contact3d`: the normal force varies, the point may lift
//! off, both tangential directions share one slip limit) take part through their AFT; the
//! motion is then about the static state x_s (the static step with every contact stuck,
//! `model::lumped_static`): x = x_s + qψ. Their stuck mode and first slip limit come from
//! the same system linearized at x_s: each point as the thesis's model at its static
//! normal force (two tangential 1D elements and the closed contact's normal spring).
//!
//! The start is the stuck mode (within a pair at one frequency, turned to a branch's
//! start: [`super::degenerate`]) with ω and ξ of the system linearized at the start's
//! motion ([`rayleigh`]); a mean nothing but friction resists is held by the gauge
//! spring of [`equations`] (docs/backbone-fe.md "Where the EPMC starts").
//!
//! The backbone starts where every contact sticks and is followed in ln q by
//! pseudo-arclength continuation ([`arclength`]) through turning points; each requested
//! amplitude is solved where the path crosses it, so past a turning point it appears
//! again (the points are in path order). Where the path stops, the remaining amplitudes
//! are approached in q alone ([`stepping`]) and the path resumes from there.

mod arclength;
mod equations;
mod stepping;

use nalgebra::DMatrix;

use super::degenerate::start_mode;
use super::first_order::{rayleigh, stick_limit};
use super::{BackboneError, BackbonePoint, C64};
use crate::mhb::aft::Jacobian;
use crate::mhb::contact3d::{Hb3, System3};
use crate::mhb::{default_samples, MhbError, System};
use crate::model::lumped_static;
use equations::{Epmc, State};

/// Decades below the first slip limit where the path starts at the lowest.
const STUCK_DECADES: f64 = 6.0;

/// An EPMC point: the backbone point and the full solution.
#[derive(Debug, Clone)]
pub struct EpmcPoint {
    pub point: BackbonePoint,
    /// Artificial damping ξ (1/time).
    pub xi: f64,
    /// Coefficients of the vibration qψ about the static state, DOF-major (layout of
    /// [`crate::mhb::aft`]).
    pub u: Vec<f64>,
}

/// The EPMC backbone of mode `mode` (1-based) at H harmonics (N samples by
/// [`default_samples`]) at the modal amplitudes `q`.
pub fn backbone(
    sys: &System,
    mode: usize,
    h: usize,
    q: &[f64],
) -> Result<Vec<EpmcPoint>, BackboneError> {
    backbone_sampled(sys, mode, h.max(1), default_samples(h.max(1)), q)
}

/// [`backbone`] with N samples per period (at least 2H + 2).
pub fn backbone_sampled(
    sys: &System,
    mode: usize,
    h: usize,
    samples: usize,
    q: &[f64],
) -> Result<Vec<EpmcPoint>, BackboneError> {
    let t = trace(sys, mode, h, samples, q)?;
    if let Some(e) = t.stopped {
        return Err(e);
    }
    match t.skipped.first() {
        Some(&q) => Err(BackboneError::PathStopped {
            modal_amplitude: q,
            reason: "no solution to the tolerance here (the path jumped over it)".into(),
        }),
        None => Ok(t.points),
    }
}

/// The points of [`backbone_sampled`] in path order up to where the continuation
/// stopped, the turning points passed (modal amplitudes where q reverses) and why it
/// stopped, if it did.
#[derive(Debug)]
pub struct Traced {
    pub points: Vec<EpmcPoint>,
    pub turning_points: Vec<f64>,
    /// Ranges of q with no solution to the tolerance that the path jumped over, and the
    /// requested amplitudes inside them (not in `points`).
    pub gaps: Vec<(f64, f64)>,
    pub skipped: Vec<f64>,
    /// Ranges of q (from, to) continued in q alone where the arclength path stopped
    /// ([`stepping`]): turning points in them are not followed.
    pub fixed_q: Vec<(f64, f64)>,
    pub stopped: Option<BackboneError>,
}

impl Traced {
    /// No points, and why (`None`: nothing was asked).
    fn empty(stopped: Option<BackboneError>) -> Self {
        Traced {
            points: Vec::new(),
            turning_points: Vec::new(),
            gaps: Vec::new(),
            skipped: Vec::new(),
            fixed_q: Vec::new(),
            stopped,
        }
    }
}

/// [`backbone_sampled`] keeping the points converged before a failure. Errors that
/// concern the whole run (no such mode, a bad amplitude) are `Err`.
pub fn trace(
    sys: &System,
    mode: usize,
    h: usize,
    samples: usize,
    q: &[f64],
) -> Result<Traced, BackboneError> {
    trace_observed(sys, mode, h, samples, q, &|_| {})
}

/// [`trace`] telling `on_point` every modal amplitude it finds a solution at.
pub fn trace_observed(
    sys: &System,
    mode: usize,
    h: usize,
    samples: usize,
    q: &[f64],
    on_point: &dyn Fn(f64),
) -> Result<Traced, BackboneError> {
    let full = System3 {
        linear: sys.clone(),
        elements: Vec::new(),
    };
    trace_points(&full, sys, mode, h, samples, q, on_point)
}

/// [`trace_observed`] of a system with three-direction points, `full`, and the same
/// system linearized at its static state, `linearized` (module docs; the same DOFs).
pub fn trace_points(
    full: &System3,
    linearized: &System,
    mode: usize,
    h: usize,
    samples: usize,
    q: &[f64],
    on_point: &dyn Fn(f64),
) -> Result<Traced, BackboneError> {
    if let Some(&bad) = q.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(BackboneError::Amplitude(bad));
    }
    let sys = linearized;
    let free = unforced(full);
    let (mut ep, guess, w0, lq_stuck) = setup(&free, sys, mode, h, samples)?;
    ep.on_point = Some(on_point);
    let mut targets: Vec<f64> = q.iter().map(|v| v.ln()).collect();
    targets.sort_by(f64::total_cmp);
    targets.dedup();
    let Some(&first) = targets.first() else {
        return Ok(Traced::empty(None));
    };
    // The path starts where every contact still sticks, at most STUCK_DECADES below
    // the stick limit: the backbone is the stuck linear mode all the way down, and far
    // below, the motion is round-off against the static state (amplitudes there are
    // given the start's solution).
    let lq0 = first
        .min(lq_stuck)
        .max(lq_stuck - STUCK_DECADES * std::f64::consts::LN_10);
    let guess = at_amplitude(sys, guess, lq0.exp(), ep.hb.ncoef())?;
    let (st, dissipated) = match ep.solve(guess, lq0.exp()) {
        Ok(s) => s,
        Err(residual) => {
            return Ok(Traced::empty(Some(BackboneError::NotConverged {
                modal_amplitude: lq0.exp(),
                residual,
            })))
        }
    };
    let mut out = Traced::empty(None);
    let mut crossings = Vec::new();
    let mut resume = (lq0, st, dissipated);
    // Every round either reaches farther in q or ends.
    for _ in 0..targets.len() + 1 {
        let path = arclength::follow(&mut ep, &resume.1, resume.0, resume.2, w0, &targets);
        crossings.extend(path.crossings);
        out.turning_points.extend(path.turning_points);
        out.gaps.extend(path.gaps);
        out.skipped.extend(path.skipped);
        let Some(why) = path.stopped else { break };
        // Where the path stops, step in q alone to the amplitudes beyond the farthest
        // reached, from the path's end or else from the largest amplitude solved.
        let rest: Vec<f64> = targets
            .iter()
            .copied()
            .filter(|l| *l > path.farthest)
            .collect();
        let mut starts = vec![path.end];
        if let Some(c) = crossings.iter().max_by(|a, b| a.0.total_cmp(&b.0)) {
            starts.push(c.clone());
        }
        // Where the path stopped the balance is rough (sampled loops' kinks): Newton at
        // fixed q with difference Jacobians, which straddle the kinks.
        ep.hb.set_jacobian(Jacobian::Differences);
        let stepped = starts
            .into_iter()
            .map(|s| (s.0, stepping::toward(&mut ep, s, &rest)))
            .find(|(from, s)| s.last.0 > path.farthest.max(*from));
        ep.hb.set_jacobian(Jacobian::Exact);
        let Some((from, stepped)) = stepped else {
            out.stopped = Some(why);
            break;
        };
        out.fixed_q.push((from.exp(), stepped.last.0.exp()));
        crossings.extend(stepped.crossings);
        if stepped.failed.is_none() {
            break;
        }
        resume = stepped.last;
        targets.retain(|l| *l > resume.0);
        if targets.is_empty() {
            break;
        }
    }
    out.points = points(&mut ep, sys, crossings)?;
    Ok(out)
}

/// The stuck guess with ω and ξ of the first-order estimate at modal amplitude q
/// ([`rayleigh`]): Mindlin points soften from the first micrometre, and at the stuck
/// ω a pair partner the motion leaves stuck (the block's other sliding direction) is
/// exactly resonant, a singular Jacobian at the start.
fn at_amplitude(sys: &System, mut guess: State, q: f64, m: usize) -> Result<State, BackboneError> {
    let shape: Vec<C64> = (0..sys.n())
        .map(|d| C64::new(guess.psi[d * m + 1], -guess.psi[d * m + 2]))
        .collect();
    let (omega, xi) = rayleigh(sys, &shape, q, guess.omega)?;
    if omega.is_finite() && omega > 0.0 && xi.is_finite() {
        guess.omega = omega;
        guess.xi = xi;
    }
    Ok(guess)
}

/// The system without its harmonic load (the EPMC motion is free); without points its
/// static load too (one-direction joints at a fixed normal force: the motion is about
/// x = 0), with them the static load stays (it sets their normal forces).
fn unforced(sys: &System3) -> System3 {
    let mut free = sys.clone();
    let n = free.linear.n();
    free.linear.f1 = vec![C64::new(0.0, 0.0); n];
    if free.elements.is_empty() {
        free.linear.f0 = vec![0.0; n];
    }
    free
}

/// The static state of `free` in the coefficients' layout (its mean only).
fn static_state(free: &System3, m: usize) -> Result<Vec<f64>, BackboneError> {
    let n = free.linear.n();
    let mut rest = vec![0.0; n * m];
    if free.linear.f0.iter().all(|f| *f == 0.0) && free.elements.is_empty() {
        return Ok(rest);
    }
    let names: Vec<String> = (1..=free.elements.len())
        .map(|k| format!("point {k}"))
        .collect();
    let st = lumped_static::solve(free, &names)
        .map_err(|e| BackboneError::Mhb(MhbError::Continuation(e)))?;
    for (d, x) in st.x.iter().enumerate() {
        rest[d * m] = *x;
    }
    Ok(rest)
}

/// The EPMC equations of mode `mode` of `free` (the unforced `sys`) at H harmonics and N
/// samples, the stuck mode as the first guess, its ω₀ (rad/time) and the ln q where
/// every contact still sticks (half the first slip limit).
fn setup<'a>(
    free: &'a System3,
    sys: &System,
    mode: usize,
    h: usize,
    samples: usize,
) -> Result<(Epmc<'a>, State, f64, f64), BackboneError> {
    let n = sys.n();
    let stuck = start_mode(sys, mode)?;
    let h = h.max(1);
    let samples = samples.max(2 * h + 2);
    let m = 2 * h + 1;
    let mut psi = vec![0.0; n * m];
    for d in 0..n {
        psi[d * m + 1] = stuck.shape[d].re;
        psi[d * m + 2] = -stuck.shape[d].im;
    }
    let phi_r: Vec<f64> = stuck.shape.iter().map(|v| v.re).collect();
    let m_ref: Vec<f64> = (0..n)
        .map(|a| (0..n).map(|b| sys.m[(a, b)] * phi_r[b]).sum())
        .collect();
    let w0 = stuck.omega();
    let ep = Epmc {
        hb: Hb3::new(free, h, samples),
        rest: static_state(free, m)?,
        m_ref,
        scale: (w0 * w0).max(f64::MIN_POSITIVE),
        gauge: equations::gauge_spring(&resisting(free, sys)),
        on_point: None,
    };
    let guess = State {
        psi,
        omega: w0,
        xi: 2.0 * stuck.damping_ratio() * w0,
    };
    let lq_stuck = (0.5 * stick_limit(sys, &stuck.shape)?).ln();
    Ok((ep, guess, w0, lq_stuck))
}

/// The stiffness that resists a mean motion whatever the joints do: the linearized
/// system's `sys` (its 1D joints apart) with the normal springs k_N of `free`'s
/// three-direction points (their normal mean is set by the contact, not a gauge).
fn resisting(free: &System3, sys: &System) -> DMatrix<f64> {
    let mut k = sys.k.clone();
    for e in &free.elements {
        for &(p, wp) in &e.rows[2] {
            for &(q, wq) in &e.rows[2] {
                k[(p, q)] += e.contact.k_n * wp * wq;
            }
        }
    }
    k
}

/// The backbone at `q` (ascending) by [`stepping`] alone from the stuck start, to
/// compare with the arclength path where both apply.
#[cfg(test)]
pub fn amplitude_stepping(
    sys: &System,
    mode: usize,
    h: usize,
    samples: usize,
    q: &[f64],
) -> Result<Vec<EpmcPoint>, BackboneError> {
    let free = unforced(&System3 {
        linear: sys.clone(),
        elements: Vec::new(),
    });
    let (mut ep, guess, _, lq0) = setup(&free, sys, mode, h, samples)?;
    let (st, diss) =
        ep.solve(guess, lq0.exp())
            .map_err(|residual| BackboneError::NotConverged {
                modal_amplitude: lq0.exp(),
                residual,
            })?;
    let targets: Vec<f64> = q.iter().map(|v| v.ln()).collect();
    let s = stepping::toward(&mut ep, (lq0, st, diss), &targets);
    if let Some(residual) = s.failed {
        return Err(BackboneError::NotConverged {
            modal_amplitude: s.last.0.exp(),
            residual,
        });
    }
    points(&mut ep, sys, s.crossings)
}

/// The EPMC points of the solutions found, in path order.
fn points(
    ep: &mut Epmc,
    sys: &System,
    found: Vec<(f64, State, Vec<f64>)>,
) -> Result<Vec<EpmcPoint>, BackboneError> {
    found
        .into_iter()
        .map(|(lq, st, diss)| point(ep, sys, &st, lq.exp(), diss))
        .collect()
}

/// One point: the 1D elements' relative amplitudes (of `sys`, the linearized system)
/// and each three-direction point's tangential amplitude (the semi-major axis of its
/// first-harmonic ellipse) and normal force range.
fn point(
    ep: &mut Epmc,
    sys: &System,
    st: &State,
    q: f64,
    diss: Vec<f64>,
) -> Result<EpmcPoint, BackboneError> {
    let m = ep.hb.ncoef();
    let u: Vec<f64> = st.psi.iter().map(|v| v * q).collect();
    let shape: Vec<C64> = (0..sys.n())
        .map(|d| C64::new(u[d * m + 1], -u[d * m + 2]))
        .collect();
    let full = ep.hb.system();
    let mut element_amplitudes = super::first_order::relative(&full.linear, &shape);
    for e in &full.elements {
        let first = |a: usize| e.rows[a].iter().map(|&(d, w)| shape[d] * w).sum::<C64>();
        element_amplitudes.push(semi_major(first(0), first(1)));
    }
    let normal_range = if full.elements.is_empty() {
        Vec::new()
    } else {
        let x: Vec<f64> = u.iter().zip(&ep.rest).map(|(v, r)| v + r).collect();
        ep.hb.normal_ranges(&x)?
    };
    Ok(EpmcPoint {
        point: BackbonePoint {
            modal_amplitude: q,
            omega: st.omega,
            damping_ratio: st.xi / (2.0 * st.omega),
            element_amplitudes,
            shape,
            energy_per_cycle: diss,
            normal_range,
        },
        xi: st.xi,
        u,
    })
}

/// The largest |Re((a, b) e^{iθ})| over θ: the semi-major axis of the ellipse a
/// two-component first harmonic (a, b) draws (|a| for a line along the first component,
/// the radius for a circle).
fn semi_major(a: C64, b: C64) -> f64 {
    let p = a.norm_sqr() + b.norm_sqr();
    // Re(v e^{iθ}) = cos θ·Re v − sin θ·Im v; its squared length is
    // p/2 + (c·cos 2θ − s·sin 2θ)/2 with c = |Re v|² − |Im v|², s = 2 Re v·Im v.
    let c = a.re * a.re + b.re * b.re - a.im * a.im - b.im * b.im;
    let s2 = 2.0 * (a.re * a.im + b.re * b.im);
    (0.5 * (p + c.hypot(s2))).max(0.0).sqrt()
}
