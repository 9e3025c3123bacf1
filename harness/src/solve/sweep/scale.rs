//! The problem's own amplitude scale, for tolerances that do not depend on the user's
//! start estimate (`initial_amplitude`), and the zero-load sweep.
//!
//! The scale at a frequency is the largest contact amplitude of the linear response with
//! every joint stuck: κ = k_T0 (the A → 0 limit of k*, d* = 0; docs/model.md §4) in every
//! closed tangential direction and the cubic springs at their linear stiffness. The
//! absolute tolerance of the amplitude test is [`super::ATOL_REL`] times it: amplitudes
//! a million times smaller than the stuck response are round-off of the contact
//! iteration. A zero load has the exactly zero response (k* = k_T0, d* = 0, regime stick
//! at every closed point, no dissipation).

use std::time::Instant;

use super::{Options, PassRecord, PointFreq, Setup, SweepError, SweepResult, C64};
use crate::capi::{self, Linearized};
use crate::settings::Mode;
use crate::solve::contact::tangential;

/// A → 0 linearization of every active point (k* = k_T0, d* = 0, regime stick), at ω.
fn stuck_points(setup: &Setup, omega: f64) -> Result<Vec<Linearized>, SweepError> {
    let p = setup.problem;
    setup
        .active
        .iter()
        .map(|&i| {
            let c = &p.contacts[i];
            let t = tangential(&p.interfaces[c.interface], setup.pressure[i]);
            Ok(capi::linearize(&t, 0.0, omega)?)
        })
        .collect()
}

/// κ of every active point with the joint stuck: k_T0 per area, real (the A → 0 limit of
/// k*, without a library call, so thesis mode stays UINTER-only).
fn stuck_kappa(setup: &Setup) -> Vec<[C64; 2]> {
    let p = setup.problem;
    setup
        .active
        .iter()
        .map(|&i| {
            [C64::new(
                p.interfaces[p.contacts[i].interface].contact.k_t0_per_area,
                0.0,
            ); 2]
        })
        .collect()
}

/// Largest contact amplitude (length) of the stuck linear response at `f`, or `None`
/// when the stuck dynamic stiffness is singular there.
fn stuck_amplitude(
    setup: &mut Setup,
    kappa: &[[C64; 2]],
    f: f64,
) -> Result<Option<f64>, SweepError> {
    let p = setup.problem;
    let linear: Vec<f64> = p.cubic_springs.iter().map(|sp| sp.stiffness).collect();
    setup.fill(2.0 * std::f64::consts::PI * f, kappa, &linear);
    let Some(num) = setup.factor(f)? else {
        return Ok(None);
    };
    let mut x = vec![C64::new(0.0, 0.0); p.sys.dofs.n_free()];
    num.solve_into(&p.excitation, &mut x)
        .map_err(|source| SweepError::Umfpack { freq: f, source })?;
    let mut a = 0.0f64;
    for j in 0..setup.active.len() {
        for d in setup.tangential(j, &x) {
            a = a.max(d.norm());
        }
    }
    for sp in &p.cubic_springs {
        a = a.max(sp.row.iter().map(|&(i, w)| x[i] * w).sum::<C64>().norm());
    }
    Ok(Some(a))
}

/// The smallest over `freqs` of the stuck response's largest contact amplitude (length;
/// frequencies where the stuck stiffness is singular left out; 0 when none is left or
/// nothing moves). One factorization per frequency.
pub fn stuck_scale(setup: &mut Setup, freqs: &[f64]) -> Result<f64, SweepError> {
    let kappa = stuck_kappa(setup);
    let mut scale = f64::INFINITY;
    for &f in freqs {
        if let Some(a) = stuck_amplitude(setup, &kappa, f)? {
            if a > 0.0 && a.is_finite() {
                scale = scale.min(a);
            }
        }
    }
    Ok(if scale.is_finite() { scale } else { 0.0 })
}

/// Whether the load is identically zero.
pub fn is_zero_load(setup: &Setup) -> bool {
    setup.problem.excitation.iter().all(|v| v.norm() == 0.0)
}

/// The sweep of a zero load: zero response and power, the closed points stuck
/// (k* = k_T0, d* = 0, energy 0, A/δ* = 0), converged; a frequency where the stuck
/// dynamic stiffness is singular is reported singular (its free vibration is undetermined).
/// In harmonic-balance mode every harmonic 0..H of every output is zero too.
pub fn zero_load(
    setup: &mut Setup,
    freqs: &[f64],
    opts: &Options,
) -> Result<SweepResult, SweepError> {
    let p = setup.problem;
    let kappa = stuck_kappa(setup);
    let linear: Vec<f64> = p.cubic_springs.iter().map(|sp| sp.stiffness).collect();
    let nf = freqs.len();
    let harmonics = match opts.iteration.mode {
        Mode::HarmonicBalance => {
            let h = opts.iteration.harmonics.unwrap_or(1).max(1);
            vec![vec![vec![C64::new(0.0, 0.0); h + 1]; p.outputs.len()]; nf]
        }
        _ => Vec::new(),
    };
    let mut res = SweepResult {
        freqs: freqs.to_vec(),
        harmonics,
        outputs: vec![vec![C64::new(0.0, 0.0); p.outputs.len()]; nf],
        power: vec![0.0; nf],
        iterations: vec![0; nf],
        ..Default::default()
    };
    for &f in freqs {
        let omega = 2.0 * std::f64::consts::PI * f;
        let t = Instant::now();
        setup.fill(omega, &kappa, &linear);
        let singular = setup.factor(f)?.is_none();
        res.factorizations += 1;
        res.time("factorization", t);
        res.singular.push(singular);
        res.converged.push(!singular);
        if opts.point_results {
            let mut pts = vec![PointFreq::default(); p.contacts.len()];
            if !singular {
                for (l, &i) in stuck_points(setup, omega)?.iter().zip(&setup.active) {
                    pts[i] = PointFreq {
                        amplitude: [0.0; 2],
                        k_star: [l.k_star; 2],
                        d_star: [0.0; 2],
                        energy: 0.0,
                        ratio: [0.0; 2],
                        regime: [l.regime; 2],
                    };
                }
            }
            res.points.push(pts);
        }
    }
    res.passes.push(PassRecord {
        pass: 1,
        kind: "zero load".into(),
        frequencies: freqs.to_vec(),
        converged: res.converged.iter().filter(|&&c| c).count(),
    });
    Ok(res)
}
