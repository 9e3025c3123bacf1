//! First-order backbone: at modal amplitude q, the complex mode of
//! λ²M + λ(D + Σ Pᵀd*P) + (K + Σ Pᵀk*P) whose contact amplitudes A_e = q·|P_e φ|
//! (φᴴMφ = 1) are those k*, d* were taken at (docs/model.md §3; k* (3.8), d* (3.14) of
//! the thesis through `jointlin_linearize`; cubic springs k* = ¾k₃A², d* = 0), and whose
//! |λ| is the ω d* was taken at. The fixed point (A_e, ω) is found by
//! [`crate::mhb::consistency`]; each amplitude starts from the previous one and follows
//! the mode by MAC. Frequency |λ|, damping ratio −Re λ/|λ|.
//!
//! Large systems (a reduced FE model: a hundred joints, a few hundred DOFs) take two
//! cheaper steps with the same fixed point: above [`ALL_MODES_MAX`] DOFs the traced mode
//! is continued from the previous one ([`track`]) instead of computing every mode, and
//! above [`NEWTON_MAX`] elements the amplitudes are iterated by Anderson acceleration in
//! ln A (one mode per iteration, as the FE sweep's fast mode) instead of Newton with a
//! forward-difference Jacobian (elements + 1 modes per iteration).

use nalgebra::DMatrix;

use super::modes::{complex_modes, mac, normalize, pick, track, Mode, C64};
use super::{BackboneError, BackbonePoint};
use crate::capi;
use crate::mhb::{consistency, Law, System};
use crate::solve::sweep::anderson::Anderson;

/// Relative tolerance of the consistency (amplitudes and ω).
const TOL: f64 = 1e-10;
const MAX_ITER: usize = 60;
/// Every mode (and the pick by MAC) up to this many DOFs; above, the traced mode is
/// refined from the previous one: every mode of a 150-DOF reduced model costs seconds
/// (a singular-value decomposition and refinement per mode), one mode milliseconds.
pub const ALL_MODES_MAX: usize = 40;
/// Newton with a forward-difference Jacobian up to this many elements; above, Anderson.
pub const NEWTON_MAX: usize = 8;
/// A refined mode whose MAC with the previous one is below this is a different mode: the
/// step falls back to every mode and the pick by MAC.
const MAC_MIN: f64 = 0.9;
/// Anderson: history depth, most iterations, and the fraction of the largest amplitude
/// below which an amplitude is round-off (floored there in ln A and left out of the
/// mismatch; its k* differs from k_T0 by O(A/δ*), see `solve::sweep::fast`).
const ANDERSON_DEPTH: usize = 5;
const ANDERSON_MAX_ITER: usize = 200;
const ZERO_AMP_REL: f64 = 1e-9;
/// Round-off floor: when the mismatch has not fallen below its best for
/// [`ANDERSON_STALL`] steps and that best is at most this, the amplitudes are consistent
/// to working accuracy (an element moving 3e-5 of the largest carries the mode shape's
/// round-off, ~1e-8 relative on a reduced model with stiff contacts), not unconverged.
const ROUNDOFF_MISMATCH: f64 = 1e-6;
const ANDERSON_STALL: usize = 20;
/// The Anderson iteration, as named in messages.
const ANDERSON_METHOD: &str = "Anderson acceleration in ln A";

/// k* and d* of every element at amplitudes `amp` and ω.
fn linearized(
    sys: &System,
    amp: &[f64],
    omega: f64,
) -> Result<Vec<(f64, f64, f64)>, BackboneError> {
    sys.elements
        .iter()
        .zip(amp)
        .map(|(e, &a)| match e.law {
            Law::Cubic(k3) => Ok((capi::linearize_cubic(0.0, k3, a)?, 0.0, 0.0)),
            Law::Point(t) => {
                let l = capi::linearize(&t, a, omega)?;
                Ok((l.k_star, l.d_star, l.energy_per_cycle))
            }
        })
        .collect()
}

/// Adds z·PᵀP of every element to `mat` (z per element).
fn add_elements(sys: &System, mat: &mut DMatrix<f64>, z: impl Fn(usize) -> f64) {
    for (idx, e) in sys.elements.iter().enumerate() {
        let v = z(idx);
        mat[(e.i, e.i)] += v;
        if let Some(j) = e.j {
            mat[(j, j)] += v;
            mat[(e.i, j)] -= v;
            mat[(j, e.i)] -= v;
        }
    }
}

/// The modes of the system linearized at amplitudes `amp` and frequency ω.
pub fn linearized_modes(sys: &System, amp: &[f64], omega: f64) -> Result<Vec<Mode>, BackboneError> {
    let lin = linearized(sys, amp, omega)?;
    let mut k = sys.k.clone();
    let mut d = sys.d.clone();
    add_elements(sys, &mut k, |i| lin[i].0);
    add_elements(sys, &mut d, |i| lin[i].1);
    Ok(complex_modes(&sys.m, &d, &k)?)
}

/// The mode of the system linearized at `amp` and ω that continues `reference`: every
/// mode and the pick by MAC up to [`ALL_MODES_MAX`] DOFs, else [`track`] from it.
fn traced_mode(
    sys: &System,
    amp: &[f64],
    omega: f64,
    reference: &Mode,
    modal_amplitude: f64,
) -> Result<Mode, BackboneError> {
    let overdamped = BackboneError::Overdamped { modal_amplitude };
    if sys.n() > ALL_MODES_MAX {
        let lin = linearized(sys, amp, omega)?;
        let mut k = sys.k.clone();
        let mut d = sys.d.clone();
        add_elements(sys, &mut k, |i| lin[i].0);
        add_elements(sys, &mut d, |i| lin[i].1);
        if let Some(md) = track(&sys.m, &d, &k, reference.lambda, &reference.shape) {
            if mac(&sys.m, &reference.shape, &md.shape) >= MAC_MIN {
                return Ok(md);
            }
        }
    }
    let modes = linearized_modes(sys, amp, omega)?;
    let i = pick(&sys.m, &modes, &reference.shape, omega).ok_or(overdamped)?;
    Ok(modes[i].clone())
}

/// Relative amplitudes |P_e φ| of the elements for a shape φ.
pub fn relative(sys: &System, phi: &[C64]) -> Vec<f64> {
    sys.elements
        .iter()
        .map(|e| (phi[e.i] - e.j.map_or(C64::new(0.0, 0.0), |j| phi[j])).norm())
        .collect()
}

/// The stuck linear mode `mode` (1-based, by frequency): every contact at zero
/// amplitude (k* = k_T0, d* = 0).
pub fn stuck_mode(sys: &System, mode: usize) -> Result<Mode, BackboneError> {
    let modes = stuck_modes(sys, mode.max(1))?;
    let count = modes.len();
    match modes.into_iter().nth(mode.wrapping_sub(1)) {
        Some(Some(m)) => Ok(m),
        Some(None) => Err(BackboneError::Overdamped {
            modal_amplitude: 0.0,
        }),
        None => Err(BackboneError::NoMode { mode, count }),
    }
}

/// The stuck linear modes 1…`count` (fewer if the system has fewer) by one eigen solve;
/// None for a mode of a large system that does not continue to the damped system
/// ([`track`]).
pub fn stuck_modes(sys: &System, count: usize) -> Result<Vec<Option<Mode>>, BackboneError> {
    let zeros = vec![0.0; sys.elements.len()];
    if sys.n() > ALL_MODES_MAX {
        return stuck_modes_refined(sys, count, &zeros);
    }
    // ω only scales d*, which is 0 at zero amplitude.
    let modes = linearized_modes(sys, &zeros, 1.0)?;
    Ok(modes.into_iter().take(count).map(Some).collect())
}

/// [`stuck_modes`] of a large system: the undamped modes of (K_s, M) (symmetric,
/// K_s φ = ω² M φ as (L⁻¹K_sL⁻ᵀ) y = ω² y with M = LLᵀ), each continued to D ([`track`]).
fn stuck_modes_refined(
    sys: &System,
    count: usize,
    zeros: &[f64],
) -> Result<Vec<Option<Mode>>, BackboneError> {
    let lin = linearized(sys, zeros, 1.0)?;
    let mut k = sys.k.clone();
    add_elements(sys, &mut k, |i| lin[i].0);
    let l = sys
        .m
        .clone()
        .cholesky()
        .ok_or(super::modes::ModeError::SingularMass)?
        .l();
    let li = l
        .try_inverse()
        .ok_or(super::modes::ModeError::SingularMass)?;
    let a = &li * &k * li.transpose();
    let eig = ((&a + a.transpose()) * 0.5).symmetric_eigen();
    let mut order: Vec<usize> = (0..sys.n()).filter(|&i| eig.eigenvalues[i] > 0.0).collect();
    order.sort_by(|&x, &y| eig.eigenvalues[x].total_cmp(&eig.eigenvalues[y]));
    let tracked = |o: usize| {
        let y = eig.eigenvectors.column(o);
        let phi: Vec<C64> = (li.transpose() * y)
            .iter()
            .map(|&v| C64::new(v, 0.0))
            .collect();
        let w = eig.eigenvalues[o].sqrt();
        track(&sys.m, &sys.d, &k, C64::new(0.0, w), &phi)
    };
    Ok(order.into_iter().take(count).map(tracked).collect())
}

/// The amplitudes a = g(a) of many elements (and ω, the last entry) by Anderson
/// acceleration in ln a from `z0`, to the relative mismatch `tol` over the entries above
/// [`ZERO_AMP_REL`] of the largest amplitude, or to the round-off floor
/// ([`ROUNDOFF_MISMATCH`]).
fn anderson_consistency(
    z0: &[f64],
    mut g: impl FnMut(&[f64]) -> Result<Vec<f64>, BackboneError>,
    tol: f64,
) -> Result<Result<consistency::Converged, consistency::Stalled>, BackboneError> {
    let ne = z0.len() - 1;
    let mut acc = Anderson::new(ANDERSON_DEPTH);
    let mut x = z0.to_vec();
    let mut mismatch = f64::INFINITY;
    // The best g(x) so far, its mismatch and step.
    let (mut best, mut best_mismatch, mut best_it) = (Vec::new(), f64::INFINITY, 0);
    for it in 0..ANDERSON_MAX_ITER {
        let gx = g(&x)?;
        let big = gx[..ne]
            .iter()
            .chain(&x[..ne])
            .fold(0.0f64, |m, v| m.max(*v));
        let floor = (ZERO_AMP_REL * big).max(f64::MIN_POSITIVE);
        mismatch = x
            .iter()
            .zip(&gx)
            .enumerate()
            // Entries floored in an earlier step sit at about `floor`: noise, not mismatch.
            .filter(|(i, (a, b))| *i == ne || a.max(**b) > 10.0 * floor)
            .map(|(_, (a, b))| (a - b).abs() / a.max(*b))
            .fold(0.0, f64::max);
        if mismatch <= tol {
            return Ok(Ok(consistency::Converged {
                x: gx,
                iterations: it + 1,
            }));
        }
        if mismatch < best_mismatch {
            (best, best_mismatch, best_it) = (gx.clone(), mismatch, it);
        } else if it - best_it >= ANDERSON_STALL && best_mismatch <= ROUNDOFF_MISMATCH {
            return Ok(Ok(consistency::Converged {
                x: best,
                iterations: it + 1,
            }));
        }
        let lx: Vec<f64> = x.iter().map(|v| v.max(floor).ln()).collect();
        let lg: Vec<f64> = gx.iter().map(|v| v.max(floor).ln()).collect();
        let next = acc.next(&lx, &lg);
        // At most a decade beyond the bracket of x and g(x) per step.
        x = next
            .iter()
            .zip(lx.iter().zip(&lg))
            .map(|(v, (a, b))| {
                v.clamp(
                    a.min(*b) - std::f64::consts::LN_10,
                    a.max(*b) + std::f64::consts::LN_10,
                )
                .exp()
            })
            .collect();
    }
    if best_mismatch <= ROUNDOFF_MISMATCH {
        return Ok(Ok(consistency::Converged {
            x: best,
            iterations: ANDERSON_MAX_ITER,
        }));
    }
    Ok(Err(consistency::Stalled {
        mismatch,
        iterations: ANDERSON_MAX_ITER,
    }))
}

/// The modal amplitude at which the first contact of the stuck mode reaches its slip
/// limit δ* (2.46) (∞ without contacts).
pub fn stick_limit(sys: &System, shape: &[C64]) -> Result<f64, BackboneError> {
    let rel = relative(sys, shape);
    let mut q = f64::INFINITY;
    for (e, r) in sys.elements.iter().zip(rel) {
        if let Law::Point(t) = e.law {
            let dstar = capi::linearize(&t, 0.0, 1.0)?.slip_limit;
            if r > 0.0 && dstar > 0.0 {
                q = q.min(dstar / r);
            }
        }
    }
    Ok(q)
}

/// ω (rad/time) and the damping ξ = φᴴ D* φ/φᴴMφ (1/time) of the Rayleigh quotients of
/// the system linearized at the motion q·φ: each contact's k*, d* (`jointlin_linearize`)
/// at its amplitude q|P_e φ|, D* = D + Σ d* PᵀP, ω² = φᴴ(K + Σ k* PᵀP)φ/φᴴMφ (d*
/// depends on ω, so ω is iterated from `omega` three times). The first-order estimate of
/// the mode at modal amplitude q with shape φ: the EPMC's start.
pub fn rayleigh(
    sys: &System,
    shape: &[C64],
    q: f64,
    omega: f64,
) -> Result<(f64, f64), BackboneError> {
    let amp: Vec<f64> = relative(sys, shape).iter().map(|r| q * r).collect();
    let quadratic = |a: &DMatrix<f64>| {
        let mut v = C64::new(0.0, 0.0);
        for (i, x) in shape.iter().enumerate() {
            for (j, y) in shape.iter().enumerate() {
                v += x.conj() * y * a[(i, j)];
            }
        }
        v.re
    };
    let mass = quadratic(&sys.m);
    let (mut w, mut xi) = (omega, 0.0);
    for _ in 0..3 {
        let lin = linearized(sys, &amp, w)?;
        let mut k = sys.k.clone();
        add_elements(sys, &mut k, |i| lin[i].0);
        let mut d = sys.d.clone();
        add_elements(sys, &mut d, |i| lin[i].1);
        let w2 = quadratic(&k) / mass;
        if !(w2 > 0.0 && w2.is_finite()) {
            break;
        }
        w = w2.sqrt();
        xi = quadratic(&d) / mass;
    }
    Ok((w, xi))
}

/// Contacts that move less than this fraction of the one moving most are left out of
/// [`slip_range`]: a reduced FE model's lateral directions of a bending mode move at
/// round-off level, and their "onsets" would stretch the range by ten decades.
const MOVES: f64 = 1e-3;

/// The default modal amplitudes of a backbone of mode `mode`, stuck … fully sliding: a
/// tenth of the first contact's slip onset δ*/|P_e φ| to 30 times the last one's, over
/// the contacts the stuck mode moves ([`MOVES`]). `NoContact` if none moves.
pub fn slip_range(sys: &System, mode: usize) -> Result<(f64, f64), BackboneError> {
    let st = stuck_mode(sys, mode)?;
    let rel = relative(sys, &st.shape);
    let big = rel.iter().copied().fold(0.0, f64::max);
    let mut onsets = Vec::new();
    for (e, r) in sys.elements.iter().zip(rel) {
        if let Law::Point(t) = e.law {
            let ds = capi::linearize(&t, 0.0, 1.0)?.slip_limit;
            if r > MOVES * big {
                onsets.push(ds / r);
            }
        }
    }
    let lo = onsets.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = onsets.iter().copied().fold(0.0, f64::max);
    if !lo.is_finite() {
        return Err(BackboneError::NoContact);
    }
    Ok((0.1 * lo, 30.0 * hi))
}

/// The first-order backbone of mode `mode` (1-based) at the modal amplitudes `q`
/// (ascending or not; each starts from its predecessor); an amplitude that fails fails
/// the whole backbone ([`trace`] keeps the points before it).
pub fn backbone(sys: &System, mode: usize, q: &[f64]) -> Result<Vec<BackbonePoint>, BackboneError> {
    let traced = trace(sys, mode, q)?;
    match traced.stopped {
        Some(e) => Err(e),
        None => Ok(traced.points),
    }
}

/// A backbone traced up to the first amplitude that failed.
pub struct Traced {
    /// The points of the amplitudes before the failure, in the order given.
    pub points: Vec<BackbonePoint>,
    /// Why the trace stopped early (None: every amplitude was solved).
    pub stopped: Option<BackboneError>,
}

/// [`backbone`], keeping the points solved before an amplitude that fails (as the EPMC
/// trace keeps its converged points): the stuck mode not found is an error, a later
/// failure stops the trace.
pub fn trace(sys: &System, mode: usize, q: &[f64]) -> Result<Traced, BackboneError> {
    trace_with(sys, mode, q, &|_| {})
}

/// [`trace`], calling `on_amplitude(i)` before amplitude `i` (0-based) is solved.
pub fn trace_with(
    sys: &System,
    mode: usize,
    q: &[f64],
    on_amplitude: &dyn Fn(usize),
) -> Result<Traced, BackboneError> {
    let mut current = stuck_mode(sys, mode)?;
    let mut points = Vec::with_capacity(q.len());
    for (i, &qa) in q.iter().enumerate() {
        on_amplitude(i);
        match point_at(sys, &current, qa) {
            Ok((point, mode)) => {
                points.push(point);
                current = mode;
            }
            Err(e) => {
                let stopped = Some(near_critical(&points, e));
                return Ok(Traced { points, stopped });
            }
        }
    }
    Ok(Traced {
        points,
        stopped: None,
    })
}

/// Damping ratio from which a trace that fails next is said to end at critical damping.
const NEAR_CRITICAL: f64 = 0.9;

/// The failure `e` after `points`, named as the mode's end when the last point's damping
/// ratio is at least [`NEAR_CRITICAL`] and rose over the last three points (a block
/// sliding on a plane as a whole: the mode's stiffness goes with its joints).
fn near_critical(points: &[BackbonePoint], e: BackboneError) -> BackboneError {
    let z: Vec<f64> = points
        .iter()
        .rev()
        .take(3)
        .map(|p| p.damping_ratio)
        .collect();
    let rising = z.len() == 3 && z.windows(2).all(|w| w[0] > w[1]);
    match points.last() {
        Some(p) if rising && p.damping_ratio >= NEAR_CRITICAL => BackboneError::CriticalDamping {
            last: p.modal_amplitude,
            damping_ratio: p.damping_ratio,
            cause: Box::new(e),
        },
        _ => e,
    }
}

/// The consistent point at modal amplitude `qa`, started from the mode `current` of
/// the previous amplitude; with its mass-normalized mode, the start of the next one.
fn point_at(sys: &System, current: &Mode, qa: f64) -> Result<(BackbonePoint, Mode), BackboneError> {
    let ne = sys.elements.len();
    if !(qa.is_finite() && qa > 0.0) {
        return Err(BackboneError::Amplitude(qa));
    }
    // Unknowns (A_1 … A_ne, ω); g gives them back from the traced mode, which each
    // evaluation refines from the last one.
    let mut last = current.clone();
    let g = |z: &[f64]| -> Result<Vec<f64>, BackboneError> {
        let w = z[ne].max(f64::MIN_POSITIVE);
        let md = traced_mode(sys, &z[..ne], w, &last, qa)?;
        let mut next: Vec<f64> = relative(sys, &md.shape).iter().map(|r| qa * r).collect();
        next.push(md.omega());
        if sys.n() > ALL_MODES_MAX {
            last = md;
        }
        Ok(next)
    };
    let mut z0: Vec<f64> = relative(sys, &current.shape)
        .iter()
        .map(|r| qa * r)
        .collect();
    z0.push(current.omega());
    let solved = if ne > NEWTON_MAX {
        anderson_consistency(&z0, g, TOL)?
    } else {
        // The amplitudes are one group of the mismatch's scale, ω another.
        let groups: Vec<usize> = (0..=ne).map(|i| usize::from(i == ne)).collect();
        consistency::solve_with(&z0, g, None, &groups, TOL, MAX_ITER)?
    };
    let z = match solved {
        Ok(c) => c.x,
        Err(st) => {
            return Err(BackboneError::NotConsistent {
                modal_amplitude: qa,
                mismatch: st.mismatch,
                iterations: st.iterations,
                method: if ne > NEWTON_MAX {
                    ANDERSON_METHOD
                } else {
                    consistency::METHOD
                },
            })
        }
    };
    let w = z[ne];
    let md = traced_mode(sys, &z[..ne], w, current, qa)?;
    let lin = linearized(sys, &z[..ne], md.omega())?;
    let shape = normalize(&sys.m, &md.shape);
    let next = Mode {
        lambda: md.lambda,
        shape: shape.clone(),
    };
    let point = BackbonePoint {
        modal_amplitude: qa,
        omega: md.omega(),
        damping_ratio: md.damping_ratio(),
        shape: shape.iter().map(|v| v * qa).collect(),
        element_amplitudes: relative(sys, &shape).iter().map(|r| qa * r).collect(),
        energy_per_cycle: lin.iter().map(|l| l.2).collect(),
        normal_range: Vec::new(),
    };
    Ok((point, next))
}
