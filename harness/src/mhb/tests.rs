use nalgebra::{Complex, DMatrix};

use super::continuation::{trace, Options};
use super::*;
use crate::capi::Tangential;
use crate::names::{LawName, RuleName};
use crate::time::mhb_reference as reference;

fn point(law: LawName, rule: RuleName, mu: f64, normal: f64, k_t0: f64) -> Law {
    Law::Point(Tangential {
        law,
        rule,
        mu,
        normal,
        k_t0,
    })
}

/// One mass m on a ground spring k and dashpot d with one element to ground, load
/// f cos ωt (f̂ real) or −i f (f sin ωt).
fn oscillator(m: f64, d: f64, k: f64, f1: Complex<f64>, law: Law) -> System {
    System {
        m: DMatrix::from_element(1, 1, m),
        d: DMatrix::from_element(1, 1, d),
        k: DMatrix::from_element(1, 1, k),
        f0: vec![0.0],
        f1: vec![f1],
        elements: vec![Element { i: 0, j: None, law }],
    }
}

/// Duffing of thesis Appendix B: ẍ + ẋ + 20x + 40x³ = 30 sin(ωt).
fn duffing() -> System {
    oscillator(1.0, 1.0, 20.0, Complex::new(0.0, -30.0), Law::Cubic(40.0))
}

use crate::bench::mhb_chain::jenkins_chain;

/// Start vector at H harmonics from a complex first harmonic per DOF.
fn start(h: usize, x1: &[Complex<f64>]) -> Vec<f64> {
    let m = 2 * h + 1;
    let mut u = vec![0.0; x1.len() * m];
    for (d, x) in x1.iter().enumerate() {
        u[d * m + 1] = x.re;
        u[d * m + 2] = -x.im;
    }
    u
}

#[test]
fn transforms_round_trip() {
    // Synthesis then analysis is the identity for N >= 2H + 2 (discrete orthogonality).
    let h = 7;
    let mut tr = Transforms::new(default_samples(h), h);
    let c: Vec<f64> = (0..15)
        .map(|i| ((i * 37 % 11) as f64 - 5.0) * 0.1)
        .collect();
    let mut x = vec![0.0; tr.n];
    tr.synthesize(&c, &mut x);
    // Sample 3 against the series evaluated directly.
    let tau = 2.0 * std::f64::consts::PI * 3.0 / tr.n as f64;
    let direct = c[0]
        + (1..=h)
            .map(|k| c[2 * k - 1] * (k as f64 * tau).cos() + c[2 * k] * (k as f64 * tau).sin())
            .sum::<f64>();
    assert!((x[3] - direct).abs() < 1e-14, "{} {}", x[3], direct);
    let mut back = vec![0.0; 15];
    tr.analyse(&x, &mut back);
    for (a, b) in c.iter().zip(&back) {
        assert!((a - b).abs() < 1e-14);
    }
}

#[test]
fn h1_element_forces_are_the_linearization() {
    // For delta = A cos(tau), the first-harmonic force of the loop is (k* A) cos - (d* omega A)
    // sin: k* is the in-phase coefficient of the Ersatzfunktion (4.3), equal to the
    // loop's own for symmetric (Masing) loops, and d* omega A = A_hys/(pi A) (3.14) is the
    // quadrature coefficient (only the first harmonic of F does work on a sinusoid). The
    // library integrates exactly; AFT samples N = 64 points of a loop with kinks:
    // k* to 1e-12 and the energy to 1e-5 below the slip limit (smooth Mindlin branches),
    // 3e-3 above it (the Coulomb kinks, rectangle rule O(N^-2)).
    let law = point(LawName::Mindlin, RuleName::Masing, 0.3, 2.0, 1282.7);
    let Law::Point(t) = law else { unreachable!() };
    let dstar = 1.5 * 0.6 / 1282.7;
    let mut tr = Transforms::new(default_samples(1), 1);
    for &(r, tol_k, tol_d) in &[(0.3, 1e-12, 1e-5), (0.9, 1e-12, 1e-5), (10.0, 3e-3, 3e-3)] {
        let a = r * dstar;
        let l = crate::capi::linearize(&t, a, 1.0).unwrap();
        let ev = aft::evaluate(&mut tr, &law, &[0.0, a, 0.0]).unwrap();
        assert!((ev.force[1] / (l.k_star * a) - 1.0).abs() < tol_k, "{r}");
        assert!((ev.force[2] / (-l.d_star * a) - 1.0).abs() < tol_d, "{r}");
        // Energy per cycle from the marched loop = the library's closed form.
        assert!(
            (ev.period.dissipated / l.energy_per_cycle - 1.0).abs() < 1e-9,
            "{r}"
        );
    }
}

#[test]
fn h1_reproduces_the_first_order_solve() {
    // The block of Appendix C (Masing rule) on a ground spring, swept through the range
    // where it slips (A/δ* up to ~3 at ω = 20). Measured 2.1e-4 at most: the N = 64
    // sampling of the loop's kinks (above) and the zeroth harmonic, which the first-order
    // method has not; 5e-4 leaves room for neither more.
    let law = point(LawName::Mindlin, RuleName::Masing, 0.3, 2.0, 1282.7);
    let sys = oscillator(2.0, 0.5, 200.0, Complex::new(0.4, 0.0), law);
    for &w in &[5.0, 10.0, 20.0, 25.0, 30.0] {
        let x1 = first_order::solve(&sys, w, &[1e-4]).unwrap();
        let mut hb = Hb::new(&sys, 1, default_samples(1));
        let s = hb
            .solve(&start(1, &x1), w, NewtonOptions::default())
            .unwrap();
        let rel = hb.amplitude(&s.u, 0) / x1[0].norm() - 1.0;
        assert!(rel.abs() < 5e-4, "ω = {w}: {rel:e}");
    }
}

#[test]
fn jenkins_jacobian_is_exact() {
    // Jenkins is piecewise linear (k_T0 or sliding), so the incremental derivative rule
    // is the exact derivative of the marched loop: central differences (step 1e-7 A,
    // truncation zero on linear pieces, round-off ~1e-9) agree to 1e-7.
    let law = point(LawName::Jenkins, RuleName::Masing, 1.0, 0.1, 2.0);
    // (A/δ* = 2 exactly would put the stick-slip kink on a sample, where the map has no
    // derivative; 2.1 avoids that.)
    for &r in &[0.3, 0.9, 2.1, 10.0] {
        let a = r * 0.05;
        for &h in &[1usize, 7] {
            let m = 2 * h + 1;
            let mut tr = Transforms::new(default_samples(h), h);
            let mut dc = vec![0.0; m];
            dc[1] = a;
            if h > 1 {
                dc[3] = 0.2 * a;
                dc[4] = -0.1 * a;
            }
            let ev = aft::evaluate(&mut tr, &law, &dc).unwrap();
            let (mut worst, mut big) = (0.0f64, 0.0f64);
            for j in 0..m {
                let eps = 1e-7 * a;
                let (mut p, mut q) = (dc.clone(), dc.clone());
                p[j] += eps;
                q[j] -= eps;
                let fp = aft::evaluate(&mut tr, &law, &p).unwrap().force;
                let fq = aft::evaluate(&mut tr, &law, &q).unwrap().force;
                for i in 0..m {
                    let fd = (fp[i] - fq[i]) / (2.0 * eps);
                    worst = worst.max((fd - ev.jac[i * m + j]).abs());
                    big = big.max(fd.abs());
                }
            }
            assert!(worst <= 1e-7 * big, "A/δ* {r}, H {h}: {:e}", worst / big);
        }
    }
}

/// Closed-form folds of the first-order Duffing response: G(ρ, ω) = ρ[(20 + 30ρ − ω²)²
/// + ω²] − 900 = 0 (ρ = A², (3.8) with C* = ¾·40·A²) and ∂G/∂ρ = 0, by Newton from a guess.
fn duffing_fold(mut rho: f64, mut w: f64) -> f64 {
    for _ in 0..50 {
        let k = 20.0 + 30.0 * rho - w * w;
        let g = rho * (k * k + w * w) - 900.0;
        let gr = k * k + w * w + 60.0 * rho * k;
        let gw = rho * (-4.0 * w * k + 2.0 * w);
        let grr = 120.0 * k + 1800.0 * rho;
        let grw = -4.0 * w * k + 2.0 * w - 120.0 * rho * w;
        let det = gr * grw - gw * grr;
        let dr = (g * grw - gw * gr) / det;
        let dw = (gr * gr - grr * g) / det;
        rho -= dr;
        w -= dw;
    }
    w
}

#[test]
fn duffing_h1_folds_and_unstable_branch() {
    // Appendix B: three amplitudes for 8.7 < ω < 13.3 at first order. Continuation passes
    // both folds; the fold frequencies are the closed form's (parabolic vertex through
    // three points, error O(step³): 2e-3 relative allowed); between the folds the
    // det-sign test marks the branch unstable, and at ω = 10 it crosses three times.
    let sys = duffing();
    let mut hb = Hb::new(&sys, 1, default_samples(1));
    let x1 = first_order::solve(&sys, 4.0, &[0.5]).unwrap();
    let opt = Options {
        omega_start: 4.0,
        omega_end: 20.0,
        step: 0.02,
        step_min: 1e-6,
        step_max: 0.05,
        max_points: 5000,
        rtol: 1e-10,
    };
    let br = trace(&mut hb, &start(1, &x1), opt).unwrap();
    assert_eq!(br.folds.len(), 2, "{:?}", br.folds);
    let (hi, lo) = (br.folds[0], br.folds[1]);
    // ρ = A² of the branch point nearest each fold starts the closed-form Newton.
    let rho_near = |w: f64| {
        let p = br
            .points
            .iter()
            .min_by(|a, b| {
                (a.sol.omega - w)
                    .abs()
                    .partial_cmp(&(b.sol.omega - w).abs())
                    .unwrap()
            })
            .unwrap();
        hb.amplitude(&p.sol.u, 0).powi(2)
    };
    let hi_cf = duffing_fold(rho_near(hi), hi);
    let lo_cf = duffing_fold(rho_near(lo), lo);
    assert!((hi / hi_cf - 1.0).abs() < 2e-3, "{hi} vs {hi_cf}");
    assert!((lo / lo_cf - 1.0).abs() < 2e-3, "{lo} vs {lo_cf}");
    // The thesis's interval 8.7 < ω < 13.3 (read off its Fig. 4.3: the closed form gives
    // 8.699 and 13.22).
    assert!(
        (lo - 8.7).abs() < 0.05 && (hi - 13.3).abs() < 0.1,
        "{lo} {hi}"
    );
    let crossings = br
        .points
        .windows(2)
        .filter(|p| (p[0].sol.omega - 10.0) * (p[1].sol.omega - 10.0) <= 0.0)
        .count();
    assert_eq!(crossings, 3);
    for p in &br.points {
        let between = p.s > 0.0 && !p.stable;
        if between {
            assert!(p.sol.omega > lo - 0.05 && p.sol.omega < hi + 0.05);
        }
    }
    assert!(br.points.iter().any(|p| !p.stable));
}

/// Initial state (x, ẋ) at t = 0 from a solution.
fn initial(hb: &Hb, u: &[f64], omega: f64) -> (Vec<f64>, Vec<f64>) {
    let m = 2 * hb.h() + 1;
    let n = u.len() / m;
    let x = (0..n)
        .map(|d| u[d * m] + (1..=hb.h()).map(|h| u[d * m + 2 * h - 1]).sum::<f64>())
        .collect();
    let v = (0..n)
        .map(|d| {
            (1..=hb.h())
                .map(|h| h as f64 * omega * u[d * m + 2 * h])
                .sum::<f64>()
        })
        .collect();
    (x, v)
}

#[test]
fn jenkins_chain_against_time_domain() {
    // 3-DOF chain, two Jenkins elements that stick and slip within a cycle near the first
    // resonance (f = 0.05). Reference: RK4, 512 steps per period, periodic to 1e-7
    // (started from the H = 7 solution to shorten the transient). Measured: first order
    // +30 %, +53 %, +24 % at ω = 0.50, 0.54, 0.58; H = 7 within 1e-3 and H = 15 within
    // 3e-4 (H = 15 vs the reference is the reference's own step error). Asserted: first
    // order off by > 20 %, H = 7 within 0.5 %, H = 15 within 0.1 %.
    let sys = jenkins_chain(0.05);
    for &w in &[0.50, 0.54, 0.58] {
        let x1 = first_order::solve(&sys, w, &[0.1, 0.1]).unwrap();
        let mut amp = Vec::new();
        let mut u7 = Vec::new();
        for &h in &[7usize, 15] {
            let mut hb = Hb::new(&sys, h, default_samples(h));
            let s = hb
                .solve(&start(h, &x1), w, NewtonOptions::default())
                .unwrap();
            amp.push(hb.amplitude(&s.u, 2));
            if h == 7 {
                u7 = s.u;
            }
        }
        let hb = Hb::new(&sys, 7, 128);
        let (x0, v0) = initial(&hb, &u7, w);
        let td = reference::steady::<6>(&sys, w, &x0, &v0, 512, 1e-7, 3000).unwrap();
        let r = td.amplitude[2];
        let fo = x1[2].norm() / r - 1.0;
        assert!(fo > 0.2, "ω {w}: first order {fo:e}");
        assert!(
            (amp[0] / r - 1.0).abs() < 5e-3,
            "ω {w}: H=7 {}",
            amp[0] / r - 1.0
        );
        assert!(
            (amp[1] / r - 1.0).abs() < 1e-3,
            "ω {w}: H=15 {}",
            amp[1] / r - 1.0
        );
    }
}

#[test]
fn mindlin_block_against_time_domain() {
    // The block of Appendix C (Masing rule) on a ground spring through its microslip range
    // (ω = 18 ... 25: A/δ* ~ 1 ... 1.6). Reference: RK4, 4096 steps per period (k_T0/m
    // is stiff), periodic to 1e-7. Measured: first order 1.6e-2 at most (ω = 18), H = 7
    // 1.8e-4 at most. Asserted: H = 7 within 1e-3, and at least 5× closer than first order.
    let law = point(LawName::Mindlin, RuleName::Masing, 0.3, 2.0, 1282.7);
    let sys = oscillator(2.0, 0.5, 200.0, Complex::new(0.4, 0.0), law);
    for &w in &[18.0, 22.0, 25.0] {
        let x1 = first_order::solve(&sys, w, &[1e-4]).unwrap();
        let mut hb = Hb::new(&sys, 7, default_samples(7));
        let s = hb
            .solve(&start(7, &x1), w, NewtonOptions::default())
            .unwrap();
        let (x0, v0) = initial(&hb, &s.u, w);
        let td = reference::steady::<2>(&sys, w, &x0, &v0, 4096, 1e-7, 3000).unwrap();
        let r = td.amplitude[0];
        let e7 = (hb.amplitude(&s.u, 0) / r - 1.0).abs();
        let e1 = (x1[0].norm() / r - 1.0).abs();
        assert!(e7 < 1e-3, "ω {w}: {e7:e}");
        assert!(e1 > 5.0 * e7, "ω {w}: {e1:e} vs {e7:e}");
    }
}

#[test]
fn duffing_superharmonic_resonance() {
    // Appendix B's Duffing below its resonance, ω = 1.2 ... 1.92 (ω₀/3 ≈ 1.49 bent up
    // by the hardening): the time domain (RK4, 1024 steps per period, periodic to 1e-8)
    // shows a superharmonic peak of the peak displacement near ω = 1.6; H = 1 has no
    // third harmonic and rises monotonically. Measured: H = 7 within 2.4e-2 (largest at
    // ω = 1.2), H = 15 closer; H = 1 off by 10 % at the peak. Asserted: the reference
    // has an interior maximum, H = 1 has none and misses it by > 8 %, H = 15 within 1.5 %.
    let sys = duffing();
    let (mut td, mut h1, mut h15) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..10 {
        let w = 1.2 + 0.08 * i as f64;
        let x1 = first_order::solve(&sys, w, &[0.5]).unwrap();
        let mut hb1 = Hb::new(&sys, 1, default_samples(1));
        let s1 = hb1
            .solve(&start(1, &x1), w, NewtonOptions::default())
            .unwrap();
        h1.push(hb1.half_range(&s1.u, 0));
        let mut hb = Hb::new(&sys, 15, default_samples(15));
        let s = hb
            .solve(&start(15, &x1), w, NewtonOptions::default())
            .unwrap();
        h15.push(hb.half_range(&s.u, 0));
        let (x0, v0) = initial(&hb, &s.u, w);
        td.push(
            reference::steady::<2>(&sys, w, &x0, &v0, 1024, 1e-8, 3000)
                .unwrap()
                .half_range[0],
        );
    }
    let peak = (1..9)
        .find(|&i| td[i] > td[i - 1] && td[i] > td[i + 1])
        .expect("a superharmonic peak in the reference");
    assert!(h1.windows(2).all(|p| p[1] > p[0]), "{h1:?}");
    assert!(
        1.0 - h1[peak] / td[peak] > 0.08,
        "{} {}",
        h1[peak],
        td[peak]
    );
    for (a, b) in h15.iter().zip(&td) {
        assert!((a / b - 1.0).abs() < 1.5e-2, "{a} {b}");
    }
}

#[test]
fn softening_friction_bends_left() {
    // The block on a ground spring (k = 200, m = 2; stick resonance √((k + k_T0)/m) =
    // 27.2 rad/s), swept by continuation at H = 3 from 5 to 40 rad/s: the peak lies
    // well below the stick resonance (softening), the branch reaches the end, and the
    // amplitude at the peak is the time domain's (RK4, 4096 steps, 1e-7): measured
    // 1.4e-3 (the truncation at H = 3; H = 7 gives 2e-4 in the test above), asserted 3e-3.
    let law = point(LawName::Mindlin, RuleName::Masing, 0.3, 2.0, 1282.7);
    let sys = oscillator(2.0, 0.5, 200.0, Complex::new(0.4, 0.0), law);
    let mut hb = Hb::new(&sys, 3, default_samples(3));
    let x1 = first_order::solve(&sys, 5.0, &[1e-4]).unwrap();
    let opt = Options {
        omega_start: 5.0,
        omega_end: 40.0,
        step: 0.02,
        step_min: 1e-7,
        step_max: 0.1,
        max_points: 3000,
        rtol: 1e-9,
    };
    let br = trace(&mut hb, &start(3, &x1), opt).unwrap();
    assert!(br.points.last().unwrap().sol.omega >= 40.0);
    let top = br
        .points
        .iter()
        .max_by(|a, b| {
            hb.amplitude(&a.sol.u, 0)
                .partial_cmp(&hb.amplitude(&b.sol.u, 0))
                .unwrap()
        })
        .unwrap();
    let w0 = ((200.0f64 + 1282.7) / 2.0).sqrt();
    assert!(top.sol.omega < 0.85 * w0, "{} vs {w0}", top.sol.omega);
    let (x0, v0) = initial(&hb, &top.sol.u, top.sol.omega);
    let td = reference::steady::<2>(&sys, top.sol.omega, &x0, &v0, 4096, 1e-7, 3000).unwrap();
    let e = hb.amplitude(&top.sol.u, 0) / td.amplitude[0] - 1.0;
    assert!(e.abs() < 3e-3, "{e:e}");
    eprintln!(
        "softening: peak at ω = {:.4} (stick {w0:.4}), {} points, folds {:?}",
        top.sol.omega,
        br.points.len(),
        br.folds
    );
}

/// Sequential sweep at fixed ω steps, each Newton started from the previous solution
/// (what a plain sweep does), or, where that fails (past a fold), from the linear
/// response scaled by 1, 2, 4, −2, −4 (cold starts towards a larger branch, in or out of
/// phase with the linear one); the amplitudes of
/// DOF 0.
fn plain_sweep(hb: &mut Hb, omegas: &[f64], u0: Vec<f64>) -> Vec<f64> {
    let mut u = u0;
    omegas
        .iter()
        .map(|&w| {
            let s = hb
                .solve(&u, w, NewtonOptions::default())
                .or_else(|e| {
                    [1.0, 2.0, 4.0, -2.0, -4.0]
                        .iter()
                        .find_map(|&c| {
                            let u0: Vec<f64> = hb.linear_start(w).iter().map(|v| c * v).collect();
                            hb.solve(&u0, w, NewtonOptions::default()).ok()
                        })
                        .ok_or(e)
                })
                .unwrap();
            u = s.u;
            hb.amplitude(&u, 0)
        })
        .collect()
}

#[test]
fn duffing_sweeps_up_and_down_jump_at_the_folds() {
    // Thesis Fig. 4.3: sweeping up follows the upper branch to the fold at 13.22 and drops;
    // sweeping down follows the lower branch to the fold at 8.699 and jumps up (closed
    // form folds, test above). Steps of 0.01 rad/s: the jump lies within one step past
    // the fold.
    let sys = duffing();
    let mut hb = Hb::new(&sys, 1, default_samples(1));
    let up: Vec<f64> = (0..1600).map(|i| 4.0 + 0.01 * i as f64).collect();
    let x1 = first_order::solve(&sys, 4.0, &[0.5]).unwrap();
    let a_up = plain_sweep(&mut hb, &up, start(1, &x1));
    let jump = |a: &[f64]| {
        (1..a.len())
            .find(|&i| (a[i] / a[i - 1]).ln().abs() > 0.5)
            .expect("a jump")
    };
    let i = jump(&a_up);
    assert!(
        up[i] > 13.22 && up[i] <= 13.24,
        "up-sweep jump at {}",
        up[i]
    );
    let down: Vec<f64> = up.iter().rev().copied().collect();
    let x1 = first_order::solve(&sys, 20.0, &[0.1]).unwrap();
    let a_down = plain_sweep(&mut hb, &down, start(1, &x1));
    let j = jump(&a_down);
    assert!(
        down[j] < 8.70 && down[j] >= 8.68,
        "down-sweep jump at {}",
        down[j]
    );
    // Up-sweep drops, down-sweep jumps up (by more than e^0.5, the detection threshold).
    assert!(a_up[i] < a_up[i - 1] && a_down[j] > a_down[j - 1]);
}

#[test]
fn duffing_stability_marks_agree_with_the_time_domain() {
    // The three H = 3 solutions at ω = 10 (Appendix B: 0.395, 1.43, 1.77 at first order):
    // the det-sign test marks the middle one unstable. RK4 (1024 steps per period,
    // periodic to 1e-8) started on each solution perturbed by +1 % stays on the
    // stable ones (amplitude within 1e-3) and leaves the unstable one (ends > 5 % away).
    let sys = duffing();
    let mut hb = Hb::new(&sys, 3, default_samples(3));
    let mut found: Vec<Solution> = Vec::new();
    for c in [0.2, 0.5, 1.0, 2.0, 4.0, -2.0, -4.0] {
        let u0: Vec<f64> = hb.linear_start(10.0).iter().map(|v| c * v).collect();
        if let Ok(s) = hb.solve(&u0, 10.0, NewtonOptions::default()) {
            let a = hb.amplitude(&s.u, 0);
            if found
                .iter()
                .all(|f| (hb.amplitude(&f.u, 0) / a - 1.0).abs() > 1e-6)
            {
                found.push(s);
            }
        }
    }
    assert_eq!(found.len(), 3, "three coexisting solutions");
    found.sort_by(|a, b| {
        hb.amplitude(&a.u, 0)
            .partial_cmp(&hb.amplitude(&b.u, 0))
            .unwrap()
    });
    let signs: Vec<f64> = found.iter().map(|s| s.det_sign).collect();
    assert!(signs[0] == signs[2] && signs[1] != signs[0], "{signs:?}");
    for (k, s) in found.iter().enumerate() {
        let a = hb.amplitude(&s.u, 0);
        let (x0, v0) = initial(&hb, &s.u, 10.0);
        let x0: Vec<f64> = x0.iter().map(|x| 1.01 * x).collect();
        let td = reference::steady::<2>(&sys, 10.0, &x0, &v0, 1024, 1e-8, 5000).unwrap();
        let e = (td.amplitude[0] / a - 1.0).abs();
        if k == 1 {
            assert!(e > 0.05, "unstable branch kept: {e:e}");
        } else {
            assert!(e < 1e-3, "stable branch {k} left: {e:e}");
        }
    }
}

#[test]
fn thesis_rule_drift_is_extrapolated_to_the_closed_loop() {
    // The thesis rule under a prescribed periodic slip drifts to its closed loop by a
    // ratio q ≈ 1 − A/δ* per period (docs/mhb.md). Reference: 600 plain periods at
    // A/δ* = 0.05 (q ≈ 0.95: the drift is then below 1e-14 of the force scale).
    let law = point(LawName::Mindlin, RuleName::Thesis, 0.2, 1.0, 2e4);
    let Law::Point(t) = law else { unreachable!() };
    let dstar = 1.5 * 0.2 / 2e4;
    let n = 64;
    let tau = |k: usize| 2.0 * std::f64::consts::PI * k as f64 / n as f64;
    let a = 0.05 * dstar;
    let delta: Vec<f64> = (0..n)
        .map(|k| a * tau(k).cos() + 0.1 * a * (3.0 * tau(k)).sin())
        .collect();
    let mut state = [0.0; crate::capi::POINT_STATE_LEN];
    let mut next = state;
    let mut reference = vec![0.0; n];
    for _ in 0..600 {
        for k in 0..n {
            reference[k] = crate::capi::point_step(&t, &state, delta[k], &mut next)
                .unwrap()
                .force;
            state = next;
        }
    }
    let per = aft::march(&law, &delta).unwrap();
    let scale = reference.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let err = per
        .force
        .iter()
        .zip(&reference)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale;
    eprintln!(
        "thesis rule, A/δ* = 0.05: {} periods, closed loop vs 600 periods {err:.2e}",
        per.periods
    );
    // Without extrapolation the march needed ~330 periods here; with it a handful.
    assert!(per.periods <= 20, "{} periods", per.periods);
    // Closure tolerance 1e-11 of the scale, amplified by ≈ 1/(1 − q) = 20 at most.
    assert!(err < 1e-9, "{err:.3e}");
}

/// Number of amplitudes A ∈ `amps` with A·|K(A) − mω² + i(cω + ωd*(A))| = F at ω: the
/// sign changes of that residual over a dense amplitude grid (first-order harmonic
/// balance, (3.5–3.14)); `kd(A)` gives (K(A), ωd*(A)).
fn first_order_solutions(amps: &[f64], kd: &[(f64, f64)], c: f64, f: f64, w: f64) -> usize {
    let g: Vec<f64> = amps
        .iter()
        .zip(kd)
        .map(|(a, (k, wd))| a * (k - w * w).hypot(c * w + wd) - f)
        .collect();
    g.windows(2)
        .filter(|p| p[0].signum() != p[1].signum())
        .count()
}

#[test]
fn softening_friction_oscillators_have_no_first_order_folds() {
    // A softening friction case whose first-order FRF folds.
    // For a unit mass on a ground spring k = 1 in parallel with a Jenkins element
    // (k_T0 = β, δ* = 1; k*, d* from jointlin_linearize) with viscous damping c, a dense
    // scan of the first-order residual finds one amplitude at every frequency for every
    // combination below: forces from 0.1 μF_N to 2.5 μF_N (across the Den Hartog limit
    // 4μF_N/π, where the sliding response becomes resonant), β = 1 and 19 (a bilinear
    // hysteretic oscillator with post-yield stiffness 5 %), c = 1e-3 and 1e-2. The
    // stiffness falls with amplitude, but the dissipated energy grows faster, so the
    // curve leans left without turning over (docs/mhb.md). The same scan finds the
    // Duffing oscillator's three solutions between its folds (8.70 < ω < 13.2, Appendix
    // B), so it can see folds where they exist.
    // A from 1e-2 to 1e6 δ* (the resonant sliding response with c = 1e-3 reaches ~1e3).
    let amps: Vec<f64> = (0..4000)
        .map(|i| 1e-2 * 1e8f64.powf(i as f64 / 3999.0))
        .collect();
    let duffing: Vec<(f64, f64)> = amps.iter().map(|a| (20.0 + 30.0 * a * a, 0.0)).collect();
    let multi: Vec<f64> = (0..400)
        .map(|i| 5.0 + 10.0 * i as f64 / 399.0)
        .filter(|&w| first_order_solutions(&amps, &duffing, 1.0, 30.0, w) == 3)
        .collect();
    assert!(
        (multi[0] - 8.70).abs() < 0.05 && (multi[multi.len() - 1] - 13.2).abs() < 0.05,
        "{:?}",
        (multi.first(), multi.last())
    );
    for beta in [1.0, 19.0] {
        let t = Tangential {
            law: LawName::Jenkins,
            rule: RuleName::Masing,
            mu: 1.0,
            normal: beta, // μF_N = β, δ* = μF_N/k_T0 = 1
            k_t0: beta,
        };
        assert_eq!(
            crate::capi::linearize(&t, 0.0, 1.0).unwrap().slip_limit,
            1.0
        );
        let w0 = (1.0 + beta).sqrt();
        for c in [1e-3, 1e-2] {
            for f_rel in [0.1, 0.5, 1.0, 1.28, 1.35, 1.6, 2.5] {
                let f = f_rel * beta;
                let omegas: Vec<f64> = (0..600)
                    .map(|i| 0.5 + (1.1 * w0 - 0.5) * i as f64 / 599.0)
                    .collect();
                // d* ∝ 1/ω: ωd* is the same at every ω; one linearization per amplitude.
                let kd: Vec<(f64, f64)> = amps
                    .iter()
                    .map(|&a| {
                        let l = crate::capi::linearize(&t, a, 1.0).unwrap();
                        (1.0 + l.k_star, l.d_star)
                    })
                    .collect();
                for &w in &omegas {
                    let n = first_order_solutions(&amps, &kd, c, f, w);
                    assert!(
                        n <= 1,
                        "β {beta}, c {c}, F {f_rel} μF_N, ω {w}: {n} solutions"
                    );
                }
            }
        }
    }
}
