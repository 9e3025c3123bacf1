//! A-posteriori check of a converged frequency, by a path independent of the solve: the
//! residual of the linearized equations (docs/model.md §5)
//!
//!   r = (K + K_c(k*) − ω²M + iω(D + D_c(d*))) x − f̂
//!
//! formed from the unfactored parts (Setup::base, M, D, and each active point's springs
//! through its contact rows Bⱼ, not the assembled pair blocks), every sum compensated
//! (Ogita–Rump–Oishi Dot2: TwoProduct by FMA, TwoSum), so the near-cancellation of
//! K − ω²M at a resonance costs no digits. The frequency passes when
//! - ‖r‖₂ ≤ [`RESIDUAL_REL`]·rtol·‖f̂‖₂ or the normwise backward error
//!   η = ‖r‖₂/(‖S‖‖x‖₂ + ‖f̂‖₂) ≤ [`ROUNDOFF`]·ε (the contact iteration's FGMRES stops
//!   at ‖r‖ ≤ 1e-4·rtol·‖f̂‖ or η ≤ 8ε), and
//! - every amplitude the linearization used agrees with |Bⱼx| by the convergence test
//!   (twice its tolerance).

use super::{Setup, C64};

/// ‖r‖/‖f̂‖ must stay below this multiple of rtol: the equations hold to a tenth of the
/// tolerance asked of the amplitudes (FGMRES stops at 1e-4·rtol, `fast::GMRES_REL`; the
/// condensed path's x = S₀⁻¹(f̂ − BᵀΔr) left 6e-9 at rtol 1e-6 on the block of
/// block-stick.toml with k_T0 = 1e12 N/mm³, where it equals thesis mode's to 1.2e-8) ...
pub const RESIDUAL_REL: f64 = 0.1;
/// ... or η below this multiple of ε: round-off of the product S x (a direct solve with
/// the factorization leaves η ≤ 2ε, FGMRES stops at 8ε, `krylov::ROUNDOFF`), reached
/// near a resonance where ‖S‖‖x‖ ≫ ‖f̂‖.
pub const ROUNDOFF: f64 = 100.0;

/// Compensated sum of products.
#[derive(Debug, Clone, Copy, Default)]
struct Dot2 {
    s: f64,
    c: f64,
}

impl Dot2 {
    fn add_prod(&mut self, a: f64, b: f64) {
        let p = a * b;
        let ep = a.mul_add(b, -p);
        let s = self.s + p;
        let z = s - self.s;
        let es = (self.s - (s - z)) + (p - z);
        self.s = s;
        self.c += ep + es;
    }

    fn value(self) -> f64 {
        self.s + self.c
    }
}

/// Complex accumulator of Dot2 parts.
#[derive(Debug, Clone, Copy, Default)]
struct CDot2 {
    re: Dot2,
    im: Dot2,
}

impl CDot2 {
    /// += a·z.
    fn add(&mut self, a: C64, z: C64) {
        self.re.add_prod(a.re, z.re);
        self.re.add_prod(-a.im, z.im);
        self.im.add_prod(a.re, z.im);
        self.im.add_prod(a.im, z.re);
    }

    /// += a·z for a real a (what [`CDot2::add`] does with a zero imaginary part, whose
    /// products are exact zeros).
    fn add_real(&mut self, a: f64, z: C64) {
        self.re.add_prod(a, z.re);
        self.im.add_prod(a, z.im);
    }

    /// += i·b·z for a real b.
    fn add_imaginary(&mut self, b: f64, z: C64) {
        self.re.add_prod(-b, z.im);
        self.im.add_prod(b, z.re);
    }

    fn value(self) -> C64 {
        C64::new(self.re.value(), self.im.value())
    }
}

/// Outcome of the check at one frequency.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Verdict {
    /// Normwise backward error η of x.
    pub backward_error: f64,
    /// ‖r‖₂/‖f̂‖₂.
    pub relative_residual: f64,
    /// Largest |a − |Bⱼx|| over the allowed (twice the convergence tolerance); ≤ 1 passes.
    pub consistency: f64,
}

impl Verdict {
    pub fn passes(&self, rtol: f64) -> bool {
        let solved = self.relative_residual <= RESIDUAL_REL * rtol
            || self.backward_error <= ROUNDOFF * f64::EPSILON;
        solved && self.consistency <= 1.0
    }
}

/// What the converged state claims at one frequency, per active point: κ (per area) and
/// the two tangential amplitudes it was linearized for, with the cap applied to |Bⱼx|
/// before comparing (δ* when macroslip is off and the host caps what it reports,
/// otherwise ∞); k* per cubic spring.
pub struct Claim<'a> {
    pub kappa: &'a [[C64; 2]],
    /// Coupled slip: κ₁₂ = κ₂₁ per point (per area) and the phase cosine ρ the
    /// linearization used; both empty for the thesis's model.
    pub kappa_off: &'a [C64],
    pub correlation: &'a [f64],
    pub amplitudes: &'a [[f64; 2]],
    pub caps: &'a [f64],
    pub spring_k: &'a [f64],
}

/// Checks x at ω against `claim`; `rtol`, `atol` of the convergence test.
pub fn check(setup: &Setup, omega: f64, claim: &Claim, x: &[C64], rtol: f64, atol: f64) -> Verdict {
    let eq = residual(
        setup,
        omega,
        (claim.kappa, claim.kappa_off),
        claim.spring_k,
        x,
        &setup.problem.excitation,
    );
    let mut consistency = 0.0f64;
    // ρ by the sweep's test (fast_coupled::rho_consistent), twice its tolerance.
    for (j, (rho, bx)) in claim.correlation.iter().zip(&eq.contact).enumerate() {
        let [a1, a2] = claim.amplitudes[j];
        let (lo, hi) = (a1.min(a2), a1.max(a2));
        if hi > 0.0 {
            let off = (rho - super::fast_coupled::correlation(bx[0], bx[1])).abs() * lo;
            consistency = consistency.max(off / (2.0 * rtol * hi));
        }
    }
    for (j, bx) in eq.contact.iter().enumerate() {
        for d in 0..2 {
            let (a, b) = (claim.amplitudes[j][d], bx[d].norm().min(claim.caps[j]));
            let allowed = 2.0 * (rtol * a.max(b) + atol);
            consistency = consistency.max(if allowed > 0.0 {
                (a - b).abs() / allowed
            } else if a == b {
                0.0
            } else {
                f64::INFINITY
            });
        }
    }
    Verdict {
        backward_error: eq.backward_error(),
        relative_residual: eq.relative_residual(),
        consistency,
    }
}

/// The residual of S x = f̂ ([`residual`]).
pub struct Equations {
    /// ‖S x − f̂‖₂, compensated.
    pub residual: f64,
    /// ‖S‖ (the geometric mean of its 1- and ∞-norm bounds) ‖x‖₂ + ‖f̂‖₂.
    pub scale: f64,
    /// ‖f̂‖₂.
    pub load: f64,
    /// Bⱼx per active point: its two relative tangential displacements.
    pub contact: Vec<[C64; 2]>,
}

impl Equations {
    /// Normwise backward error η = ‖r‖/(‖S‖‖x‖ + ‖f̂‖) (0 for x = f̂ = 0).
    pub fn backward_error(&self) -> f64 {
        if self.scale > 0.0 {
            self.residual / self.scale
        } else {
            0.0
        }
    }

    /// ‖r‖/‖f̂‖ (‖r‖ for f̂ = 0).
    pub fn relative_residual(&self) -> f64 {
        if self.load > 0.0 {
            self.residual / self.load
        } else {
            self.residual
        }
    }
}

/// r = (K + K_c(κ) − ω²M + iωD) x − f̂ from the unfactored parts (module docs), κ per
/// area on each active point's rows, k* − k on each cubic spring's (`spring_k` may be
/// shorter than the springs: the rest keep their linear k, which is in base).
pub fn residual(
    setup: &Setup,
    omega: f64,
    (kappa, kappa_off): (&[[C64; 2]], &[C64]),
    spring_k: &[f64],
    x: &[C64],
    f: &[C64],
) -> Equations {
    let p = setup.problem;
    let pt = &p.sys.pattern;
    let n = pt.n;
    let w2 = omega * omega;
    let mut y = vec![CDot2::default(); n];
    let (mut cols, mut rows) = (vec![0.0f64; n], vec![0.0f64; n]);
    let (base, m) = (&setup.base, &p.sys.m.values);
    let damping = setup.damping.map(|d| &d.values);
    let structural = setup.structural.filter(|_| omega > 0.0).map(|h| &h.values);
    for (j, &xj) in x[..n].iter().enumerate() {
        for k in pt.col_ptr[j] as usize..pt.col_ptr[j + 1] as usize {
            let i = pt.row_idx[k] as usize;
            let d = damping.map_or(0.0, |d| d[k]);
            let h = structural.map_or(0.0, |h| h[k]);
            let imaginary = omega * d + h;
            // K, −ω²M and iω(D + H) each on their own: no digit lost where K − ω²M cancels.
            y[i].add_real(base[k], xj);
            y[i].add_real(-w2 * m[k], xj);
            if imaginary != 0.0 {
                y[i].add_imaginary(imaginary, xj);
            }
            let v = C64::new(base[k] - w2 * m[k], imaginary).norm();
            cols[j] += v;
            rows[i] += v;
        }
    }
    let max = |s: &[f64]| s.iter().fold(0.0f64, |a, &b| a.max(b));
    let mut s_norm = (max(&cols) * max(&rows)).sqrt();
    // Bⱼᵀ (κ·area) Bⱼ x per active point and direction, and (k* − k) rᵀ r x per cubic
    // spring (its linear k is in base).
    let mut springs = |row: &[(usize, f64)], coef: C64| -> C64 {
        let mut bx = CDot2::default();
        for &(i, w) in row {
            bx.add(C64::new(w, 0.0), x[i]);
        }
        let bx = bx.value();
        for &(i, w) in row {
            y[i].add(coef * w, bx);
        }
        s_norm += coef.norm() * row.iter().map(|&(_, w)| w * w).sum::<f64>();
        bx
    };
    let contact: Vec<[C64; 2]> = setup
        .active
        .iter()
        .enumerate()
        .map(|(j, &i)| {
            let c = &p.contacts[i];
            std::array::from_fn(|d| springs(&c.rows[1 + d], kappa[j][d] * c.area))
        })
        .collect();
    for (sp, &k) in p.cubic_springs.iter().zip(spring_k) {
        springs(&sp.row, C64::new(k - sp.stiffness, 0.0));
    }
    // Coupled slip: B₁ᵀ κ₁₂ B₂ x + B₂ᵀ κ₁₂ B₁ x per point.
    for (j, k12) in kappa_off.iter().enumerate() {
        let c = &p.contacts[setup.active[j]];
        let coef = k12 * c.area;
        for d in 0..2 {
            for &(i, w) in &c.rows[1 + d] {
                y[i].add(coef * w, contact[j][1 - d]);
            }
        }
        let norm2 = |d: usize| c.rows[1 + d].iter().map(|&(_, w)| w * w).sum::<f64>();
        s_norm += 2.0 * coef.norm() * (norm2(0) * norm2(1)).sqrt();
    }
    let norm = |v: &mut dyn Iterator<Item = C64>| v.map(|z| z.norm_sqr()).sum::<f64>().sqrt();
    let residual = norm(&mut y.iter().zip(f).map(|(yi, fi)| {
        let mut acc = *yi;
        acc.add(C64::new(-1.0, 0.0), *fi);
        acc.value()
    }));
    let load = norm(&mut f.iter().copied());
    Equations {
        residual,
        scale: s_norm * norm(&mut x.iter().copied()) + load,
        load,
        contact,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::sweep::three_beams_coarse;

    #[test]
    fn a_planted_wrong_solution_is_caught() {
        let (scene, p, stat) = three_beams_coarse();
        let mut setup = Setup::new(&p, &stat, &scene.spec.effects).unwrap();
        // Stuck joints (κ = k_T0) near the first resonance (1174.5 Hz), where K − ω²M
        // nearly cancels.
        let f = 1170.0;
        let omega = 2.0 * std::f64::consts::PI * f;
        let kt = p.interfaces[0].contact.k_t0_per_area;
        let kappa = vec![[C64::new(kt, 0.0); 2]; setup.active.len()];
        setup.fill(omega, &kappa, &[]);
        let num = setup.factor(f).unwrap().unwrap();
        let mut x = vec![C64::new(0.0, 0.0); p.sys.dofs.n_free()];
        num.solve_into(&p.excitation, &mut x).unwrap();
        let amps: Vec<[f64; 2]> = (0..setup.active.len())
            .map(|j| setup.tangential(j, &x).map(|v| v.norm()))
            .collect();
        let rtol = 1e-3;
        let caps = vec![f64::INFINITY; amps.len()];
        let claim = |kappa, amplitudes| Claim {
            kappa,
            kappa_off: &[],
            correlation: &[],
            amplitudes,
            caps: &caps,
            spring_k: &[],
        };
        let ok = check(&setup, omega, &claim(&kappa, &amps), &x, rtol, 0.0);
        assert!(ok.passes(rtol), "{ok:?}");
        assert!(ok.backward_error < 1e-13, "{ok:?}");
        eprintln!("right: {ok:?}");

        // x off by 1e-4 relative, alternating in sign from DOF to DOF.
        let wrong: Vec<C64> = x
            .iter()
            .enumerate()
            .map(|(i, v)| v * (1.0 + 1e-4 * if i % 2 == 0 { 1.0 } else { -1.0 }))
            .collect();
        let v = check(&setup, omega, &claim(&kappa, &amps), &wrong, rtol, 0.0);
        eprintln!("x off: {v:?}");
        assert!(!v.passes(rtol), "{v:?}");
        // The right x claimed for k* 10 % off at every point.
        let soft: Vec<[C64; 2]> = kappa.iter().map(|k| k.map(|v| v * 0.9)).collect();
        let v = check(&setup, omega, &claim(&soft, &amps), &x, rtol, 0.0);
        eprintln!("k* off: {v:?}");
        assert!(!v.passes(rtol), "{v:?}");
        // The right x and k*, linearized for amplitudes 1 % off.
        let off: Vec<[f64; 2]> = amps.iter().map(|a| a.map(|v| v * 1.01)).collect();
        let v = check(&setup, omega, &claim(&kappa, &off), &x, rtol, 0.0);
        assert!(!v.passes(rtol) && v.backward_error < 1e-13, "{v:?}");
    }
}
