//! The fast mode's results at one frequency: the independent check of a converged
//! solution and the row of outputs, power and per-point results.

use std::time::Instant;

use super::driver::Row;
use super::fast_unknowns::Unknowns;
use super::fast_workspace::Workspace;
use super::modal_route::ModalRoute;
use super::posteriori::{self, Claim, Verdict};
use super::{PointFreq, Setup, SweepError, SweepResult, C64};
use crate::settings::IterationSpec;
use crate::solve::umfpack::Numeric;

impl Workspace {
    /// (ΔBû)ⱼ: the diagonal, and with coupled slip the point's off-diagonal.
    pub(super) fn delta_r(&self, j: usize, nc: usize) -> C64 {
        let off = if j < 2 * nc {
            self.delta_off[j / 2] * self.r[j ^ 1]
        } else {
            C64::new(0.0, 0.0)
        };
        self.delta[j] * self.r[j] + off
    }

    /// The independent check of a converged frequency (posteriori.rs); the condensed
    /// path forms x = S₀⁻¹(f̂ − Bᵀ Δ r) for it (one more solve, by the factorization or
    /// the modal route).
    pub fn check(
        &mut self,
        setup: &Setup,
        un: &Unknowns,
        (num, modal): (Option<&Numeric>, Option<&mut ModalRoute>),
        omega: f64,
        f: f64,
        it: IterationSpec,
    ) -> Result<Verdict, SweepError> {
        let (p, na, nc) = (un.p, un.active.len(), un.coupled_points());
        if self.condensed {
            self.x_rhs.copy_from_slice(&p.excitation);
            for j in 0..un.m {
                let c = self.delta_r(j, nc);
                for &(i, w) in un.row(j) {
                    self.x_rhs[i] -= c * w;
                }
            }
            if let Some(num) = num {
                num.solve_into(&self.x_rhs, &mut self.x_full)
                    .map_err(|source| SweepError::Umfpack { freq: f, source })?;
            } else if let Some(route) = modal {
                route
                    .field(&self.x_rhs, &mut self.x_full)
                    .map_err(|source| SweepError::ModalField { freq: f, source })?;
            }
        }
        let lin = &self.lin;
        let kappa: Vec<[C64; 2]> = (0..na)
            .map(|q| {
                [
                    un.kappa(&lin[2 * q], omega),
                    un.kappa(&lin[2 * q + 1], omega),
                ]
            })
            .collect();
        let amplitudes: Vec<[f64; 2]> = (0..na)
            .map(|q| [self.a[2 * q], self.a[2 * q + 1]])
            .collect();
        let kappa_off: Vec<C64> = self
            .lin2
            .iter()
            .map(|l| un.kappa2(l, 0, 1, omega))
            .collect();
        let claim = Claim {
            kappa: &kappa,
            kappa_off: &kappa_off,
            correlation: &self.rho,
            amplitudes: &amplitudes,
            caps: &vec![f64::INFINITY; na],
            spring_k: &self.ks,
        };
        let scale = self
            .a
            .iter()
            .chain(&self.a_star)
            .fold(0.0f64, |x, &y| x.max(y));
        let atol = super::ATOL_REL.min(it.tolerance) * scale;
        Ok(posteriori::check(
            setup,
            omega,
            &claim,
            self.field(),
            it.tolerance,
            atol,
        ))
    }

    /// The displacement amplitude of every free DOF at the last solve (length).
    pub fn field(&self) -> &[C64] {
        if self.condensed {
            &self.x_full
        } else {
            &self.u
        }
    }

    /// Outputs ŷ = o₀ − O Δ r (condensed) or C û (FGMRES), the joints' power and the
    /// per-point results of the frequency f.
    pub fn row(&self, un: &Unknowns, f: f64, point_results: bool, res: &mut SweepResult) -> Row {
        let (p, m, nc, eff) = (un.p, un.m, un.coupled_points(), un.eff);
        let nout = p.outputs.len();
        let outputs: Vec<C64> = if self.condensed {
            (0..nout)
                .map(|k| {
                    self.rec.y0[k]
                        - (0..m)
                            .map(|j| self.rec.o[k + nout * j] * self.delta_r(j, nc))
                            .sum::<C64>()
                })
                .collect()
        } else {
            p.outputs.iter().map(|o| o.value(&self.u)).collect()
        };
        let t = Instant::now();
        let mut power = 0.0;
        let mut pts = point_results.then(|| vec![PointFreq::default(); p.contacts.len()]);
        for q in 0..un.active.len() {
            let (l1, l2) = (&self.lin[2 * q], &self.lin[2 * q + 1]);
            let e = if eff.contact_damping {
                (l1.energy_per_cycle + l2.energy_per_cycle) * un.area[q]
            } else {
                0.0
            };
            power += e * f;
            if let Some(pts) = pts.as_mut() {
                pts[un.active[q]] = PointFreq {
                    amplitude: [self.a_star[2 * q], self.a_star[2 * q + 1]],
                    k_star: [l1.k_star, l2.k_star],
                    d_star: if eff.contact_damping {
                        [l1.d_star, l2.d_star]
                    } else {
                        [0.0; 2]
                    },
                    energy: e,
                    ratio: [l1.amplitude_ratio, l2.amplitude_ratio],
                    regime: [l1.regime, l2.regime],
                };
            }
        }
        if pts.is_some() {
            res.time("point outputs", t);
        }
        Row {
            outputs,
            power,
            points: pts,
            ..Row::default()
        }
    }
}
