//! Softening friction and the thesis unloading rule's drift.

use super::*;

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
    let td = reference::steady(&sys, top.sol.omega, &x0, &v0, 4096, 1e-7, 3000).unwrap();
    let e = hb.amplitude(&top.sol.u, 0) / td.amplitude[0] - 1.0;
    assert!(e.abs() < 3e-3, "{e:e}");
    eprintln!(
        "softening: peak at ω = {:.4} (stick {w0:.4}), {} points, folds {:?}",
        top.sol.omega,
        br.points.len(),
        br.folds
    );
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
