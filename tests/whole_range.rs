//! The stateless C functions over the whole double range: the right number, or a named
//! error, never a plausible wrong value with JOINTLIN_OK. Each case is an input that
//! once returned a wrong answer (listed in docs/robustness.md, "Whole double range").
//!
//! Units: the block of Appendix C (N, mm, s): μ = 0.3, k_T0 = 1282.7 N/mm unless stated.

use jointlin::ffi::error::*;
use jointlin::ffi::linearize::*;
use jointlin::ffi::screw::jointlin_screw_preload;
use std::f64::consts::PI;

const MU: f64 = 0.3;
const KT0: f64 = 1282.7;
const OMEGA: f64 = 1.3;

fn contact(law: i32, rule: i32, mu: f64, f_n: f64, k_t0: f64) -> jointlin_contact {
    jointlin_contact {
        law,
        rule,
        mu,
        normal_force: f_n,
        k_t0,
    }
}

/// jointlin_linearize with a method (None = default); asserts no panic and finite outputs
/// on JOINTLIN_OK, an untouched output otherwise.
fn lin_with(
    c: &jointlin_contact,
    a: f64,
    method: Option<jointlin_method>,
) -> (i32, jointlin_linearization) {
    let sentinel = jointlin_linearization {
        regime: -1,
        ..Default::default()
    };
    let mut out = sentinel;
    let m = method.as_ref().map_or(std::ptr::null(), |m| m as *const _);
    let status = unsafe { jointlin_linearize(c, a, OMEGA, m, &mut out) };
    assert_ne!(status, JOINTLIN_ERR_PANIC);
    if status == JOINTLIN_OK {
        let l = out;
        let all = [
            l.k_star,
            l.d_star,
            l.eta,
            l.energy_per_cycle,
            l.peak_force,
            l.slip_limit,
            l.amplitude_ratio,
        ];
        assert!(all.iter().all(|v| v.is_finite() && *v >= 0.0), "{l:?}");
        assert!(l.k_star <= c.k_t0);
    } else {
        assert_eq!(out, sentinel, "written on error {status}");
    }
    (status, out)
}

fn lin(c: &jointlin_contact, a: f64) -> jointlin_linearization {
    let (status, l) = lin_with(c, a, None);
    assert_eq!(status, JOINTLIN_OK, "{c:?} A = {a:e}");
    l
}

/// |got − want| within `rel` of want, or within 2 ulps of the smallest subnormal.
fn close(got: f64, want: f64, rel: f64) -> bool {
    (got - want).abs() <= rel * want.abs() + 1e-323
}

const RULES: [i32; 2] = [JOINTLIN_RULE_THESIS, JOINTLIN_RULE_MASING];

#[test]
fn subnormal_and_underflowing_amplitude_ratios_are_the_small_amplitude_loop() {
    // Mindlin, F_N = 1e12, A = 1e-300 (A/δ* = 2.9e-309, subnormal) and F_N = 1e308,
    // A = 1e-8 (A/δ* = 2.9e-313): k* was 0 (Masing) or k_T0/2 (thesis rule), regime
    // STICK. The small-amplitude loop (model.md §5): k* = k_T0, F̂ = k_T0 A, and with
    // A_hys = μF_N δ* (A/δ*)³/2, d* = μF_N A/(2πωδ*²), η = (A/δ*)/(3π).
    for (f_n, a) in [(1e12, 1e-300), (1e308, 1e-8), (2.0, 1e-320), (2.0, 5e-324)] {
        for rule in RULES {
            let c = contact(JOINTLIN_LAW_MINDLIN, rule, MU, f_n, KT0);
            let l = lin(&c, a);
            let limit = MU * f_n;
            let delta = 1.5 * limit / KT0;
            assert_eq!(l.k_star, KT0, "F_N = {f_n:e}, A = {a:e}");
            assert_eq!(l.regime, JOINTLIN_REGIME_MICROSLIP);
            assert!(close(l.peak_force, KT0 * a, 1e-15), "{l:?}");
            assert!(close(l.slip_limit, delta, 1e-15));
            // μF_N A/(2πωδ*²) = k_T0² A/(4.5 π ω μF_N), each factor in range.
            let d_want = KT0 * KT0 * a / (4.5 * PI * OMEGA) / limit;
            assert!(
                close(l.d_star, d_want, 1e-13),
                "{:e} vs {d_want:e}",
                l.d_star
            );
            let eta_want = KT0 * a / (4.5 * PI) / limit;
            assert!(close(l.eta, eta_want, 1e-13), "{:e} vs {eta_want:e}", l.eta);
            assert!(close(l.amplitude_ratio, KT0 * a / 1.5 / limit, 1e-13));
        }
        // Jenkins: stick, no loop, k* = k_T0.
        let c = contact(JOINTLIN_LAW_JENKINS, RULES[0], MU, f_n, KT0);
        let l = lin(&c, a);
        assert_eq!(
            (l.k_star, l.d_star, l.regime),
            (KT0, 0.0, JOINTLIN_REGIME_STICK)
        );
    }
    // A = 0 exactly: stick.
    let l = lin(&contact(JOINTLIN_LAW_MINDLIN, 0, MU, 2.0, KT0), 0.0);
    assert_eq!(
        (l.k_star, l.d_star, l.regime),
        (KT0, 0.0, JOINTLIN_REGIME_STICK)
    );
}

#[test]
fn k_t0_up_to_the_largest_double_slides_like_every_other_decade() {
    // k_T0 = 1e308 or f64::MAX reported OPEN with zeros (δ* subnormal) where 1e307 slid.
    // Deep sliding (model.md §5): A_hys → 4μF_N A, d* → 4μF_N/(πωA), and the scaled loop
    // k*/k_T0 · (A/δ*)^{3/2} is the same in every decade (Masing: → 1 exactly, since
    // (2/π)∫₀² √(1 − u/2) √(2u) du = 1).
    let a = 1e-3;
    for rule in RULES {
        let mut scaled = Vec::new();
        for k in [1e3, 1e300, 1e307, 1e308, f64::MAX] {
            let c = contact(JOINTLIN_LAW_MINDLIN, rule, MU, 2.0, k);
            let l = lin(&c, a);
            assert_eq!(l.regime, JOINTLIN_REGIME_SLIDING, "k_T0 = {k:e}");
            let ratio = l.amplitude_ratio;
            let want = 4.0 * 0.6 * a;
            assert!(
                close(l.energy_per_cycle, want, 2.0 / ratio + 1e-15),
                "{l:?}"
            );
            assert!(close(
                l.d_star,
                want / (PI * OMEGA * a * a),
                2.0 / ratio + 1e-15
            ));
            assert!(close(l.peak_force, 0.6, 1e-15));
            assert!(l.k_star > 0.0, "k_T0 = {k:e}: {l:?}");
            scaled.push(l.k_star * ratio.sqrt() / k * ratio);
        }
        for s in &scaled[1..] {
            assert!(close(*s, scaled[1], 1e-13), "{scaled:?}");
        }
        if rule == JOINTLIN_RULE_MASING {
            assert!(close(scaled[1], 1.0, 1e-13), "{scaled:?}");
        }
    }
}

#[test]
fn a_friction_limit_of_1e_minus_165_dissipates_four_mu_fn_a() {
    // μF_N = 1e-165: the energy came out 0 (μF_N·δ* underflowed) while reporting sliding.
    for law in [JOINTLIN_LAW_MINDLIN, JOINTLIN_LAW_JENKINS] {
        for rule in RULES {
            let c = contact(law, rule, 1.0, 1e-165, KT0);
            let a = 1e-3;
            let l = lin(&c, a);
            assert_eq!(l.regime, JOINTLIN_REGIME_SLIDING);
            let want = 4.0 * 1e-165 * a;
            assert!(close(l.energy_per_cycle, want, 1e-14), "{l:?}");
            assert!(close(l.d_star, want / (PI * OMEGA * a * a), 1e-14), "{l:?}");
            assert!(l.eta > 0.0);
        }
    }
}

#[test]
fn huge_amplitude_ratios_keep_the_digits_of_k_star() {
    // Beyond A/δ* ≈ 1e5 the in-phase sum's pieces (each ∝ (A/δ*)^{-1/2}) cancelled to a
    // k* ∝ (A/δ*)^{-3/2} with a relative error ≈ 1e-16 A/δ*. Masing: k* (A/δ*)^{3/2}/k_T0
    // = 1 − O(δ*/A); Jenkins: 16/(3π) (model.md §5). The Simpson rule with 2^20 intervals
    // agrees where it can still resolve the tip (A/δ* = 10).
    let delta = 1.5 * MU * 2.0 / KT0;
    for r in [10.0, 1e6, 1e10, 1e100, 1e200] {
        let c = contact(JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_MASING, MU, 2.0, KT0);
        let l = lin(&c, r * delta);
        let s = l.k_star / KT0 * r.sqrt() * r;
        assert!(close(s, 1.0, 1.0 / r + 1e-14), "A/δ* = {r:e}: {s}");
        let c = contact(JOINTLIN_LAW_JENKINS, JOINTLIN_RULE_THESIS, MU, 2.0, KT0);
        let dj = MU * 2.0 / KT0;
        let l = lin(&c, r * dj);
        let s = l.k_star / KT0 * r.sqrt() * r;
        assert!(
            close(s, 16.0 / (3.0 * PI), 2.0 / r + 1e-14),
            "A/δ* = {r:e}: {s}"
        );
    }
    for rule in RULES {
        let c = contact(JOINTLIN_LAW_MINDLIN, rule, MU, 2.0, KT0);
        let fine = jointlin_method {
            kind: JOINTLIN_METHOD_SIMPSON,
            points: 1 << 20,
        };
        let (s, simpson) = lin_with(&c, 10.0 * delta, Some(fine));
        assert_eq!(s, JOINTLIN_OK);
        let l = lin(&c, 10.0 * delta);
        assert!(close(l.k_star, simpson.k_star, 1e-11), "{l:?} {simpson:?}");
    }
}

#[test]
fn plain_gauss_needs_two_points() {
    // One Gauss point samples only θ = 0, where sin θ = 0: k* = 0 for every loop, and the
    // call returned JOINTLIN_ERR_OVERFLOW (η = A_hys/(πk*A²)) although documented valid.
    let c = contact(JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS, MU, 2.0, KT0);
    let one = jointlin_method {
        kind: JOINTLIN_METHOD_GAUSS,
        points: 1,
    };
    assert_eq!(lin_with(&c, 3e-4, Some(one)).0, JOINTLIN_ERR_OUT_OF_RANGE);
    for points in [2, 3, 128] {
        let m = jointlin_method {
            kind: JOINTLIN_METHOD_GAUSS,
            points,
        };
        let (s, l) = lin_with(&c, 3e-4, Some(m));
        assert_eq!(s, JOINTLIN_OK, "{points} points");
        assert!(l.k_star > 0.0 && l.eta > 0.0);
    }
    // One point per panel of the graded rule is valid (closed-form pieces carry k*).
    let graded = jointlin_method {
        kind: JOINTLIN_METHOD_GRADED,
        points: 1,
    };
    let (s, l) = lin_with(&c, 3e-4, Some(graded));
    assert_eq!(s, JOINTLIN_OK);
    assert!(l.k_star > 0.0);
}

/// jointlin_screw_preload; asserts no panic, a finite F ≥ 0 on OK, nothing written otherwise.
fn preload(t: f64, p: f64, d2: f64, mu_g: f64, mu_k: f64, d_km: f64) -> (i32, f64) {
    let mut f = -1.0;
    let status = unsafe { jointlin_screw_preload(t, p, d2, mu_g, mu_k, d_km, &mut f) };
    assert_ne!(status, JOINTLIN_ERR_PANIC);
    if status == JOINTLIN_OK {
        assert!(f.is_finite() && f >= 0.0, "T={t:e} P={p:e}: {f}");
    } else {
        assert_eq!(f, -1.0, "written on error {status}");
    }
    (status, f)
}

#[test]
fn screw_preload_is_finite_or_a_named_overflow() {
    // T = 1, P = 5e-324, μ = 0, D_Km = 0 gave +Inf with JOINTLIN_OK: F = T/(0.16 P)
    // = 1.25e324 is beyond the largest double.
    assert_eq!(
        preload(1.0, 5e-324, 7.188, 0.0, 0.0, 0.0).0,
        JOINTLIN_ERR_OVERFLOW
    );
    // All-tiny inputs gave NaN (every lever term underflowed to 0): the exact quotient.
    let (s, f) = preload(5e-324, 5e-324, 5e-324, 5e-324, 5e-324, 5e-324);
    assert_eq!(s, JOINTLIN_OK);
    assert!(close(f, 1.0 / 0.16, 1e-15), "{f}");
    let (s, f) = preload(1e-300, 1e-300, 1e-300, 0.1, 0.1, 1e-300);
    assert_eq!(s, JOINTLIN_OK);
    assert!(close(f, 1.0 / (0.16 + 0.058 + 0.05), 1e-15), "{f}");
    // T = 1.7e308 on an M8 screw (P = 1.25, d2 = 7.188, D_Km = 11.6 mm): the lever is
    // 1.3963 mm with μ = 0.12, F = 1.22e308; frictionless (lever 0.2 mm) F overflows.
    let (s, f) = preload(1.7e308, 1.25, 7.188, 0.12, 0.12, 11.6);
    assert_eq!(s, JOINTLIN_OK);
    assert!(close(
        f,
        1.7e308 / (0.2 + 0.58 * 7.188 * 0.12 + 5.8 * 0.12),
        1e-15
    ));
    assert_eq!(
        preload(1.7e308, 1.25, 7.188, 0.0, 0.0, 11.6).0,
        JOINTLIN_ERR_OVERFLOW
    );
    // A lever term beyond the double range (d2 μ_G = 1e400) gave F = 0: now its quotient.
    let (s, f) = preload(1e300, 1.0, 1e300, 1e100, 0.0, 0.0);
    assert_eq!(s, JOINTLIN_OK);
    assert!(close(f, 1e-100 / 0.58, 1e-15), "{f}");
    // Zero torque: zero preload.
    assert_eq!(
        preload(0.0, 1.25, 7.188, 0.12, 0.12, 11.6),
        (JOINTLIN_OK, 0.0)
    );
}
