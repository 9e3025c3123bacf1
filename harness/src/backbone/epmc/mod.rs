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
//! The backbone starts where every contact sticks and is followed in ln q by
//! pseudo-arclength continuation ([`arclength`]) through turning points; each requested
//! amplitude is solved where the path crosses it, so past a turning point it appears
//! again (the points are in path order). Where the path stops, the remaining amplitudes
//! are approached in q alone ([`stepping`]) and the path resumes from there.

mod arclength;
mod equations;
mod stepping;

use super::first_order::{stick_limit, stuck_mode};
use super::{BackboneError, BackbonePoint, C64};
use crate::mhb::aft::Jacobian;
use crate::mhb::{default_samples, Hb, System};
use equations::{Epmc, State};

/// An EPMC point: the backbone point and the full solution.
#[derive(Debug, Clone)]
pub struct EpmcPoint {
    pub point: BackbonePoint,
    /// Artificial damping ξ (1/time).
    pub xi: f64,
    /// Coefficients of x = qψ, DOF-major (layout of [`crate::mhb::aft`]).
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
    if let Some(&bad) = q.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(BackboneError::Amplitude(bad));
    }
    let free = unforced(sys);
    let (mut ep, guess, w0, lq_stuck) = setup(&free, sys, mode, h, samples)?;
    ep.on_point = Some(on_point);
    let mut targets: Vec<f64> = q.iter().map(|v| v.ln()).collect();
    targets.sort_by(f64::total_cmp);
    targets.dedup();
    let Some(&first) = targets.first() else {
        return Ok(Traced::empty(None));
    };
    // The path starts where every contact still sticks.
    let lq0 = first.min(lq_stuck);
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
        ep.hb.jacobian = Jacobian::Differences;
        let stepped = starts
            .into_iter()
            .map(|s| (s.0, stepping::toward(&mut ep, s, &rest)))
            .find(|(from, s)| s.last.0 > path.farthest.max(*from));
        ep.hb.jacobian = Jacobian::Exact;
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
    out.points = crossings
        .into_iter()
        .map(|(lq, st, diss)| point(&ep.hb, sys, &st, lq.exp(), diss))
        .collect();
    Ok(out)
}

/// The system without its loads (the EPMC motion is free).
fn unforced(sys: &System) -> System {
    let n = sys.n();
    System {
        f0: vec![0.0; n],
        f1: vec![C64::new(0.0, 0.0); n],
        ..sys.clone()
    }
}

/// The EPMC equations of mode `mode` of `free` (the unforced `sys`) at H harmonics and N
/// samples, the stuck mode as the first guess, its ω₀ (rad/time) and the ln q where
/// every contact still sticks (half the first slip limit).
fn setup<'a>(
    free: &'a System,
    sys: &System,
    mode: usize,
    h: usize,
    samples: usize,
) -> Result<(Epmc<'a>, State, f64, f64), BackboneError> {
    let n = sys.n();
    let stuck = stuck_mode(sys, mode)?;
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
        hb: Hb::new(free, h, samples),
        m_ref,
        scale: (w0 * w0).max(f64::MIN_POSITIVE),
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
    let free = unforced(sys);
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
    Ok(s.crossings
        .into_iter()
        .map(|(lq, st, diss)| point(&ep.hb, sys, &st, lq.exp(), diss))
        .collect())
}

fn point(hb: &Hb, sys: &System, st: &State, q: f64, diss: Vec<f64>) -> EpmcPoint {
    let m = hb.tr.ncoef();
    let u: Vec<f64> = st.psi.iter().map(|v| v * q).collect();
    let shape: Vec<C64> = (0..sys.n())
        .map(|d| C64::new(u[d * m + 1], -u[d * m + 2]))
        .collect();
    EpmcPoint {
        point: BackbonePoint {
            modal_amplitude: q,
            omega: st.omega,
            damping_ratio: st.xi / (2.0 * st.omega),
            element_amplitudes: super::first_order::relative(sys, &shape),
            shape,
            energy_per_cycle: diss,
        },
        xi: st.xi,
        u,
    }
}
