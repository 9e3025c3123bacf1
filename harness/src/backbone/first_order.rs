//! First-order backbone: at modal amplitude q, the complex mode of
//! λ²M + λ(D + Σ Pᵀd*P) + (K + Σ Pᵀk*P) whose contact amplitudes A_e = q·|P_e φ|
//! (φᴴMφ = 1) are those k*, d* were taken at (docs/model.md §3; k* (3.8), d* (3.14) of
//! the thesis through `jointlin_linearize`; cubic springs k* = ¾k₃A², d* = 0), and whose
//! |λ| is the ω d* was taken at. The fixed point (A_e, ω) is found by
//! [`crate::mhb::consistency`]; each amplitude starts from the previous one and follows
//! the mode by MAC. Frequency |λ|, damping ratio −Re λ/|λ|.

use nalgebra::DMatrix;

use super::modes::{complex_modes, normalize, pick, Mode, C64};
use super::{BackboneError, BackbonePoint};
use crate::capi;
use crate::mhb::{consistency, Law, System};

/// Relative tolerance of the consistency (amplitudes and ω).
const TOL: f64 = 1e-10;
const MAX_ITER: usize = 60;

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
    let zeros = vec![0.0; sys.elements.len()];
    // ω only scales d*, which is 0 at zero amplitude.
    let modes = linearized_modes(sys, &zeros, 1.0)?;
    modes
        .get(mode.wrapping_sub(1))
        .cloned()
        .ok_or(BackboneError::NoMode {
            mode,
            count: modes.len(),
        })
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

/// The first-order backbone of mode `mode` (1-based) at the modal amplitudes `q`
/// (ascending or not; each starts from its predecessor).
pub fn backbone(sys: &System, mode: usize, q: &[f64]) -> Result<Vec<BackbonePoint>, BackboneError> {
    let start = stuck_mode(sys, mode)?;
    let mut shape = start.shape.clone();
    let mut omega = start.omega();
    let ne = sys.elements.len();
    let mut out = Vec::with_capacity(q.len());
    for &qa in q {
        if !(qa.is_finite() && qa > 0.0) {
            return Err(BackboneError::Amplitude(qa));
        }
        // Unknowns (A_1 … A_ne, ω); g gives them back from the picked mode.
        let reference = shape.clone();
        let g = |z: &[f64]| -> Result<Vec<f64>, BackboneError> {
            let w = z[ne].max(f64::MIN_POSITIVE);
            let modes = linearized_modes(sys, &z[..ne], w)?;
            let i = pick(&sys.m, &modes, &reference, w).ok_or(BackboneError::Overdamped {
                modal_amplitude: qa,
            })?;
            let mut next: Vec<f64> = relative(sys, &modes[i].shape)
                .iter()
                .map(|r| qa * r)
                .collect();
            next.push(modes[i].omega());
            Ok(next)
        };
        let mut z0: Vec<f64> = relative(sys, &shape).iter().map(|r| qa * r).collect();
        z0.push(omega);
        let z = match consistency::solve(&z0, g, TOL, MAX_ITER)? {
            Ok(c) => c.x,
            Err(st) => {
                return Err(BackboneError::NotConsistent {
                    modal_amplitude: qa,
                    mismatch: st.mismatch,
                    iterations: st.iterations,
                })
            }
        };
        let w = z[ne];
        let modes = linearized_modes(sys, &z[..ne], w)?;
        let i = pick(&sys.m, &modes, &shape, w).ok_or(BackboneError::Overdamped {
            modal_amplitude: qa,
        })?;
        let md = &modes[i];
        let lin = linearized(sys, &z[..ne], md.omega())?;
        shape = normalize(&sys.m, &md.shape);
        omega = md.omega();
        out.push(BackbonePoint {
            modal_amplitude: qa,
            omega,
            damping_ratio: md.damping_ratio(),
            shape: shape.iter().map(|v| v * qa).collect(),
            element_amplitudes: relative(sys, &shape).iter().map(|r| qa * r).collect(),
            energy_per_cycle: lin.iter().map(|l| l.2).collect(),
        });
    }
    Ok(out)
}
