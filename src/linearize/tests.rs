//! Accuracy of every linearization option against converged references, the limits the
//! thesis names (model.md §5), hard inputs, and properties over wide random parameters.

use super::*;
use crate::hysteresis::PointState;
use proptest::prelude::*;

const REFERENCE: Method = Method::Graded { points: 64 };

fn contact(law: TangentialLaw, rule: Rule) -> Contact {
    Contact {
        law,
        rule,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    }
}

fn block_slip_limit() -> f64 {
    0.9 / 1282.7
}

/// A/δ* values: 200 log-spaced over [1e-12, 1e6] plus both sliding onsets (5/6 for the
/// thesis rule, 1 for Masing) approached from either side.
fn amplitude_ratios() -> Vec<f64> {
    let mut r: Vec<f64> = (0..=200)
        .map(|i| 10f64.powf(-12.0 + 18.0 * i as f64 / 200.0))
        .collect();
    for onset in [5.0 / 6.0, 1.0] {
        for eps in [-1e-9, -1e-6, 0.0, 1e-6, 1e-9] {
            r.push(onset * (1.0 + eps));
        }
    }
    r
}

/// Closed loop of half-width A driven through the library's own time-domain point with
/// `samples` steps per cycle: returns (∮F dδ, in-phase coefficient b₁ = (1/π)∮F sinθ dθ).
/// The loop is entered as the thesis's block enters it: first loading to the right tip.
fn time_domain_loop(c: &Contact, a: f64, samples: usize) -> (f64, f64) {
    let point = c.point().unwrap().unwrap();
    let b = point.backbone;
    let tip = match point.rule {
        Rule::Thesis => {
            let f = loop_shape::thesis_peak_force(&b, a);
            2.0 * a - f / b.k_t0()
        }
        Rule::Masing => a,
    };
    let centre = tip - a;
    let mut st = PointState::virgin(point.rule, 0.0);
    for i in 1..=200 {
        st = point.step(&st, tip * i as f64 / 200.0).unwrap().0;
    }
    let (mut area, mut b1) = (0.0, 0.0);
    let dt = 2.0 * std::f64::consts::PI / samples as f64;
    for i in 1..=samples {
        // θ runs from π/2 (right tip) once around; x = centre + A sin θ.
        let theta = std::f64::consts::FRAC_PI_2 + dt * i as f64;
        let (next, r) = point.step(&st, centre + a * theta.sin()).unwrap();
        area += 0.5 * (r.force + st.force()) * (next.slip() - st.slip());
        b1 += 0.5 * (r.force * theta.sin() + st.force() * (theta - dt).sin()) * dt
            / std::f64::consts::PI;
        st = next;
    }
    (area, b1)
}

#[test]
fn default_matches_the_converged_reference_over_eighteen_decades() {
    // Measured worst relative error of k* at 8 points per panel: 1.7e-11 (at A/δ* ≈ 7e5,
    // where the in-phase sum's pieces cancel to k*/k_T0 ≈ 1e-9); 5e-11 leaves margin.
    for rule in [Rule::Thesis, Rule::Masing] {
        let c = contact(TangentialLaw::Mindlin, rule);
        for r in amplitude_ratios() {
            let a = r * block_slip_limit();
            let reference = linearize(&c, a, 1.3, REFERENCE).unwrap();
            let got = linearize(&c, a, 1.3, Method::default()).unwrap();
            let err = ((got.k_star - reference.k_star) / reference.k_star).abs();
            assert!(err < 5e-11, "{rule:?} A/δ* = {r:e}: k* error {err:e}");
            assert_eq!(
                got.energy_per_cycle, reference.energy_per_cycle,
                "area is closed form"
            );
        }
    }
}

#[test]
fn reference_agrees_with_the_time_domain_loop_of_the_stateful_point() {
    // Independent check of k* (in-phase coefficient, (3.7)) and A_hys (∮F dδ) with the
    // hysteresis module: trapezoid sums over 2·10⁵ steps have O(h²) ≈ 1e-9 relative error.
    for law in [TangentialLaw::Mindlin, TangentialLaw::Jenkins] {
        for rule in [Rule::Thesis, Rule::Masing] {
            let c = contact(law, rule);
            for r in [0.05, 0.5, 0.8, 1.3, 5.0] {
                let a = r * block_slip_limit();
                let lin = linearize(&c, a, 1.0, REFERENCE).unwrap();
                let (area, b1) = time_domain_loop(&c, a, 200_000);
                let k_td = b1 / a;
                assert!(
                    (k_td - lin.k_star).abs() <= 1e-7 * lin.k_star,
                    "{law:?} {rule:?} {r}: k* {k_td} vs {}",
                    lin.k_star
                );
                let tol = 1e-7 * lin.energy_per_cycle + 1e-15;
                assert!(
                    (area - lin.energy_per_cycle).abs() <= tol,
                    "{law:?} {rule:?} {r}: A_hys {area} vs {}",
                    lin.energy_per_cycle
                );
            }
        }
    }
}

#[test]
fn jenkins_matches_the_classical_describing_function() {
    // Elasto-plastic describing function (e.g. Caughey 1960): with cos β = 1 − 2δ*/A,
    // k*/k = (β − sin 2β / 2)/π, A_hys = 4μF_N (A − δ*).
    let c = contact(TangentialLaw::Jenkins, Rule::Thesis);
    let d: f64 = 0.6 / 1282.7;
    for r in [1.0001f64, 1.5, 3.0, 100.0, 1e5] {
        let a = r * d;
        let beta = (1.0 - 2.0 * d / a).acos();
        let k = 1282.7 * (beta - (2.0 * beta).sin() / 2.0) / std::f64::consts::PI;
        let lin = linearize(&c, a, 1.0, Method::default()).unwrap();
        assert!(
            (lin.k_star - k).abs() <= 1e-9 * k,
            "A/δ* = {r}: {} vs {k}",
            lin.k_star
        );
        let e = 4.0 * 0.6 * (a - d);
        assert!((lin.energy_per_cycle - e).abs() <= 1e-12 * e);
    }
}

#[test]
fn simpson_and_plain_gauss_converge_to_the_reference_with_their_expected_orders() {
    // The thesis's Simpson rule sees the kinks of the loop (elastic/Mindlin switch, sliding
    // onset): its k* error falls only algebraically. Measure the order between 256 and
    // 4096 intervals in the sliding regime (A = 2δ*): expect ≈ h² (kink in f_L') or worse,
    // far from Simpson's h⁴ on smooth integrands.
    let c = contact(TangentialLaw::Mindlin, Rule::Thesis);
    let a = 2.0 * block_slip_limit();
    let reference = linearize(&c, a, 1.0, REFERENCE).unwrap().k_star;
    let err = |n| {
        (linearize(&c, a, 1.0, Method::Simpson { intervals: n })
            .unwrap()
            .k_star
            - reference)
            .abs()
            / reference
    };
    let (e1, e2) = (err(256), err(4096));
    let order = (e1 / e2).log2() / 4.0;
    eprintln!("Simpson k* errors: {e1:e} (256), {e2:e} (4096), order {order:.2}");
    assert!(order > 1.0 && order < 3.5, "Simpson order {order}");
    assert!(e2 < 1e-5);
    let default_err =
        (linearize(&c, a, 1.0, Method::default()).unwrap().k_star - reference).abs() / reference;
    assert!(
        default_err < 1e-12 && default_err < e2 * 1e-2,
        "default {default_err:e} vs Simpson(4096) {e2:e}"
    );
    // Plain Gauss in θ also stalls at the kinks.
    let gauss = |n| {
        (linearize(&c, a, 1.0, Method::Gauss { points: n })
            .unwrap()
            .k_star
            - reference)
            .abs()
            / reference
    };
    assert!(
        gauss(128) > 1e-9,
        "plain Gauss should not reach the default's accuracy"
    );
    // Simpson's loop area converges to the closed form.
    let area = linearize(&c, a, 1.0, REFERENCE).unwrap().energy_per_cycle;
    let simpson_area = linearize(&c, a, 1.0, Method::Simpson { intervals: 1 << 14 })
        .unwrap()
        .energy_per_cycle;
    assert!((simpson_area - area).abs() < 1e-6 * area);
}

#[test]
fn small_and_large_amplitude_limits() {
    for rule in [Rule::Thesis, Rule::Masing] {
        let c = contact(TangentialLaw::Mindlin, rule);
        let d = block_slip_limit();
        // A → 0: k* → k_T0 (first correction O(A/δ*)), d* → 0 like A.
        let tiny = linearize(&c, 1e-12 * d, 1.0, Method::default()).unwrap();
        assert!((tiny.k_star / 1282.7 - 1.0).abs() < 1e-11);
        assert!(tiny.d_star >= 0.0 && tiny.d_star < 1e-9 * 1282.7);
        assert_eq!(tiny.regime, Regime::Microslip);
        // A ≫ δ*: k* → 0, A_hys → 4μF_N A, d* → 4μF_N/(πωA); corrections O(δ*/A).
        let a = 1e6 * d;
        let big = linearize(&c, a, 2.0, Method::default()).unwrap();
        assert!(big.k_star < 1e-6 * 1282.7);
        let limit = 4.0 * 0.6 / (std::f64::consts::PI * 2.0 * a);
        assert!((big.d_star / limit - 1.0).abs() < 2e-6);
        assert_eq!(big.regime, Regime::Sliding);
    }
}

#[test]
fn results_are_continuous_across_the_sliding_onset() {
    for (rule, onset) in [(Rule::Thesis, 5.0 / 6.0), (Rule::Masing, 1.0)] {
        let c = contact(TangentialLaw::Mindlin, rule);
        let d = block_slip_limit();
        let below = linearize(&c, onset * (1.0 - 1e-10) * d, 1.0, Method::default()).unwrap();
        let above = linearize(&c, onset * (1.0 + 1e-10) * d, 1.0, Method::default()).unwrap();
        assert_eq!(
            (below.regime, above.regime),
            (Regime::Microslip, Regime::Sliding)
        );
        // Lipschitz in A: a relative change 2e-10 in A moves k* and A_hys by < 1e-8.
        assert!((below.k_star - above.k_star).abs() < 1e-8 * below.k_star);
        assert!(
            (below.energy_per_cycle - above.energy_per_cycle).abs() < 1e-8 * below.energy_per_cycle
        );
    }
}

#[test]
fn hard_inputs_give_finite_answers_or_named_errors() {
    let mut c = contact(TangentialLaw::Mindlin, Rule::Thesis);
    let d = block_slip_limit();
    // Open contact: zero stiffness, damping and energy.
    for f_n in [0.0, -5.0] {
        c.normal_force = f_n;
        let lin = linearize(&c, d, 1.0, Method::default()).unwrap();
        assert_eq!(
            (lin.k_star, lin.d_star, lin.energy_per_cycle, lin.regime),
            (0.0, 0.0, 0.0, Regime::Open)
        );
    }
    // F_N → 0+: deep sliding, everything finite and small.
    c.normal_force = 1e-300;
    let lin = linearize(&c, d, 1.0, Method::default()).unwrap();
    assert!(lin.k_star.is_finite() && lin.d_star.is_finite() && lin.d_star >= 0.0);
    c.normal_force = 2.0;
    // ω → 0: d* grows like 1/ω, η does not change.
    let slow = linearize(&c, d, 1e-9, Method::default()).unwrap();
    let fast = linearize(&c, d, 1.0, Method::default()).unwrap();
    assert!((slow.d_star * 1e-9 / fast.d_star - 1.0).abs() < 1e-14);
    assert_eq!(slow.eta, fast.eta);
    assert!(matches!(
        linearize(&c, 1e-200, 1e-200, Method::default()),
        Ok(_) | Err(Error::Overflow(_))
    ));
    // Round-off amplitudes of a welded joint (A² underflows): the stick limit, finite
    // (was 0/0 → a named overflow that stopped a sweep of scenes/hard/stiffness-ratio).
    for a in [1e-320, 1e-250, 1e-170, 1e-120] {
        let lin = linearize(&c, a, 1.0, Method::default()).unwrap();
        assert!(
            lin.d_star.is_finite() && lin.d_star >= 0.0 && lin.eta.is_finite(),
            "{a:e}: {lin:?}"
        );
        assert!((lin.k_star / c.k_t0 - 1.0).abs() < 1e-12, "{a:e}: {lin:?}");
    }
    // Named errors.
    assert!(matches!(
        linearize(&c, f64::NAN, 1.0, Method::default()),
        Err(Error::NonFinite(_))
    ));
    assert!(matches!(
        linearize(&c, d, 0.0, Method::default()),
        Err(Error::OutOfRange(_))
    ));
    assert!(matches!(
        linearize(&c, -d, 1.0, Method::default()),
        Err(Error::OutOfRange(_))
    ));
    assert!(matches!(
        linearize(&c, d, 1.0, Method::Simpson { intervals: 3 }),
        Err(Error::OutOfRange(_))
    ));
    // A/δ* or δ* beyond f64: a named overflow, never +inf in an output (fuzz findings).
    let tiny = Contact {
        k_t0: 1e300,
        ..contact(TangentialLaw::Mindlin, Rule::Thesis)
    };
    assert!(matches!(
        linearize(&tiny, 1e10, 1.0, Method::default()),
        Err(Error::Overflow(_))
    ));
    let huge = Contact {
        mu: 1.0,
        normal_force: 1.5e308,
        k_t0: 1.0,
        ..contact(TangentialLaw::Mindlin, Rule::Thesis)
    };
    assert!(matches!(
        linearize(&huge, 0.0, 1.0, Method::default()),
        Err(Error::Overflow(_))
    ));
    let ok = linearize(&tiny, 1e-150, 1.0, Method::default()).unwrap();
    assert!(ok.amplitude_ratio.is_finite() && ok.amplitude_ratio > 1.0);
    c.mu = f64::INFINITY;
    assert!(matches!(
        linearize(&c, d, 1.0, Method::default()),
        Err(Error::NonFinite(_))
    ));
    // k_T0 over fifteen decades at A = δ*/2 and 10δ*.
    for k in [1e-3, 1.0, 1e6, 1e12] {
        let c = Contact {
            k_t0: k,
            ..contact(TangentialLaw::Mindlin, Rule::Masing)
        };
        let d = 1.5 * 0.6 / k;
        for r in [0.5, 10.0] {
            let lin = linearize(&c, r * d, 1.0, Method::default()).unwrap();
            assert!(
                lin.k_star > 0.0
                    && lin.k_star <= k
                    && lin.d_star.is_finite()
                    && lin.eta.is_finite()
            );
            assert!((lin.amplitude_ratio - r).abs() < 1e-12 * r);
        }
    }
}

fn any_law() -> impl Strategy<Value = TangentialLaw> {
    prop_oneof![Just(TangentialLaw::Mindlin), Just(TangentialLaw::Jenkins)]
}

fn any_rule() -> impl Strategy<Value = Rule> {
    prop_oneof![Just(Rule::Thesis), Just(Rule::Masing)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn bounds_and_monotonicity(law in any_law(), rule in any_rule(), mu in 0.01f64..1.0,
                               log_fn in -6f64..6.0, log_k in -3f64..12.0, log_r in -12f64..6.0,
                               log_w in -6f64..6.0) {
        let c = Contact { law, rule, mu, normal_force: 10f64.powf(log_fn), k_t0: 10f64.powf(log_k) };
        let d = c.point().unwrap().unwrap().backbone.slip_limit();
        let a = 10f64.powf(log_r) * d;
        let lin = linearize(&c, a, 10f64.powf(log_w), Method::default()).unwrap();
        prop_assert!(lin.k_star >= 0.0 && lin.k_star <= c.k_t0);
        prop_assert!(lin.d_star >= 0.0 && lin.energy_per_cycle >= 0.0 && lin.eta >= 0.0);
        prop_assert!(lin.peak_force <= mu * c.normal_force * (1.0 + 1e-15));
        // Monotone in A: k* falls (1e-12 slack for quadrature error) and A_hys rises.
        let more = linearize(&c, a * 1.01, 1.0, Method::default()).unwrap();
        prop_assert!(more.k_star <= lin.k_star * (1.0 + 1e-12));
        prop_assert!(more.energy_per_cycle >= lin.energy_per_cycle);
    }

    #[test]
    fn time_domain_loop_area_equals_energy_per_cycle(law in any_law(), rule in any_rule(),
                                                     mu in 0.05f64..1.0, log_r in -2f64..1.5) {
        let c = Contact { law, rule, mu, normal_force: 3.0, k_t0: 500.0 };
        let d = c.point().unwrap().unwrap().backbone.slip_limit();
        let a = 10f64.powf(log_r) * d;
        let lin = linearize(&c, a, 1.0, Method::default()).unwrap();
        // 20000 trapezoid steps: O(h²) ≈ 1e-7 relative error of ∮F dδ.
        let (area, _) = time_domain_loop(&c, a, 20_000);
        prop_assert!((area - lin.energy_per_cycle).abs() <= 1e-6 * lin.energy_per_cycle + 1e-12 * mu * 3.0 * a);
    }
}
