//! The Duffing oscillator of Appendix B, ẍ + d ẋ + k x + α x³ = F sin ωt (d = 1, k = 20,
//! α = 40, F = 30), swept up and down in ω: first-order harmonic balance (closed form,
//! following a branch as a slow sweep does) against RK4 continued from frequency to
//! frequency. Hardening: for 8.7 < ω < 13.3 three harmonic-balance amplitudes exist; the
//! upward sweep stays on the large one until it ends, the downward one on the small one.

use super::{Report, Row};
use crate::time::periodic::{Cycle, SteadyTest};
use crate::time::rk4::rk4_step;
use crate::time::C64;

/// ẍ + d ẋ + k x + α x³ = F sin ωt.
#[derive(Debug, Clone, Copy)]
pub struct Duffing {
    pub d: f64,
    pub k: f64,
    pub alpha: f64,
    pub force: f64,
}

impl Duffing {
    /// Appendix B: d = 1, k = 20, α = 40, F = 30.
    pub fn appendix_b() -> Self {
        Duffing {
            d: 1.0,
            k: 20.0,
            alpha: 40.0,
            force: 30.0,
        }
    }

    /// First-order harmonic balance amplitudes, ascending: (3.8) on αx³ gives the
    /// equivalent stiffness 3αA²/4, so [(k − ω² + 3αA²/4)² + (dω)²] A² = F², a cubic in
    /// u = A².
    pub fn hbm_amplitudes(&self, omega: f64) -> Vec<f64> {
        let b = 0.75 * self.alpha;
        let det = self.k - omega * omega;
        let c = [
            -self.force * self.force,
            det * det + (self.d * omega).powi(2),
            2.0 * det * b,
            b * b,
        ];
        let mut a: Vec<f64> = cubic_roots(c)
            .into_iter()
            .filter(|&u| u > 0.0)
            .map(f64::sqrt)
            .collect();
        a.sort_by(f64::total_cmp);
        a
    }
}

/// Real roots of c₃u³ + c₂u² + c₁u + c₀ (trigonometric form for three real roots,
/// Cardano for one), each polished by two Newton steps.
pub fn cubic_roots(c: [f64; 4]) -> Vec<f64> {
    let (a2, a1, a0) = (c[2] / c[3], c[1] / c[3], c[0] / c[3]);
    let p = a1 - a2 * a2 / 3.0;
    let q = 2.0 * a2.powi(3) / 27.0 - a2 * a1 / 3.0 + a0;
    let disc = (q / 2.0).powi(2) + (p / 3.0).powi(3);
    let ys: Vec<f64> = if disc < 0.0 {
        let r = 2.0 * (-p / 3.0).sqrt();
        let phi = (3.0 * q / (p * r)).clamp(-1.0, 1.0).acos() / 3.0;
        (0..3)
            .map(|k| r * (phi - 2.0 * std::f64::consts::PI * k as f64 / 3.0).cos())
            .collect()
    } else {
        let s = disc.sqrt();
        vec![(-q / 2.0 + s).cbrt() + (-q / 2.0 - s).cbrt()]
    };
    ys.into_iter()
        .map(|y| {
            let mut u = y - a2 / 3.0;
            for _ in 0..2 {
                let f = ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
                let df = (3.0 * c[3] * u + 2.0 * c[2]) * u + c[1];
                if df != 0.0 {
                    u -= f / df;
                }
            }
            u
        })
        .collect()
}

/// A periodic state reached by RK4 at ω from (x, ẋ): (first harmonic, (max − min)/2, max,
/// cycles, end state).
pub struct Periodic {
    pub harmonic: C64,
    pub half_range: f64,
    pub max: f64,
    pub cycles: usize,
    pub steady: bool,
    pub state: [f64; 2],
}

/// RK4 with `n` steps per period from `x0` until the estimated distance to the periodic
/// state is below `tol` (or `max_cycles`).
pub fn rk4_periodic(
    sys: &Duffing,
    omega: f64,
    x0: [f64; 2],
    n: usize,
    tol: f64,
    max_cycles: usize,
) -> Periodic {
    let f = |t: f64, s: &[f64; 2]| {
        [
            s[1],
            sys.force * (omega * t).sin() - sys.d * s[1] - sys.k * s[0] - sys.alpha * s[0].powi(3),
        ]
    };
    let h = 2.0 * std::f64::consts::PI / omega / n as f64;
    let mut s = x0;
    let mut t = 0.0;
    let mut test = SteadyTest::default();
    let mut prev: Option<crate::time::periodic::CycleStats> = None;
    let mut cycles = 0;
    let mut steady = false;
    while cycles < max_cycles {
        let mut c = Cycle::new(omega, n, 1, vec![]);
        for k in 0..n {
            s = rk4_step(&f, t, &s, h);
            t = (cycles * n + k + 1) as f64 * h;
            c.push(t, &[s[0]]);
        }
        cycles += 1;
        let st = c.finish(&[]);
        let d = prev.as_ref().map_or(f64::INFINITY, |p| {
            test.push(crate::time::periodic::change(p, &st))
        });
        prev = Some(st);
        if cycles >= 3 && d <= tol {
            steady = true;
            break;
        }
    }
    let o = prev.expect("at least one cycle").outputs[0];
    Periodic {
        harmonic: o.harmonic,
        half_range: o.half_range(),
        max: o.max,
        cycles,
        steady,
        state: s,
    }
}

/// The sweep: ω = 2 … 20 rad/s in steps of 0.5 up, then down.
pub fn sweep(rep: &mut Report, log: &dyn Fn(&str)) -> Result<(), String> {
    let sys = Duffing::appendix_b();
    let case = "duffing";
    let up: Vec<f64> = (0..=36).map(|i| 2.0 + 0.5 * i as f64).collect();
    let down: Vec<f64> = up.iter().rev().copied().collect();
    let t0 = std::time::Instant::now();
    for (dir, omegas) in [("up", up), ("down", down)] {
        log(&format!("{case}: sweep {dir}"));
        let mut state = [0.0, 0.0];
        let mut branch: Option<f64> = None;
        let mut prev: Option<(f64, f64, f64)> = None; // (ω, HBM, TD)
        for &w in &omegas {
            let roots = sys.hbm_amplitudes(w);
            // Follow the branch: of the outer roots, the one nearer the previous amplitude.
            let hbm = match branch {
                None => roots[0],
                Some(b) => {
                    let lo = roots[0];
                    let hi = *roots
                        .last()
                        .expect("a cubic with F ≠ 0 has a positive root");
                    if (hi - b).abs() < (lo - b).abs() {
                        hi
                    } else {
                        lo
                    }
                }
            };
            branch = Some(hbm);
            let p = rk4_periodic(&sys, w, state, 200, 1e-7, 2000);
            state = p.state;
            let td = p.harmonic.norm();
            let mut note = format!("{} HBM roots", roots.len());
            if !p.steady {
                note.push_str(", TD not periodic within 2000 cycles");
            }
            if let Some((w0, h0, t0)) = prev {
                if (hbm / h0).ln().abs() > 0.3 {
                    rep.notes.push((
                        case.into(),
                        format!("sweep {dir}: harmonic balance jumps between ω = {w0} and {w} rad/s ({h0:.3} → {hbm:.3})"),
                    ));
                }
                if (td / t0).ln().abs() > 0.3 {
                    rep.notes.push((
                        case.into(),
                        format!("sweep {dir}: RK4 jumps between ω = {w0} and {w} rad/s ({t0:.3} → {td:.3})"),
                    ));
                }
            }
            prev = Some((w, hbm, td));
            rep.rows.push(Row::new(
                case,
                format!("ω = {w:.1} rad/s, sweep {dir}"),
                "amplitude x",
                Some(hbm),
                td,
                Some(p.half_range),
                note,
            ));
        }
    }
    let three: Vec<f64> = (0..=1800)
        .map(|i| 2.0 + 0.01 * i as f64)
        .filter(|&w| sys.hbm_amplitudes(w).len() == 3)
        .collect();
    if let (Some(a), Some(b)) = (three.first(), three.last()) {
        rep.notes.push((
            case.into(),
            format!("three harmonic-balance amplitudes for {a:.2} ≤ ω ≤ {b:.2} rad/s (thesis: 8.7 < ω < 13.3)"),
        ));
    }
    rep.notes.push((
        case.into(),
        format!(
            "RK4: 200 steps per period, each frequency continued from the previous end state until the estimated distance to the periodic state is below 1e-7; both sweeps {:.2} s",
            t0.elapsed().as_secs_f64()
        ),
    ));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn harmonic_balance_roots_satisfy_the_balance_and_rk4_settles_near_them() {
        let sys = Duffing::appendix_b();
        let roots = sys.hbm_amplitudes(10.0);
        assert_eq!(roots.len(), 3);
        for &a in &roots {
            let kk = sys.k - 100.0 + 0.75 * sys.alpha * a * a;
            let lhs = ((kk * kk + 100.0) * a * a).sqrt();
            assert!((lhs / sys.force - 1.0).abs() < 1e-12, "{a}");
        }
        // Appendix B from x(0) = 0.2: the steady maximum 0.3956 (model.md §8, independent
        // integration), the lower root 0.3948 (thesis 0.395).
        let p = rk4_periodic(&sys, 10.0, [0.2, 0.0], 400, 1e-9, 400);
        assert!(p.steady);
        assert!((p.max - 0.3956).abs() < 5e-4, "{}", p.max);
        assert!((roots[0] - 0.3948).abs() < 1e-4);
    }
}
