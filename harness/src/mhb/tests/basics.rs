//! Harmonic transforms, the first harmonic against the first-order solve, the Jacobian.

use super::*;

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

#[test]
fn mindlin_jacobian_is_the_closed_loops_derivative() {
    // Mindlin points: the tangent-linear step over one period from the closed loop and
    // periodicity (aft module docs) against central differences of the whole AFT map
    // (each side marched from a virgin point to its closed loop; step 1e-6 A: truncation
    // ~1e-12, round-off and closure ~1e-11/1e-6 of the force scale; measured 6e-11…8e-8,
    // the largest for the thesis rule's slow drift at A/δ* = 0.05). Microslip to gross
    // sliding, both unloading rules, H = 1 and 7 with higher harmonics and a mean slip.
    // (Below A/δ* ≈ 0.01 the differences themselves lose their digits under the thesis
    // rule: the closure tolerance is amplified by the drift's 1/(1 − q) ≈ δ*/A.)
    for rule in [RuleName::Thesis, RuleName::Masing] {
        let law = point(LawName::Mindlin, rule, 1.0, 0.1, 2.0);
        let dstar = 1.5 * 0.1 / 2.0;
        for &r in &[0.05, 0.3, 0.9, 3.0] {
            let a = r * dstar;
            for &h in &[1usize, 7] {
                let m = 2 * h + 1;
                let mut tr = Transforms::new(default_samples(h), h);
                let mut dc = vec![0.0; m];
                dc[0] = 0.1 * a;
                dc[1] = a;
                dc[2] = 0.3 * a;
                if h > 1 {
                    dc[3] = 0.2 * a;
                    dc[6] = -0.1 * a;
                }
                let ev = aft::evaluate(&mut tr, &law, &dc).unwrap();
                let (mut worst, mut big) = (0.0f64, 0.0f64);
                for j in 0..m {
                    let eps = 1e-6 * a;
                    let (mut p, mut q) = (dc.clone(), dc.clone());
                    p[j] += eps;
                    q[j] -= eps;
                    let fp = aft::forces(&mut tr, &law, &p).unwrap().0;
                    let fq = aft::forces(&mut tr, &law, &q).unwrap().0;
                    for i in 0..m {
                        let fd = (fp[i] - fq[i]) / (2.0 * eps);
                        worst = worst.max((fd - ev.jac[i * m + j]).abs());
                        big = big.max(fd.abs());
                    }
                }
                assert!(
                    worst <= 1e-6 * big,
                    "{rule:?}, A/δ* {r}, H {h}: {:e}",
                    worst / big
                );
            }
        }
    }
}

/// The stuck stiffness adds k_T0 only where the point carries a tangential force: a
/// closed point with friction; an open point (F_N ≤ 0), a frictionless one and a cubic
/// spring add nothing, as the start of a sweep and the stuck frequencies both take it.
#[test]
fn stuck_stiffness_skips_open_and_frictionless_points() {
    let stuck = |mu: f64, normal: f64| {
        let law = point(LawName::Jenkins, RuleName::Thesis, mu, normal, 50.0);
        let sys = oscillator(1.0, 0.0, 20.0, Complex::new(1.0, 0.0), law);
        sys.stuck_stiffness()[(0, 0)]
    };
    assert_eq!(stuck(0.3, 10.0), 70.0);
    assert_eq!(stuck(0.3, 0.0), 20.0);
    assert_eq!(stuck(0.3, -1.0), 20.0);
    assert_eq!(stuck(0.0, 10.0), 20.0);
    assert_eq!(duffing().stuck_stiffness()[(0, 0)], 20.0);
}

/// The lumped first-order consistency map g(a) = |P x̂(a)|: its exact derivative
/// (`first_order::amplitude_derivative`) equals central differences of the map on the
/// Jenkins chain with Mindlin elements (smooth in A), both microslipping, near resonance.
#[test]
fn first_order_amplitude_derivative_is_the_maps_derivative() {
    let mut sys = jenkins_chain(0.05);
    for e in sys.elements.iter_mut() {
        e.law = point(LawName::Mindlin, RuleName::Masing, 1.0, 0.1, 2.0);
    }
    let omega = 0.5;
    let g = |a: &[f64]| {
        let x = first_order::solve_linear(&sys, omega, a).unwrap();
        first_order::element_amplitudes(&sys, &x)
    };
    let a = [0.03, 0.05];
    let jac = first_order::amplitude_derivative(&sys, omega, &a).unwrap();
    for p in 0..2 {
        let h = 1e-5 * a[p];
        let (mut ap, mut am) = (a, a);
        ap[p] += h;
        am[p] -= h;
        let (gp, gm) = (g(&ap), g(&am));
        for r in 0..2 {
            let fd = (gp[r] - gm[r]) / (2.0 * h);
            let scale = jac.column(p).amax().max(fd.abs());
            assert!(
                (jac[(r, p)] - fd).abs() <= 1e-6 * scale,
                "∂g{r}/∂a{p}: {} against {fd}",
                jac[(r, p)]
            );
        }
    }
}
