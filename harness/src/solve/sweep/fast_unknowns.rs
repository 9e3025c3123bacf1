//! The contact unknowns of the fast sweep, fixed for the sweep: 2 per active contact
//! point (tangential directions, j < mc), then 1 per cubic spring; their sparse rows of
//! the contact map B, their weights (area, or 1 for a spring) and their linearization
//! through the C API at amplitudes a (thesis (3.8), (3.14)).

use super::fast_coupled::{CoupledPoints, Lin2};
use super::{Setup, C64};
use crate::capi::{self, CapiError, Linearized, Tangential};
use crate::model::Problem;
use crate::settings::Effects;
use crate::solve::contact::{area_average, tangential};

/// Amplitudes below this fraction of the largest one are round-off: handed to the
/// linearization as exactly 0 (k* = k_T0, d* = 0: the A → 0 limit; k* differs from it by
/// O(A/δ*)), floored there before taking logs, and equal to each other in the
/// convergence test. Without it a direction that is never excited (amplitude 0) would
/// drive ln a to −∞. Such directions come out of a solve as noise: up to 2.4e-11 of the
/// largest amplitude on three-beams-coarse (lateral directions of the bending modes),
/// with LU or FGMRES alike. A floor below the noise (1e-15 was) let FGMRES's noise,
/// different at each solve because each starts from the previous û, reach the Anderson
/// step as O(1) changes of ln a: 2–3× the condensed path's contact iterations, and two
/// frequencies near the second resonance that never converged at rtol ≤ 1e-6.
pub const ZERO_AMP_REL: f64 = 1e-9;

/// Timing key of the cubic springs' linearization calls.
pub const CUBIC_TIMING: &str = "cubic springs (C API)";

/// The sweep's contact unknowns and their laws.
pub struct Unknowns<'a> {
    pub p: &'a Problem,
    pub eff: Effects,
    /// Contact indices of the active points.
    pub active: Vec<usize>,
    /// Per active point: its tangential data at the base pressure, and its area.
    pub tang: Vec<Tangential>,
    pub area: Vec<f64>,
    /// Area samples of sampled points: (tangential data at the sample's pressure, area
    /// fraction), zero-pressure samples left out (they carry no friction).
    samples: Vec<Vec<(Tangential, f64)>>,
    /// With coupled slip: the points' 2 × 2 describing functions (fast_coupled.rs).
    pub coupled: Option<CoupledPoints>,
    /// δ* per active point, only when macroslip is off or coupled slip reports A/δ*.
    slip_limit: Vec<f64>,
    /// ‖Bⱼ‖₂² per unknown: ‖Bⱼᵀ Δⱼ Bⱼ‖₂ = |Δⱼ|‖Bⱼ‖₂² bounds the update's norm.
    pub row_norm2: Vec<f64>,
    /// Tangential unknowns (2 per active point).
    pub mc: usize,
    /// All unknowns.
    pub m: usize,
}

impl<'a> Unknowns<'a> {
    /// The unknowns of `setup` (δ* by the library where needed: A = 0 gives δ* and k_T0).
    pub fn new(setup: &Setup<'a>, eff: Effects) -> Result<Self, CapiError> {
        let p = setup.problem;
        let active = setup.active.clone();
        let tang: Vec<Tangential> = active
            .iter()
            .map(|&i| tangential(&p.interfaces[p.contacts[i].interface], setup.pressure[i]))
            .collect();
        let area = active.iter().map(|&i| p.contacts[i].area).collect();
        let samples: Vec<Vec<(Tangential, f64)>> = active
            .iter()
            .map(|&i| {
                let itf = &p.interfaces[p.contacts[i].interface];
                setup.friction_samples[i]
                    .iter()
                    .filter(|(_, pr)| *pr > 0.0)
                    .map(|&(f, pr)| (tangential(itf, pr), f))
                    .collect()
            })
            .collect();
        let coupled = eff
            .coupled_slip
            .then(|| CoupledPoints::new(&tang, &samples));
        let slip_limit: Vec<f64> = if eff.macroslip && coupled.is_none() {
            Vec::new()
        } else {
            tang.iter()
                .map(|t| capi::linearize(t, 0.0, 1.0).map(|l| l.slip_limit))
                .collect::<Result<_, _>>()?
        };
        let mc = 2 * active.len();
        let mut u = Unknowns {
            p,
            eff,
            active,
            tang,
            area,
            samples,
            coupled,
            slip_limit,
            row_norm2: Vec::new(),
            mc,
            m: mc + p.cubic_springs.len(),
        };
        u.row_norm2 = (0..u.m)
            .map(|j| u.row(j).iter().map(|&(_, w)| w * w).sum())
            .collect();
        Ok(u)
    }

    /// Active points with coupled slip (0 without it).
    pub fn coupled_points(&self) -> usize {
        if self.coupled.is_some() {
            self.active.len()
        } else {
            0
        }
    }

    /// The sparse row of unknown j in B: (free DOF, weight).
    pub fn row(&self, j: usize) -> &'a [(usize, f64)] {
        if j < self.mc {
            self.p.contacts[self.active[j / 2]].rows[1 + j % 2].as_slice()
        } else {
            self.p.cubic_springs[j - self.mc].row.as_slice()
        }
    }

    /// The weight of unknown j: its point's area, 1 for a spring.
    pub fn weight(&self, j: usize) -> f64 {
        if j < self.mc {
            self.area[j / 2]
        } else {
            1.0
        }
    }

    /// κ = k* + iωd* of a direction (d* only with contact damping).
    pub fn kappa(&self, l: &Linearized, omega: f64) -> C64 {
        let d = if self.eff.contact_damping {
            omega * l.d_star
        } else {
            0.0
        };
        C64::new(l.k_star, d)
    }

    /// κ of entry (i, j) of a coupled point's matrices.
    pub fn kappa2(&self, l: &Lin2, i: usize, j: usize, omega: f64) -> C64 {
        let d = if self.eff.contact_damping {
            omega * l.d[i][j]
        } else {
            0.0
        };
        C64::new(l.k[i][j], d)
    }

    /// Every tangential direction's law at amplitudes `a` (phase cosines `rho` with
    /// coupled slip) into `lin` (and `lin2`); amplitudes capped at δ* without macroslip,
    /// counted in `caps`.
    pub fn linearize(
        &self,
        (a, rho): (&[f64], &[f64]),
        omega: f64,
        (lin, lin2): (&mut [Linearized], &mut [Lin2]),
        caps: &mut usize,
    ) -> Result<(), CapiError> {
        let floor = zero_floor(a);
        if let Some(cp) = &self.coupled {
            for q in 0..self.active.len() {
                let mut amp = [a[2 * q], a[2 * q + 1]].map(|v| if v < floor { 0.0 } else { v });
                let major = amp[0].max(amp[1]);
                let limit = self.slip_limit[q];
                if !self.eff.macroslip && major > limit {
                    amp = amp.map(|v| v * limit / major);
                    *caps += 1;
                }
                let l = cp.linearize(q, amp, rho[q], omega)?;
                lin2[q] = l;
                // The diagonal as the thesis model's per-direction record (outputs, the
                // factorized reference); the energy is the point's, split evenly.
                for d in 0..2 {
                    let (k, dd) = (l.k[d][d], l.d[d][d]);
                    lin[2 * q + d] = Linearized {
                        k_star: k,
                        d_star: dd,
                        eta: if k > 0.0 { omega * dd / k } else { 0.0 },
                        energy_per_cycle: 0.5 * l.energy,
                        slip_limit: limit,
                        amplitude_ratio: if limit > 0.0 { amp[d] / limit } else { 0.0 },
                        regime: l.regime,
                    };
                }
            }
            return Ok(());
        }
        for j in 0..self.mc {
            let mut amp = if a[j] < floor { 0.0 } else { a[j] };
            if !self.eff.macroslip && amp > self.slip_limit[j / 2] {
                amp = self.slip_limit[j / 2];
                *caps += 1;
            }
            lin[j] = capi::linearize(&self.tang[j / 2], amp, omega)?;
            if !self.p.contacts[self.active[j / 2]].samples.is_empty() {
                lin[j] = area_average(&lin[j], &self.samples[j / 2], amp, omega)?;
            }
        }
        Ok(())
    }

    /// k* of every cubic spring (3.8) for its amplitude.
    pub fn linearize_springs(&self, a: &[f64], ks: &mut [f64]) -> Result<(), CapiError> {
        let floor = zero_floor(a);
        for (q, sp) in self.p.cubic_springs.iter().enumerate() {
            let amp = if a[self.mc + q] < floor {
                0.0
            } else {
                a[self.mc + q]
            };
            ks[q] = capi::linearize_cubic(sp.stiffness, sp.cubic, amp)?;
        }
        Ok(())
    }
}

/// The round-off floor of amplitudes `a` ([`ZERO_AMP_REL`] of the largest).
pub fn zero_floor(a: &[f64]) -> f64 {
    ZERO_AMP_REL * a.iter().fold(0.0f64, |x, &y| x.max(y))
}
