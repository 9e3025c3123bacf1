//! The modal route of the first-order steady state (docs/model.md §10, "modal route"):
//! the linear part is the structure with every active joint stuck (κ₀ = k_T0 per area,
//! the springs' linear k), S_s(ω) = K_s − ω²M + iωD + iH, represented by its p lowest
//! modes (K_s φ_r = λ_r M φ_r, φᵀMφ = 1) and, optionally, the omitted ones' residual
//! flexibility with its first inertia term ([`super::modal_residual`]):
//!
//!   S_s(ω)⁻¹ ≈ Φ Z(ω)⁻¹ Φᵀ + R + ω²RMR,   Z = Λ − ω²I + iωΦᵀDΦ + iΦᵀHΦ.
//!
//! The contact nonlinearity is then condensed exactly as in the direct route
//! ([`super::fast`]): G = B S_s⁻¹ Bᵀ, r₀ = B S_s⁻¹ f̂, O = C S_s⁻¹ Bᵀ, y₀ = C S_s⁻¹ f̂ with
//! B the contact rows, C the outputs. The modes and the residual's images come once per
//! basis (one Lanczos run, 2m solves with one Cholesky factor of K_s; a basis serves
//! later sweeps of the same problem with another load); each frequency then costs a
//! dense p × p factorization and products of sizes m × p × m, independent of the mesh.
//! Modal damping (`Problem::modal_damping`) adds iω·2ζ_rω_r to Z's diagonal.

use nalgebra::{DMatrix, Dyn, LU};

use super::modal_residual::{Kept, Residual, RowFn};
use super::{Setup, C64};
use crate::fe::csc::Csc;
use crate::model::Output;
use crate::solve::cholmod::CholmodError;
use crate::solve::modal::{lowest_modes, ModalError, ModalOptions};
use crate::solve::modal_band::modes_below;

/// Which modes the modal route keeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ModeChoice {
    /// Exactly this many (fewer if the model has fewer DOFs).
    Count(usize),
    /// Every mode below this frequency (1/time), at least [`MIN_MODES`], at most
    /// [`MAX_MODES`].
    Below(f64),
}

/// How the linear part of each frequency is solved.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum LinearRoute {
    /// One sparse factorization of the dynamic stiffness per frequency.
    #[default]
    Direct,
    /// The stuck structure's modes ([`ModalRoute`]), with or without the static
    /// residual flexibility of the omitted modes.
    Modal { modes: ModeChoice, residual: bool },
}

/// A frequency with |λ_r − ω² + i(damping)| ≤ this × λ_r for a kept mode r is singular
/// (no response: an undamped eigenfrequency). The modal eigenvalues are known to about
/// 1e-11 relative on the stiff-joint model of scenes/hard/open-resonance.toml (the
/// direct route's factorization calls a band of ~1e-10 around them singular there);
/// 1e-9 keeps a margin, and 1e-6 away the response is regular and one mode dominates.
pub const SINGULAR_MODAL_REL: f64 = 1e-9;

/// Default band of the modal route: modes below this multiple of the sweep's highest
/// frequency. The omitted modes' error is O((f/f_{p+1})⁴) of their static part
/// (modal_residual.rs): on the knife's loss table (scenes/knife.toml, 30 108 DOFs) the
/// powers were within −0.72 % of the direct route's with the modes below 2 × f_max
/// (11 modes), within −0.05 … +0.18 % (4-digit rounding) below 4 × (20 modes).
pub const BAND_FACTOR: f64 = 4.0;
/// Fewest and most modes of a [`ModeChoice::Below`] band.
pub const MIN_MODES: usize = 6;
pub const MAX_MODES: usize = crate::settings::MODAL_MAX_MODES;

/// What the modal route used (run.json).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ModalSummary {
    /// Modes kept.
    pub modes: usize,
    /// Their highest natural frequency (1/time).
    pub highest_mode_frequency: f64,
    /// The band asked for (1/time), when the count came from a band.
    pub band_limit: Option<f64>,
    /// False when [`MAX_MODES`] stopped the band search before its limit.
    pub band_complete: bool,
    /// The static residual flexibility of the omitted modes was added.
    pub residual_flexibility: bool,
    /// Largest backward error of the kept modes.
    pub largest_backward_error: f64,
}

/// Errors of the modal route's setup.
#[derive(Debug, thiserror::Error)]
pub enum ModalRouteError {
    #[error("modal route: the stuck structure's modes: {0}")]
    Modes(#[from] ModalError),
    #[error(
        "modal route: the stuck structure's mode {mode} has λ = {lambda:e} (rad/time)²: the \
         structure is not held with its joints stuck; use the direct route"
    )]
    NotHeld { mode: usize, lambda: f64 },
    #[error("modal route: the stuck stiffness K_s (residual flexibility): {0}")]
    Static(#[from] CholmodError),
}

/// The modal data of one sweep and the current frequency's factorization of Z.
pub struct ModalRoute {
    lambda: Vec<f64>,
    shapes: Vec<Vec<f64>>,
    /// U = BΦ (m × p), C Φ (outputs × p), Φᵀf̂ (p).
    u: DMatrix<C64>,
    c: DMatrix<C64>,
    phi_f: Vec<C64>,
    /// ΦᵀDΦ and ΦᵀHΦ (p × p), when the sweep has them.
    damping: Option<DMatrix<f64>>,
    /// Modal damping 2ζ_rω_r per mode (rad/time; empty: none).
    modal_damping: Vec<f64>,
    structural: Option<DMatrix<f64>>,
    /// The omitted modes' residual flexibility and its inertia term, when asked for.
    residual: Option<Residual>,
    /// The last [`ModalRoute::receptance`]'s ω² and factorization of Z.
    w2: f64,
    z: Option<LU<C64, Dyn, Dyn>>,
    pub summary: ModalSummary,
    /// What the basis was built for ([`ModalRoute::serves`]).
    key: Key,
}

/// The settings and stuck structure a basis was built for.
struct Key {
    modes: ModeChoice,
    residual: bool,
    damping: (bool, bool),
    active: Vec<usize>,
    kappa0: Vec<[C64; 2]>,
    ks0: Vec<f64>,
}

impl ModalRoute {
    /// The kept modes' undamped natural frequencies (1/time, ascending): the stuck
    /// structure's resonances.
    pub fn frequencies(&self) -> Vec<f64> {
        self.lambda
            .iter()
            .map(|&l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
            .collect()
    }

    /// The stuck structure of `setup` with tangential κ₀ (per area, per active point) and
    /// spring stiffnesses `ks0`; `row(j)` the sparse contact row j of m.
    pub fn new<'r>(
        setup: &mut Setup,
        kappa0: &[[C64; 2]],
        ks0: &[f64],
        (m, row): (usize, &RowFn<'_, 'r>),
        modes: ModeChoice,
        residual: bool,
    ) -> Result<Self, ModalRouteError> {
        let p = setup.problem;
        // S(0) with κ₀ is K_s (no mass, damping × 0, structural off at ω = 0).
        setup.fill(0.0, kappa0, ks0);
        let ks = Csc {
            pattern: setup.s.pattern.clone(),
            values: setup.s.values.iter().map(|v| v.re).collect(),
        };
        let opts = ModalOptions::default();
        let (found, band_limit, band_complete) = match modes {
            ModeChoice::Count(count) => {
                let n = count.clamp(1, ks.n());
                let found = lowest_modes(&ks, &p.sys.m, &ModalOptions { n_modes: n, ..opts })?;
                (found, None, true)
            }
            ModeChoice::Below(limit) => {
                let b = modes_below(&ks, &p.sys.m, limit, MIN_MODES, MAX_MODES, &opts)?;
                (b.modes, Some(limit), b.complete)
            }
        };
        if let Some((mode, &lambda)) = found
            .eigenvalues
            .iter()
            .enumerate()
            .find(|(_, &l)| l <= 0.0)
        {
            return Err(ModalRouteError::NotHeld {
                mode: mode + 1,
                lambda,
            });
        }
        let np = found.eigenvalues.len();
        let outputs = &p.outputs;
        let nout = outputs.len();
        let shapes = found.shapes;
        let dot_row =
            |r: &[(usize, f64)], phi: &[f64]| r.iter().map(|&(i, w)| w * phi[i]).sum::<f64>();
        let u = DMatrix::from_fn(m, np, |j, r| C64::new(dot_row(row(j), &shapes[r]), 0.0));
        let c = DMatrix::from_fn(nout, np, |k, r| {
            C64::new(dot_row(&outputs[k].dofs, &shapes[r]), 0.0)
        });
        let project = |a: &Csc<f64>| {
            let images: Vec<Vec<f64>> = shapes.iter().map(|phi| a.mul_vec(phi)).collect();
            DMatrix::from_fn(np, np, |r, s| {
                shapes[r].iter().zip(&images[s]).map(|(x, y)| x * y).sum()
            })
        };
        let damping = setup.damping.map(project);
        // ζ_r of the model's modal damping, summed over the ranges that hold mode r.
        let modal_damping: Vec<f64> = if p.modal_damping.is_empty() {
            Vec::new()
        } else {
            found
                .eigenvalues
                .iter()
                .enumerate()
                .map(|(r, &l)| {
                    let w = l.sqrt();
                    2.0 * w
                        * p.modal_damping
                            .iter()
                            .map(|d| d.ratio_of(r + 1, w))
                            .sum::<f64>()
                })
                .collect()
        };
        let structural = setup.structural.map(project);
        let kept = Kept {
            shapes: &shapes,
            lambda: &found.eigenvalues,
        };
        let asked_residual = residual;
        let residual = if residual {
            Some(Residual::new(&ks, &p.sys.m, &kept, (m, row), outputs)?)
        } else {
            None
        };
        let summary = ModalSummary {
            modes: np,
            highest_mode_frequency: found.eigenvalues[np - 1].sqrt() / (2.0 * std::f64::consts::PI),
            band_limit,
            band_complete,
            residual_flexibility: residual.is_some(),
            largest_backward_error: found.residuals.iter().fold(0.0, |a: f64, &b| a.max(b)),
        };
        let mut route = ModalRoute {
            lambda: found.eigenvalues,
            shapes,
            u,
            c,
            phi_f: vec![C64::new(0.0, 0.0); np],
            residual,
            w2: 0.0,
            z: None,
            summary,
            damping,
            modal_damping,
            structural,
            key: Key {
                modes,
                residual: asked_residual,
                damping: (setup.damping.is_some(), setup.structural.is_some()),
                active: setup.active.clone(),
                kappa0: kappa0.to_vec(),
                ks0: ks0.to_vec(),
            },
        };
        route.set_load(&p.excitation, row, outputs)?;
        Ok(route)
    }

    /// Whether this basis serves a sweep of the same problem asking for `modes` and
    /// `residual` with the same damping parts (material, structural) and the same stuck
    /// structure (active points, κ₀, spring stiffnesses).
    pub fn serves(
        &self,
        (modes, residual): (ModeChoice, bool),
        setup: &Setup,
        kappa0: &[[C64; 2]],
        ks0: &[f64],
    ) -> bool {
        let k = &self.key;
        k.modes == modes
            && k.residual == residual
            && k.damping == (setup.damping.is_some(), setup.structural.is_some())
            && k.active == setup.active
            && k.kappa0 == kappa0
            && k.ks0 == ks0
    }

    /// The load's images Φᵀf̂ and, with the residual, its B and C images (four solves
    /// with K_s's factor).
    pub fn set_load<'r>(
        &mut self,
        f: &[C64],
        row: &dyn Fn(usize) -> &'r [(usize, f64)],
        outputs: &[Output],
    ) -> Result<(), CholmodError> {
        self.phi_f = self
            .shapes
            .iter()
            .map(|phi| phi.iter().zip(f).map(|(a, b)| b * *a).sum())
            .collect();
        let kept = Kept {
            shapes: &self.shapes,
            lambda: &self.lambda,
        };
        match self.residual.as_mut() {
            Some(r) => r.set_load(&kept, f, row, outputs),
            None => Ok(()),
        }
    }

    /// Factors Z(ω) and writes G, O, r₀, y₀ into `rec`. False when Z is singular (an
    /// undamped eigenfrequency): its pivots' ratio below `super::SINGULAR_RCOND`.
    pub fn receptance(&mut self, omega: f64, rec: &mut super::receptance::Receptance) -> bool {
        let np = self.lambda.len();
        let mut z = DMatrix::from_element(np, np, C64::new(0.0, 0.0));
        for r in 0..np {
            z[(r, r)] = C64::new(self.lambda[r] - omega * omega, 0.0);
        }
        for (r, c) in self.modal_damping.iter().enumerate() {
            z[(r, r)].im += omega * c;
        }
        if let Some(d) = &self.damping {
            z.zip_apply(d, |a, b| a.im += omega * b);
        }
        if let Some(h) = self.structural.as_ref().filter(|_| omega > 0.0) {
            z.zip_apply(h, |a, b| a.im += b);
        }
        // An undamped kept mode at ω: singular by the modes' own accuracy.
        if (0..np).any(|r| z[(r, r)].norm() <= SINGULAR_MODAL_REL * self.lambda[r]) {
            self.z = None;
            return false;
        }
        let lu = z.lu();
        let upper = lu.u();
        let diag: Vec<f64> = (0..np).map(|r| upper[(r, r)].norm()).collect();
        let (lo, hi) = diag
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
        if !(hi > 0.0 && lo / hi >= super::SINGULAR_RCOND) {
            self.z = None;
            return false;
        }
        let m = self.u.nrows();
        // Y = Z⁻¹ [Uᵀ | Φᵀf̂] (p × (m + 1)).
        let mut rhs = DMatrix::from_element(np, m + 1, C64::new(0.0, 0.0));
        rhs.view_mut((0, 0), (np, m)).copy_from(&self.u.transpose());
        for r in 0..np {
            rhs[(r, m)] = self.phi_f[r];
        }
        if !lu.solve_mut(&mut rhs) {
            self.z = None;
            return false;
        }
        let y = rhs;
        let g = &self.u * y.columns(0, m);
        let r0 = &self.u * y.column(m);
        let o = &self.c * y.columns(0, m);
        let y0 = &self.c * y.column(m);
        rec.g.copy_from_slice(g.as_slice());
        rec.o.copy_from_slice(o.as_slice());
        rec.r0.copy_from_slice(r0.as_slice());
        rec.y0.copy_from_slice(y0.as_slice());
        self.w2 = omega * omega;
        if let Some(r) = &self.residual {
            r.add_to(self.w2, &mut rec.g, &mut rec.o, &mut rec.r0, &mut rec.y0);
        }
        self.z = Some(lu);
        true
    }

    /// x ≈ S_s(ω)⁻¹ g at the frequency of the last [`ModalRoute::receptance`]: the modal
    /// part Φ Z⁻¹ Φᵀ g and, with the residual, (R + ω²RMR) g.
    pub fn field(&mut self, g: &[C64], x: &mut [C64]) -> Result<(), CholmodError> {
        let np = self.lambda.len();
        let proj: Vec<C64> = self
            .shapes
            .iter()
            .map(|phi| phi.iter().zip(g).map(|(a, b)| b * *a).sum())
            .collect();
        let mut q = DMatrix::from_column_slice(np, 1, &proj);
        if let Some(lu) = &self.z {
            lu.solve_mut(&mut q);
        }
        x.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        for (r, phi) in self.shapes.iter().enumerate() {
            for (xi, &p) in x.iter_mut().zip(phi) {
                *xi += q[r] * p;
            }
        }
        let kept = Kept {
            shapes: &self.shapes,
            lambda: &self.lambda,
        };
        match self.residual.as_mut() {
            Some(r) => r.add_field(&kept, self.w2, g, x),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
#[path = "modal_route_tests.rs"]
mod tests;
