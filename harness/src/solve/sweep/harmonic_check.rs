//! A-posteriori check of a converged harmonic balance ([`super::harmonic_fe`]) by the
//! uncondensed path: per harmonic h = 0..H the full equations
//!
//!   S_h x_h = f̂ δ_h1 − Bᵀ ĝ_h,    S_h = K + K_N + k_T0·BᵀAB − (hω)²M + i·hω·D
//!
//! solved with a fresh factorization of S_h (not the receptances G_h that Newton
//! iterated on), with ĝ the contact forces of the converged r. The frequency passes when
//! - each x_h solves its equations: the residual formed from the unfactored parts in
//!   compensated sums ([`posteriori::residual`]) meets the rule of the other modes
//!   ([`Verdict::passes`]: ‖r‖ ≤ 0.1·rtol·‖rhs‖ over all harmonics, or η ≤ 100ε), and
//! - the balance's claim holds: ‖B x − r‖₂ over all harmonics and directions is at most
//!   twice what Newton's stop allows (‖R‖ ≤ rtol·‖r₀‖; R = r − B x exactly when the
//!   condensation is right), reported as `consistency` ≤ 1.
//!
//! Cost: H + 1 factorizations and solves per converged frequency, beside the balance's
//! H + 1 factorizations and (H + 1)·m solves.

use super::harmonic_fe::{FeBalance, FeSolution};
use super::posteriori::{self, Verdict};
use super::receptance::Receptance;
use super::{SweepError, C64};

impl FeBalance<'_, '_> {
    /// Checks the converged `sol` at the condensed ω; `rtol` of the balance's Newton,
    /// `freq` for messages.
    pub fn check(&mut self, sol: &FeSolution, rtol: f64, freq: f64) -> Result<Verdict, SweepError> {
        let nc = self.tr.ncoef();
        let h_max = (nc - 1) / 2;
        let p = self.setup.problem;
        let kref = self.reference();
        let rows = self.rows();
        let row = |k: usize| rows[k];
        let m = self.m();
        // Coefficient h of a direction-major real vector as a complex amplitude a − ib.
        let coef = |v: &[f64], k: usize, h: usize| {
            if h == 0 {
                C64::new(v[k * nc], 0.0)
            } else {
                C64::new(v[k * nc + 2 * h - 1], -v[k * nc + 2 * h])
            }
        };
        let n = p.sys.dofs.n_free();
        let (mut res2, mut load2, mut eta, mut miss2) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let mut x = vec![C64::new(0.0, 0.0); n];
        for h in 0..=h_max {
            let omega = h as f64 * self.omega;
            let mut rhs = if h == 1 {
                p.excitation.clone()
            } else {
                vec![C64::new(0.0, 0.0); n]
            };
            for k in 0..m {
                let g = coef(&sol.ghat, k, h);
                for &(i, w) in row(k) {
                    rhs[i] -= g * w;
                }
            }
            let unproven = Verdict {
                backward_error: f64::INFINITY,
                relative_residual: f64::INFINITY,
                consistency: f64::INFINITY,
            };
            if let Some(route) = self.modal.as_mut() {
                // The modal route's own field: its residual in the full equations is
                // the truncation error (reported), its consistency the claim's check.
                let mut scratch = Receptance::new(0, m, p.outputs.len());
                if !route.receptance(omega, &mut scratch) {
                    return Ok(unproven);
                }
                route
                    .field(&rhs, &mut x)
                    .map_err(|source| SweepError::ModalField { freq, source })?;
            } else {
                self.setup.fill(omega, &kref, &[]);
                self.stats.factorizations += 1;
                // Regular when the balance condensed it; a singular refactorization is
                // no evidence for the solution.
                let Some(num) = self.setup.factor(freq)? else {
                    return Ok(unproven);
                };
                num.solve_into(&rhs, &mut x)
                    .map_err(|source| SweepError::Umfpack { freq, source })?;
            }
            let eq = posteriori::residual(self.setup, omega, (&kref, &[]), &[], &x, &rhs);
            res2 += eq.residual * eq.residual;
            load2 += eq.load * eq.load;
            eta = eta.max(eq.backward_error());
            for k in 0..m {
                let bx: C64 = row(k).iter().map(|&(i, w)| x[i] * w).sum();
                let claim = coef(&sol.r, k, h);
                let bx = if h == 0 { C64::new(bx.re, 0.0) } else { bx };
                miss2 += (bx - claim).norm_sqr();
            }
        }
        let start = self.linear_start();
        let scale = start.iter().map(|v| v * v).sum::<f64>().sqrt();
        let allowed = 2.0 * rtol * scale;
        let miss = miss2.sqrt();
        Ok(Verdict {
            backward_error: eta,
            relative_residual: if load2 > 0.0 {
                (res2 / load2).sqrt()
            } else {
                res2.sqrt()
            },
            consistency: if allowed > 0.0 {
                miss / allowed
            } else if miss == 0.0 {
                0.0
            } else {
                f64::INFINITY
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::mhb::NewtonOptions;
    use crate::solve::sweep::harmonic_fe::FeBalance;
    use crate::solve::sweep::{three_beams_coarse, Setup};

    /// three-beams-coarse at 1180 Hz (just above its first resonance, the joints in
    /// microslip), H = 3: the converged balance passes; the same solution with one
    /// contact coefficient 1 % off, or claimed for forces 1 % off, does not.
    #[test]
    fn the_uncondensed_path_confirms_a_balance_and_catches_planted_errors() {
        let (scene, p, stat) = three_beams_coarse();
        let mut setup = Setup::new(&p, &stat, &scene.spec.effects).unwrap();
        let mut hb = FeBalance::new(&mut setup, 3, 64);
        let f = 1180.0;
        assert!(hb.condense(2.0 * std::f64::consts::PI * f).unwrap());
        let rtol = 1e-6;
        let opt = NewtonOptions { rtol, max_iter: 50 };
        let sol = hb.solve(&hb.linear_start(), opt).unwrap();
        assert!(sol.converged, "{}", sol.residual);
        let v = hb.check(&sol, rtol, f).unwrap();
        eprintln!("right: {v:?}");
        assert!(v.passes(rtol), "{v:?}");
        assert!(v.consistency <= 0.5 + 1e-9, "{v:?}");

        let nc = hb.tr.ncoef();
        let mut off = sol.clone();
        off.r[nc + 1] *= 1.01;
        let v = hb.check(&off, rtol, f).unwrap();
        eprintln!("r off: {v:?}");
        assert!(!v.passes(rtol), "{v:?}");

        let mut forces = sol.clone();
        forces.ghat.iter_mut().for_each(|g| *g *= 1.01);
        let v = hb.check(&forces, rtol, f).unwrap();
        eprintln!("forces off: {v:?}");
        assert!(!v.passes(rtol), "{v:?}");
    }
}
