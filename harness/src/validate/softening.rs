//! Softening friction oscillator with folds (scenes/softening-friction.toml):
//! m ẍ + c ẋ + k x + α x³ + F_T(x) = F cos ωt, α < 0 (a softening support) and F_T a
//! Mindlin contact to ground (Masing rule). A friction contact alone does not fold (the
//! dissipation grows as fast as the stiffness falls; docs/mhb.md); the softening support
//! bends the resonant branch over itself while the contact slips on it.
//!
//! Independent fold reference: a dense scan of the first-order residual
//! g(A, ω) = A·|k*_c(A) + k*_f(A) − mω² + i(cω + ωd*_f(A))| − F, k*_c = k + ¾αA² ((3.8),
//! `jointlin_linearize_cubic`) and k*_f, d*_f of the contact ((4.3), (3.14),
//! `jointlin_linearize`), counting its roots in A per ω. Then pseudo-arclength
//! continuation of the harmonic balance through both folds, and RK4 at points of the
//! stable branches.

use nalgebra::{Complex, DMatrix};

use super::{Report, Row};
use crate::capi::{self, Tangential};
use crate::mhb::continuation::{trace, Branch, Options};
use crate::mhb::{default_samples, first_order, state_at_zero, Element, Hb, Law, MhbError, System};
use crate::names::{LawName, RuleName};
use crate::time::mhb_reference as reference;

/// Parameters (SI: kg, N/m, N/m³, N·s/m, N); [`Self::scene`] are those of the scene.
#[derive(Debug, Clone, Copy)]
pub struct SofteningFriction {
    pub m: f64,
    pub c: f64,
    pub k: f64,
    /// Cubic coefficient α (< 0: softening), N/m³.
    pub alpha: f64,
    pub contact: Tangential,
    /// Force amplitude F (N), load F cos ωt.
    pub force: f64,
}

impl SofteningFriction {
    /// scenes/softening-friction.toml: m = 1, c = 0.05, k = 100, α = −1000, Mindlin
    /// (Masing) μ = 0.5, F_N = 0.2, k_T0 = 100 (δ* = 1.5 mm), F = 0.18.
    pub fn scene() -> Self {
        SofteningFriction {
            m: 1.0,
            c: 0.05,
            k: 100.0,
            alpha: -1000.0,
            contact: Tangential {
                law: LawName::Mindlin,
                rule: RuleName::Masing,
                mu: 0.5,
                normal: 0.2,
                k_t0: 100.0,
            },
            force: 0.18,
        }
    }

    /// Amplitude bound of the scans: half the static stability limit √(k/|α|) of the
    /// softening spring. Above it lies the branch that runs up the backbone towards the
    /// limit (k*_c → 0), which the scene's sweep and force stay clear of.
    pub fn amplitude_bound(&self) -> f64 {
        0.5 * (self.k / self.alpha.abs()).sqrt()
    }

    /// (k*_c + k*_f, ωd*_f) per amplitude (ωd* of a rate-independent contact does not
    /// depend on ω, so one linearization per amplitude serves every frequency).
    fn stiffness_damping(&self, amps: &[f64]) -> Result<Vec<(f64, f64)>, capi::CapiError> {
        amps.iter()
            .map(|&a| {
                let kc = capi::linearize_cubic(self.k, self.alpha, a)?;
                let f = capi::linearize(&self.contact, a, 1.0)?;
                Ok((kc + f.k_star, f.d_star))
            })
            .collect()
    }

    /// g(A, ω)/F: the first-order residual relative to the force (0 on the response).
    pub fn residual(&self, a: f64, omega: f64) -> Result<f64, capi::CapiError> {
        let (k, wd) = self.stiffness_damping(&[a])?[0];
        Ok(a * (k - self.m * omega * omega).hypot(self.c * omega + wd) / self.force - 1.0)
    }

    /// Number of first-order amplitudes A ≤ [`Self::amplitude_bound`] at each ω: sign
    /// changes of g(A, ω) over 4000 log-spaced amplitudes from 1e-3 δ*.
    pub fn first_order_counts(&self, omegas: &[f64]) -> Result<Vec<usize>, capi::CapiError> {
        let dstar = capi::linearize(&self.contact, 0.0, 1.0)?.slip_limit;
        let (a0, a1) = (1e-3 * dstar, self.amplitude_bound());
        let amps: Vec<f64> = (0..4000)
            .map(|i| a0 * (a1 / a0).powf(i as f64 / 3999.0))
            .collect();
        let kd = self.stiffness_damping(&amps)?;
        Ok(omegas
            .iter()
            .map(|&w| {
                let g: Vec<f64> = amps
                    .iter()
                    .zip(&kd)
                    .map(|(a, (k, wd))| {
                        a * (k - self.m * w * w).hypot(self.c * w + wd) - self.force
                    })
                    .collect();
                g.windows(2)
                    .filter(|p| p[0].signum() != p[1].signum())
                    .count()
            })
            .collect())
    }

    /// First-order folds (lower, upper) ω: the first and last frequency with three
    /// amplitudes on a grid of `step` rad/s over [lo, hi].
    pub fn first_order_folds(
        &self,
        lo: f64,
        hi: f64,
        step: f64,
    ) -> Result<Option<(f64, f64)>, capi::CapiError> {
        let omegas: Vec<f64> = (0..=((hi - lo) / step).round() as usize)
            .map(|i| lo + step * i as f64)
            .collect();
        let counts = self.first_order_counts(&omegas)?;
        let three: Vec<f64> = omegas
            .iter()
            .zip(&counts)
            .filter(|(_, &n)| n == 3)
            .map(|(&w, _)| w)
            .collect();
        Ok(three.first().map(|&a| (a, *three.last().unwrap_or(&a))))
    }

    /// The lumped system of [`crate::mhb`]: one DOF, the cubic term and the contact as
    /// elements to ground, load F cos ωt.
    pub fn system(&self) -> System {
        let one = |v: f64| DMatrix::from_element(1, 1, v);
        System {
            m: one(self.m),
            d: one(self.c),
            k: one(self.k),
            f0: vec![0.0],
            f1: vec![Complex::new(self.force, 0.0)],
            elements: vec![
                Element {
                    i: 0,
                    j: None,
                    law: Law::Cubic(self.alpha),
                },
                Element {
                    i: 0,
                    j: None,
                    law: Law::Point(self.contact),
                },
            ],
        }
    }
}

/// Continuation of the `h`-harmonic balance of `sys` from ω = `from` to `to` (either
/// direction), started on the first-order solution from a small amplitude.
pub fn continuation(
    sys: &System,
    h: usize,
    from: f64,
    to: f64,
) -> Result<(Hb<'_>, Branch), MhbError> {
    let mut hb = Hb::new(sys, h, default_samples(h));
    let x1 = first_order::solve(sys, from, &[1e-4, 1e-4])?;
    let m = 2 * h + 1;
    let mut u0 = vec![0.0; m];
    u0[1] = x1[0].re;
    u0[2] = -x1[0].im;
    let opt = Options {
        omega_start: from,
        omega_end: to,
        step: 0.01,
        step_min: 1e-7,
        step_max: 0.05,
        max_points: 5000,
        rtol: 1e-10,
    };
    let br = trace(&mut hb, &u0, opt)?;
    Ok((hb, br))
}

/// Initial state (x, ẋ) at t = 0 of a one-DOF harmonic-balance solution.
pub fn initial_state(hb: &Hb, u: &[f64], omega: f64) -> ([f64; 1], [f64; 1]) {
    let (x, v) = state_at_zero(&u[..2 * hb.h() + 1], hb.h(), omega);
    ([x[0]], [v[0]])
}

/// RK4 reference amplitude (1024 steps per period, periodic to 1e-9) started on a
/// harmonic-balance solution.
pub fn time_domain(sys: &System, hb: &Hb, u: &[f64], omega: f64) -> Result<f64, MhbError> {
    let (x0, v0) = initial_state(hb, u, omega);
    Ok(reference::steady(sys, omega, &x0, &v0, 1024, 1e-9, 5000)?.amplitude[0])
}

/// `jointlin validate --case softening-friction`: folds of the scan and of continuation
/// (H = 1 and 3), the unstable stretch, and H = 3 against RK4 on both stable branches.
pub fn sweep(rep: &mut Report, log: &dyn Fn(&str)) -> Result<(), String> {
    let case = "softening-friction";
    let p = SofteningFriction::scene();
    let sys = p.system();
    let t0 = std::time::Instant::now();
    log(&format!("{case}: first-order scan"));
    let scan = p
        .first_order_folds(9.0, 10.5, 1e-3)
        .map_err(|e| e.to_string())?;
    match scan {
        Some((lo, hi)) => rep.notes.push((
            case.into(),
            format!("first-order residual scan (Δω = 1e-3 rad/s): three amplitudes for {lo:.3} ≤ ω ≤ {hi:.3} rad/s"),
        )),
        None => rep.notes.push((case.into(), "first-order residual scan: no folds".into())),
    }
    for h in [1usize, 3] {
        log(&format!("{case}: continuation H = {h}"));
        let (hb, br) = continuation(&sys, h, 8.5, 11.0).map_err(|e| e.to_string())?;
        let unstable: Vec<f64> = br
            .points
            .iter()
            .filter(|q| !q.stable)
            .map(|q| q.sol.omega)
            .collect();
        let span = unstable
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &w| {
                (a.min(w), b.max(w))
            });
        let folds: Vec<String> = br.folds.iter().map(|w| format!("{w:.4}")).collect();
        rep.notes.push((
            case.into(),
            format!(
                "continuation H = {h}: folds at ω = {} rad/s; {} of {} points marked unstable, ω in [{:.3}, {:.3}]",
                folds.join(", "),
                unstable.len(),
                br.points.len(),
                span.0,
                span.1
            ),
        ));
        if h != 3 {
            continue;
        }
        // Amplitude vs RK4 on the resonant branch (upper) and the low branch at two
        // frequencies between the folds, where both are stable.
        for &w in &[9.6, 9.75] {
            for (name, upper) in [("resonant", true), ("low", false)] {
                let on: Vec<&crate::mhb::continuation::Point> =
                    br.points.iter().filter(|q| q.stable).collect();
                let pick = on
                    .windows(2)
                    .filter(|q| (q[0].sol.omega - w) * (q[1].sol.omega - w) <= 0.0)
                    .map(|q| q[0])
                    .max_by(|a, b| {
                        let (x, y) = (hb.amplitude(&a.sol.u, 0), hb.amplitude(&b.sol.u, 0));
                        if upper {
                            x.total_cmp(&y)
                        } else {
                            y.total_cmp(&x)
                        }
                    });
                let Some(q) = pick else { continue };
                let a = hb.amplitude(&q.sol.u, 0);
                let td =
                    time_domain(&sys, &hb, &q.sol.u, q.sol.omega).map_err(|e| e.to_string())?;
                rep.rows.push(Row::new(
                    case,
                    format!("ω = {:.3} rad/s, {name} branch (H = 3)", q.sol.omega),
                    "amplitude x",
                    Some(a),
                    td,
                    None,
                    "RK4 1024 steps/period from the H = 3 solution".into(),
                ));
            }
        }
    }
    rep.notes.push((
        case.into(),
        format!(
            "scan, continuation and RK4 {:.2} s",
            t0.elapsed().as_secs_f64()
        ),
    ));
    Ok(())
}
