//! First-order coupled slip in the fast sweep (`[effects] coupled_slip` with
//! `mode = "fast"`; docs/contact3d.md §4). A point's two tangential directions move with
//! the complex amplitudes (r̂₁, r̂₂): an ellipse, on which its Jenkins cells slip under
//! one circular limit. The library's describing function (`jointlin_linearize3d_phasors`,
//! tabulated unit cell) turns it into two symmetric 2 × 2 matrices per area,
//! t̂ = (K* + iωD*) r̂, at the static step's pressure (constant normal load).
//!
//! The ellipse is fixed by a₁ = |r̂₁|, a₂ = |r̂₂| and ρ = Re(r̂₁ r̄̂₂)/(a₁a₂), the cosine of
//! the phase between the directions (M = Re(r̂ r̂ᴴ) has entries a₁², a₂², ρa₁a₂). The
//! fast sweep iterates a as for the thesis's model and ρ beside it.

use crate::capi::{self, CapiError, Contact3, Tangential};

use super::C64;

/// A point's describing function at one ellipse (per area).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Lin2 {
    /// K* (force/length³), symmetric.
    pub k: [[f64; 2]; 2],
    /// D* (force·time/length³), symmetric.
    pub d: [[f64; 2]; 2],
    /// Energy per cycle per area (force/length).
    pub energy: f64,
    pub regime: i32,
}

/// The active points' coupled elements: per point the contact (per area) and its
/// (pressure, area fraction) samples (one sample at the point's pressure when node-based).
pub struct CoupledPoints {
    points: Vec<(Contact3, Vec<(f64, f64)>)>,
}

impl CoupledPoints {
    /// From the points' tangential data and their area samples (tangential data at the
    /// sample's pressure, area fraction; empty: node-based).
    pub fn new(tang: &[Tangential], samples: &[Vec<(Tangential, f64)>]) -> Self {
        let points = tang
            .iter()
            .zip(samples)
            .map(|(t, s)| {
                // k_N is not used at constant normal load; any valid stiffness. The
                // cells as in the harmonic balance: both modes describe the same element.
                let contact = Contact3::new(t.law, t.mu, t.k_t0, 1.0);
                let pressures = if s.is_empty() {
                    vec![(t.normal, 1.0)]
                } else {
                    s.iter().map(|(ts, f)| (ts.normal, *f)).collect()
                };
                (contact, pressures)
            })
            .collect();
        CoupledPoints { points }
    }

    /// Point q on the ellipse of amplitudes `a` (length) and phase cosine `rho` at ω: the
    /// area average of its samples' describing functions.
    pub fn linearize(
        &self,
        q: usize,
        a: [f64; 2],
        rho: f64,
        omega: f64,
    ) -> Result<Lin2, CapiError> {
        let (contact, samples) = &self.points[q];
        let u = phasors(a, rho);
        let mut out = Lin2::default();
        for &(pressure, fraction) in samples {
            let l = capi::linearize3d_phasors(contact, pressure, u, omega, true)?;
            for i in 0..2 {
                for j in 0..2 {
                    out.k[i][j] += fraction * l.k_star[2 * i + j];
                    out.d[i][j] += fraction * l.d_star[2 * i + j];
                }
            }
            out.energy += fraction * l.energy_per_cycle;
            out.regime = out.regime.max(l.regime);
        }
        Ok(out)
    }
}

/// Phasors of the ellipse (a₁, a₂, ρ): r̂₁ = a₁, r̂₂ = a₂(ρ − i√(1 − ρ²)) (the sense of
/// rotation does not change the describing function).
pub fn phasors(a: [f64; 2], rho: f64) -> [C64; 2] {
    let rho = rho.clamp(-1.0, 1.0);
    let sin = ((1.0 - rho) * (1.0 + rho)).sqrt();
    [C64::new(a[0], 0.0), C64::new(a[1] * rho, -a[1] * sin)]
}

/// ρ = Re(r̂₁ r̄̂₂)/(|r̂₁||r̂₂|), 0 when either is 0.
pub fn correlation(r1: C64, r2: C64) -> f64 {
    let den = r1.norm() * r2.norm();
    if den > 0.0 {
        ((r1 * r2.conj()).re / den).clamp(-1.0, 1.0)
    } else {
        0.0
    }
}

/// Whether the estimated and computed ρ agree: the cross term ρa₁a₂ of M within rtol of
/// the larger amplitude squared, |ρ − ρ*| min(a)/max(a) ≤ rtol (ρ barely shapes a thin
/// ellipse), per point; `a` holds two amplitudes per point.
pub fn rho_consistent(a: &[f64], rho: &[f64], rho_star: &[f64], rtol: f64) -> bool {
    rho.iter().zip(rho_star).enumerate().all(|(q, (r, s))| {
        let (lo, hi) = (a[2 * q].min(a[2 * q + 1]), a[2 * q].max(a[2 * q + 1]));
        hi == 0.0 || (r - s).abs() * lo <= rtol * hi
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_phase_cosine_round_trips_through_the_phasors() {
        for (a, rho) in [([1.0, 0.5], 0.3), ([2.0, 2.0], -1.0), ([1e-3, 4e-3], 0.999)] {
            let u = phasors(a, rho);
            assert!((u[0].norm() - a[0]).abs() < 1e-15 * a[0]);
            assert!((u[1].norm() - a[1]).abs() < 1e-15 * a[1]);
            assert!((correlation(u[0], u[1]) - rho).abs() < 1e-15);
        }
        assert_eq!(correlation(C64::new(0.0, 0.0), C64::new(1.0, 0.0)), 0.0);
        // A thin ellipse tolerates a large ρ change, a round one does not.
        assert!(rho_consistent(&[1.0, 1e-4], &[0.0], &[0.5], 1e-3));
        assert!(!rho_consistent(&[1.0, 1.0], &[0.0], &[0.01], 1e-3));
    }
}
