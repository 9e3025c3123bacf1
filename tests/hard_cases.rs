//! Stability suite at library level: hard inputs through the C API (and the core
//! where the C API has no entry), each asserting a finite answer or a named diagnostic —
//! never NaN/∞ on JOINTLIN_OK, never JOINTLIN_ERR_PANIC, never a hang (every loop is
//! bounded; cases that iterate run under a wall-clock [`deadline`]).
//!
//! Units: the block of Appendix C (N, mm, s, t): μ = 0.3, F_N = 2 N, k_T0 = 1282.7 N/mm,
//! so μF_N = 0.6 N and δ* = 1.5 μF_N/k_T0 = 7.016e-4 mm (model.md §3, §8).

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::error::*;
use jointlin::ffi::linearize::*;
use jointlin::ffi::point::*;
use jointlin::ffi::store::*;
use jointlin::hysteresis::Rule;
use jointlin::iterate::{solve_point, IterateError, Options, PointProblem, Scheme};
use jointlin::law::TangentialLaw;
use jointlin::linearize::{Contact, Method};
use std::f64::consts::PI;
use std::sync::mpsc;
use std::time::Duration;

const MU: f64 = 0.3;
const FN: f64 = 2.0;
const KT0: f64 = 1282.7;
const MASS: f64 = 0.002;

/// Mindlin's slip limit δ* = 1.5 μF_N/k_T0 (2.46).
fn slip_limit(mu: f64, f_n: f64, k_t0: f64) -> f64 {
    1.5 * mu * f_n / k_t0
}

/// The slip limit of a law: Mindlin (2.46), or μF_N/k_T0 for the Jenkins element.
fn law_slip_limit(law: i32, mu: f64, f_n: f64, k_t0: f64) -> f64 {
    if law == JOINTLIN_LAW_JENKINS {
        mu * f_n / k_t0
    } else {
        slip_limit(mu, f_n, k_t0)
    }
}

/// Runs `f` on its own thread and fails the test if it takes longer than `secs` (a hang
/// is a failure, not a stuck CI job).
fn deadline<T: Send + 'static>(secs: u64, what: &str, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    match rx.recv_timeout(Duration::from_secs(secs)) {
        Ok(v) => v,
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("{what}: no answer within {secs} s"),
        Err(mpsc::RecvTimeoutError::Disconnected) => panic!("{what}: panicked"),
    }
}

fn contact(law: i32, rule: i32, mu: f64, f_n: f64, k_t0: f64) -> jointlin_contact {
    jointlin_contact {
        law,
        rule,
        mu,
        normal_force: f_n,
        k_t0,
    }
}

const SENTINEL: jointlin_linearization = jointlin_linearization {
    k_star: -1.0,
    d_star: -1.0,
    eta: -1.0,
    energy_per_cycle: -1.0,
    peak_force: -1.0,
    slip_limit: -1.0,
    amplitude_ratio: -1.0,
    regime: -1,
};

/// jointlin_linearize; on JOINTLIN_OK checks every documented bound, on an error that the
/// output was not written. Returns the status and the output.
fn lin(c: &jointlin_contact, a: f64, omega: f64) -> (i32, jointlin_linearization) {
    let mut out = SENTINEL;
    let status = unsafe { jointlin_linearize(c, a, omega, std::ptr::null(), &mut out) };
    assert_ne!(status, JOINTLIN_ERR_PANIC, "{c:?} A={a:e} ω={omega:e}");
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
        assert!(all.iter().all(|v| v.is_finite()), "{c:?} A={a:e}: {l:?}");
        assert!(
            l.k_star >= 0.0 && l.k_star <= c.k_t0,
            "{c:?} A={a:e}: {l:?}"
        );
        assert!(l.d_star >= 0.0 && l.eta >= 0.0 && l.energy_per_cycle >= 0.0);
        assert!(l.peak_force <= c.mu * c.normal_force.max(0.0) * (1.0 + 1e-12));
        assert!((JOINTLIN_REGIME_OPEN..=JOINTLIN_REGIME_SLIDING).contains(&l.regime));
    } else {
        assert_eq!(out, SENTINEL, "written on error {status}");
    }
    (status, out)
}

const LAWS: [i32; 2] = [JOINTLIN_LAW_MINDLIN, JOINTLIN_LAW_JENKINS];
const RULES: [i32; 2] = [JOINTLIN_RULE_THESIS, JOINTLIN_RULE_MASING];

#[test]
fn normal_force_to_zero_and_below_is_open_or_finite() {
    for law in LAWS {
        for rule in RULES {
            // F_N ≤ 0 (and -0.0): open, everything exactly 0, status OK.
            for f_n in [0.0, -0.0, -1e-300, -2.0, -1e300] {
                let (s, l) = lin(&contact(law, rule, MU, f_n, KT0), 1e-3, 1.3);
                assert_eq!(s, JOINTLIN_OK);
                assert_eq!(l.regime, JOINTLIN_REGIME_OPEN);
                assert_eq!((l.k_star, l.d_star, l.energy_per_cycle), (0.0, 0.0, 0.0));
            }
            // F_N → 0+ down to the smallest subnormal: a fixed amplitude is ever deeper in
            // sliding; A_hys → 4μF_N A (model.md §5), up to a relative O(δ*/A) from the
            // elastic and microslip parts of the loop, in every decade (the loop is scaled
            // back from the point's own units without underflow on the way).
            let mut last_energy = f64::INFINITY;
            for f_n in [
                1e-1, 1e-10, 1e-50, 1e-100, 1e-152, 1e-165, 1e-200, 1e-300, 1e-305, 1e-310, 1e-323,
                5e-324,
            ] {
                let c = contact(law, rule, MU, f_n, KT0);
                let (s, l) = lin(&c, 1e-3, 1.3);
                if 1e-3 / law_slip_limit(law, MU, f_n, KT0) > f64::MAX {
                    // A/δ* (an output) beyond the largest double: named.
                    assert_eq!(s, JOINTLIN_ERR_OVERFLOW, "F_N = {f_n:e}");
                    continue;
                }
                assert_eq!(s, JOINTLIN_OK, "F_N = {f_n:e}");
                assert!(l.energy_per_cycle <= last_energy, "F_N = {f_n:e}");
                last_energy = l.energy_per_cycle;
                assert_eq!(l.regime, JOINTLIN_REGIME_SLIDING, "F_N = {f_n:e}");
                let want = 4.0 * MU * f_n * 1e-3;
                if want >= f64::MIN_POSITIVE {
                    assert!(
                        (l.energy_per_cycle / want - 1.0).abs() < 2.0 / l.amplitude_ratio + 1e-14,
                        "F_N = {f_n:e}: {} vs {want:e}",
                        l.energy_per_cycle
                    );
                    // d* → 4μF_N/(πωA) as well (3.14).
                    let d_want = want / (PI * 1.3 * 1e-6);
                    assert!((l.d_star / d_want - 1.0).abs() < 2.0 / l.amplitude_ratio + 1e-14);
                } else {
                    // 4μF_N A itself is subnormal: its nearest double, within an ulp.
                    assert!((l.energy_per_cycle - want).abs() <= 1e-323, "F_N = {f_n:e}");
                }
            }
        }
    }
}

#[test]
fn amplitudes_from_1e_minus_12_to_1e6_slip_limits() {
    for law in LAWS {
        let d = law_slip_limit(law, MU, FN, KT0);
        for rule in RULES {
            let c = contact(law, rule, MU, FN, KT0);
            let mut prev: Option<jointlin_linearization> = None;
            for e in -48..=24 {
                // 1e-12 … 1e6 δ* in quarter decades
                let ratio = 10f64.powf(f64::from(e) / 4.0);
                let (s, l) = lin(&c, ratio * d, 1.3);
                assert_eq!(s, JOINTLIN_OK, "A/δ* = {ratio:e}");
                assert!((l.amplitude_ratio / ratio - 1.0).abs() < 1e-12);
                if let Some(p) = prev {
                    // k* never increases with the amplitude; A_hys never decreases.
                    assert!(l.k_star <= p.k_star * (1.0 + 1e-12), "A/δ* = {ratio:e}");
                    assert!(l.energy_per_cycle >= p.energy_per_cycle, "A/δ* = {ratio:e}");
                }
                prev = Some(l);
            }
            // Limits (model.md §5): A → 0: k* → k_T0 (Mindlin softens like A/δ*; Jenkins
            // sticks exactly); A ≫ δ*: A_hys → 4μF_N A, k* → 0.
            let (_, small) = lin(&c, 1e-12 * d, 1.3);
            assert!((small.k_star / KT0 - 1.0).abs() < 1e-11, "{small:?}");
            let (_, big) = lin(&c, 1e6 * d, 1.3);
            assert_eq!(big.regime, JOINTLIN_REGIME_SLIDING);
            let hys = 4.0 * MU * FN * 1e6 * d;
            assert!((big.energy_per_cycle / hys - 1.0).abs() < 1e-5, "{big:?}");
            assert!(big.k_star / KT0 < 1e-5, "{big:?}");
        }
    }
}

#[test]
fn exactly_at_the_stick_slip_limit_results_are_continuous() {
    for law in LAWS {
        let d = law_slip_limit(law, MU, FN, KT0);
        for rule in RULES {
            let c = contact(law, rule, MU, FN, KT0);
            let below = lin(&c, d * (1.0 - f64::EPSILON), 1.3).1;
            let at = lin(&c, d, 1.3).1;
            let above = lin(&c, d * (1.0 + f64::EPSILON), 1.3).1;
            for l in [below, above] {
                // k* and A_hys are continuous across the onset of sliding: a relative
                // change of an ulp in A moves them by a few ulps at most (1e-12 is slack).
                assert!(
                    (l.k_star / at.k_star - 1.0).abs() < 1e-12,
                    "{law} {rule}: {l:?} vs {at:?}"
                );
                // A_hys is 0 up to δ* for the Jenkins element: compare on the scale μF_N δ*.
                let scale = MU * FN * d;
                assert!(
                    (l.energy_per_cycle - at.energy_per_cycle).abs() <= 1e-12 * scale,
                    "{law} {rule}: {l:?} vs {at:?}"
                );
            }
            assert!(below.regime != JOINTLIN_REGIME_OPEN && above.regime != JOINTLIN_REGIME_OPEN);
            // The time-domain point driven exactly to ±δ*: force ±μF_N (to rounding),
            // finite tangent, nothing dissipated on virgin loading of a Jenkins element.
            let mut state = [0.0; JOINTLIN_POINT_STATE_LEN];
            for s in [
                d,
                -d,
                d,
                0.0,
                -d * (1.0 + f64::EPSILON),
                d * (1.0 - f64::EPSILON),
            ] {
                let mut next = [0.0; JOINTLIN_POINT_STATE_LEN];
                let mut out = jointlin_step {
                    force: 0.0,
                    tangent: 0.0,
                    dissipated: 0.0,
                };
                let st = unsafe {
                    jointlin_point_step(&c, state.as_ptr(), s, next.as_mut_ptr(), &mut out)
                };
                assert_eq!(st, JOINTLIN_OK);
                assert!(out.force.is_finite() && out.tangent.is_finite() && out.dissipated >= 0.0);
                assert!(out.force.abs() <= MU * FN * (1.0 + 1e-12), "{out:?}");
                assert!(next.iter().all(|v| v.is_finite()));
                state = next;
            }
        }
    }
}

#[test]
fn omega_to_zero_gives_d_star_like_one_over_omega_or_a_named_overflow() {
    let d = slip_limit(MU, FN, KT0);
    let c = contact(JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS, MU, FN, KT0);
    let (_, base) = lin(&c, 2.0 * d, 1.0);
    for omega in [
        1e-3, 1e-6, 1e-12, 1e-50, 1e-100, 1e-200, 1e-290, 1e-300, 1e-310, 5e-324,
    ] {
        let (s, l) = lin(&c, 2.0 * d, omega);
        match s {
            JOINTLIN_OK => {
                // d* ω = A_hys/(π A²) is independent of ω; η, k* do not depend on ω.
                assert!(
                    (l.d_star * omega / base.d_star - 1.0).abs() < 1e-12,
                    "ω = {omega:e}"
                );
                assert_eq!((l.k_star, l.eta), (base.k_star, base.eta));
            }
            // d* = A_hys/(π ω A²) beyond f64 (ω ≤ ~1e-308 here).
            JOINTLIN_ERR_OVERFLOW => assert!(omega < 1e-300, "ω = {omega:e}"),
            // A subnormal ω is still > 0 and finite: only overflow may reject it.
            other => panic!("ω = {omega:e}: status {other}"),
        }
    }
    // ω = 0 and ω < 0 are out of range (the API says ω > 0).
    assert_eq!(lin(&c, d, 0.0).0, JOINTLIN_ERR_OUT_OF_RANGE);
    assert_eq!(lin(&c, d, -1.0).0, JOINTLIN_ERR_OUT_OF_RANGE);
}

#[test]
fn k_t0_over_fifteen_decades() {
    for law in LAWS {
        for rule in RULES {
            for e in -3..=12 {
                let k = 10f64.powi(e);
                let c = contact(law, rule, MU, FN, k);
                let d = law_slip_limit(law, MU, FN, k);
                for r in [1e-6, 0.5, 1.0, 10.0, 1e4] {
                    let (s, l) = lin(&c, r * d, 1.3);
                    assert_eq!(s, JOINTLIN_OK, "k_T0 {k:e} A/δ* {r}");
                    assert!((l.amplitude_ratio / r - 1.0).abs() < 1e-12);
                    // The loop scales exactly: k*/k_T0 and A_hys/(μF_N δ*) depend only on
                    // A/δ*, so every decade of k_T0 gives the same normalized numbers.
                    let base = lin(
                        &contact(law, rule, MU, FN, 1.0),
                        r * law_slip_limit(law, MU, FN, 1.0),
                        1.3,
                    )
                    .1;
                    assert!(
                        (l.k_star / k - base.k_star).abs() <= 1e-12 * base.k_star,
                        "k_T0 {k:e} A/δ* {r}"
                    );
                    let norm =
                        |l: &jointlin_linearization, dd: f64| l.energy_per_cycle / (MU * FN * dd);
                    let (a, b) = (norm(&l, d), norm(&base, law_slip_limit(law, MU, FN, 1.0)));
                    assert!(
                        (a - b).abs() <= 1e-12 * b.max(1e-300),
                        "k_T0 {k:e} A/δ* {r}: {a} vs {b}"
                    );
                }
            }
        }
    }
}

#[test]
fn nan_inf_and_null_are_named_and_nothing_is_written() {
    let good = contact(JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_THESIS, MU, FN, KT0);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for field in 0..3 {
            let mut c = good;
            match field {
                0 => c.mu = bad,
                1 => c.normal_force = bad,
                _ => c.k_t0 = bad,
            }
            assert_eq!(lin(&c, 1e-4, 1.3).0, JOINTLIN_ERR_NON_FINITE);
        }
        assert_eq!(lin(&good, bad, 1.3).0, JOINTLIN_ERR_NON_FINITE);
        assert_eq!(lin(&good, 1e-4, bad).0, JOINTLIN_ERR_NON_FINITE);
    }
    let mut out = SENTINEL;
    let s = unsafe { jointlin_linearize(std::ptr::null(), 1e-4, 1.3, std::ptr::null(), &mut out) };
    assert_eq!((s, out), (JOINTLIN_ERR_NULL, SENTINEL));
    let s = unsafe { jointlin_linearize(&good, 1e-4, 1.3, std::ptr::null(), std::ptr::null_mut()) };
    assert_eq!(s, JOINTLIN_ERR_NULL);
    // Unknown codes are out of range, never a panic.
    for (law, rule) in [(2, 0), (0, 2), (-1, 0), (i32::MAX, i32::MIN)] {
        assert_eq!(
            lin(&contact(law, rule, MU, FN, KT0), 1e-4, 1.3).0,
            JOINTLIN_ERR_OUT_OF_RANGE
        );
    }
}

/// Every output of a UINTER call is finite on OK, and untouched on an error.
fn uinter_checked(u: &mut Uinter, store: *const jointlin_store) -> i32 {
    let before = u.outputs();
    let s = u.call(store);
    assert_ne!(s, JOINTLIN_ERR_PANIC);
    let after = u.outputs();
    if s == JOINTLIN_OK {
        // STATEV(58:) are the host's: any value it left there is passed through.
        assert!(u.statev[..57].iter().all(|v| v.is_finite()), "STATEV");
        assert!(
            u.stress
                .iter()
                .chain(&u.ddsddr)
                .chain(&u.dviscous)
                .chain(&u.dstructural)
                .all(|v| v.is_finite()),
            "{:?}",
            u.stress
        );
        assert!(u.sfd.is_finite() && u.sfd >= 0.0, "SFD {}", u.sfd);
    } else {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&before), bits(&after), "written on error {s}");
    }
    s
}

#[test]
fn uinter_time_domain_with_huge_slips_increments_and_alternating_signs() {
    let d = slip_limit(MU, FN, KT0);
    for rule in [0.0, 1.0] {
        for law in [0.0, 1.0] {
            let mut props = block_props();
            props[0] = law;
            props[1] = rule;
            let mut u = Uinter::new(props, 3);
            let h = 2e-4; // p = 2
            let mut ok = 0;
            let mut energy = 0.0;
            // Slips from 1e-15 δ* to 1e300 mm, alternating sign, and tiny wiggles.
            let mut k = 0u32;
            for e in (-15..=300).step_by(5) {
                for sign in [1.0, -1.0] {
                    k += 1;
                    let s = sign * d * 10f64.powi(e);
                    let wiggle = if k.is_multiple_of(3) {
                        s * (1.0 + f64::EPSILON)
                    } else {
                        s
                    };
                    let status = {
                        for (dr, (new, old)) in
                            u.drdisp.iter_mut().zip([h, s, -wiggle].iter().zip(u.rdisp))
                        {
                            *dr = new - old;
                        }
                        u.rdisp = [h, s, -wiggle];
                        u.linper = 0;
                        uinter_checked(&mut u, std::ptr::null())
                    };
                    // Increments of 2e300 mm overflow DRDISP's arithmetic nowhere; a
                    // result that would not be finite is JOINTLIN_ERR_OVERFLOW.
                    assert!(
                        status == JOINTLIN_OK || status == JOINTLIN_ERR_OVERFLOW,
                        "slip {s:e}: {status}"
                    );
                    if status == JOINTLIN_OK {
                        ok += 1;
                        energy += u.sfd;
                        assert!(u.stress[1].abs() <= MU * 2.0 * (1.0 + 1e-12));
                    }
                }
            }
            assert!(ok > 100, "{ok} of {k} calls succeeded");
            // STATEV(5) accumulates SFD: finite even after 1e300-mm slides (μp·Δs would be
            // 1e300 per call: within f64).
            assert!(energy.is_finite() && u.statev[4].is_finite());
        }
    }
}

#[test]
fn uinter_extreme_props_and_corrupt_statev() {
    // (PROPS, overclosure): stiff, soft, huge, tiny values of every property.
    let mut cases: Vec<(Vec<f64>, f64)> = Vec::new();
    for mu in [0.0, 1e-300, 0.3, 1e300] {
        for k_t0 in [1e-300, 1e-3, 1282.7, 1e12, 1e300] {
            for k_n in [1e-300, 1e4, 1e300] {
                cases.push((vec![0.0, 0.0, mu, k_t0, 0.0, k_n, 0.0], 2e-4));
            }
        }
    }
    for e_star in [1e-300, 2e5, 1e300] {
        for r_star in [1e-300, 1.0, 1e300] {
            for g_star in [1e-300, 8e4, 1e300] {
                cases.push((
                    vec![
                        0.0, 1.0, 0.3, 0.0, 1.0, e_star, r_star, 1.0, g_star, 1.0, 0.0, 0.0,
                    ],
                    1e-3,
                ));
            }
        }
    }
    let mut outcomes = std::collections::BTreeMap::new();
    for (props, h) in &cases {
        for overclosure in [*h, 1e-300, 1e300, -1e300] {
            let mut u = Uinter::new(props.clone(), 3);
            let mut statuses = Vec::new();
            for (k, s) in [1e-6, -1e-3, 1e3, -1e300, 0.0].iter().enumerate() {
                u.rdisp = [overclosure, *s, -*s];
                u.drdisp = [0.0, *s, -*s];
                u.linper = 0;
                statuses.push(uinter_checked(&mut u, std::ptr::null()));
                // The steady state on what the general step left, at increment k + 1.
                let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
                assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0);
                assert_eq!(uexternaldb(store, 1, 0, 1, k as i32 + 1), 0);
                let mut v = u.clone();
                v.linper = 1;
                v.kinc = k as i32 + 1;
                statuses.push(uinter_checked(&mut v, store));
                unsafe { jointlin_store_free(store) };
            }
            for s in statuses {
                // Finite inputs whose results overflow (p = k_N h with k_N = h = 1e300, or
                // μp beyond f64) are JOINTLIN_ERR_OVERFLOW, never NON_FINITE.
                assert!(
                    [
                        JOINTLIN_OK,
                        JOINTLIN_ERR_OVERFLOW,
                        JOINTLIN_ERR_PROPS,
                        JOINTLIN_ERR_OUT_OF_RANGE
                    ]
                    .contains(&s),
                    "{props:?} h {overclosure:e}: {s}"
                );
                *outcomes.entry(s).or_insert(0) += 1;
            }
        }
    }
    // Most combinations are fine; the rest are named.
    assert!(
        outcomes[&JOINTLIN_OK] > outcomes.values().sum::<i32>() / 2,
        "{outcomes:?}"
    );

    // Corrupt STATEV: garbage in the hysteresis slots (finite numbers a host could leave
    // there) is OK with finite outputs or JOINTLIN_ERR_OUT_OF_RANGE ("corrupt hysteresis
    // state"), never a panic or NaN.
    let mut seed = 0x9e3779b97f4a7c15u64;
    let mut rand = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    let mut named = 0;
    for trial in 0..400 {
        let mut props = block_props();
        props[1] = f64::from(trial % 2);
        let mut u = Uinter::new(props, 3);
        for v in u.statev[..57].iter_mut() {
            let r = rand();
            *v = match r % 4 {
                0 => 0.0,
                1 => (r % 7) as f64 - 3.0,
                2 => f64::from_bits(r).clamp(-1e300, 1e300),
                _ => ((r >> 8) as f64 / 2f64.powi(56) - 0.5) * 10f64.powi((r % 40) as i32 - 20),
            };
            if !v.is_finite() {
                *v = 1.0;
            }
        }
        u.rdisp = [2e-4, 1e-4 * (trial as f64).sin(), 3e-4];
        u.drdisp = [0.0, 1e-5, -1e-5];
        u.linper = trial % 2;
        let store = new_store(1e-4, 1e-3, JOINTLIN_KINC_ORIGINAL);
        assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0);
        assert_eq!(uexternaldb(store, 1, 0, 1, 1), 0);
        let s = uinter_checked(&mut u, store);
        assert!(
            [
                JOINTLIN_OK,
                JOINTLIN_ERR_OUT_OF_RANGE,
                JOINTLIN_ERR_OVERFLOW
            ]
            .contains(&s),
            "trial {trial}: {s}"
        );
        named += i32::from(s != JOINTLIN_OK);
        unsafe { jointlin_store_free(store) };
    }
    assert!(named > 0, "garbage hysteresis state was never rejected");
}

/// Many points whose store estimate is exactly their slip limit δ* (pressure chosen so that
/// 1.5 μ p / k_T0 = the initial amplitude), and a host that reports amplitudes on both
/// sides of δ* by a few ulps: k*, d* are finite, the store converges in bounded passes.
#[test]
fn many_points_exactly_at_the_stick_slip_limit_through_the_store() {
    deadline(60, "store at the slip limit", || {
        let a0 = 1e-4;
        let p = a0 * KT0 / (1.5 * MU); // δ*(p) = a0
        let store = new_store(a0, 1e-9, JOINTLIN_KINC_ORIGINAL);
        const N: usize = 200;
        let mut passes = 0;
        loop {
            let (action, _) = next_action(store);
            let list = match action {
                JOINTLIN_ACTION_RUN_SWEEP => vec![1, 2],
                JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL => increments(store),
                JOINTLIN_ACTION_DONE => break,
                other => panic!("action {other} after {passes} passes"),
            };
            passes += 1;
            assert!(passes <= 25, "bounded");
            assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
            for &kinc in &list {
                assert_eq!(uexternaldb(store, 1, 0, 2, kinc), 0);
                for i in 0..N {
                    let mut u = Uinter::new(block_props(), 3);
                    u.coords = [i as f64, 0.0, 0.0];
                    u.stress[0] = p * (1.0 + (i % 3) as f64 * f64::EPSILON);
                    u.linper = 1;
                    u.kinc = kinc;
                    u.kstep = 2;
                    u.freqr = 50.0;
                    assert_eq!(uinter_checked(&mut u, store), JOINTLIN_OK);
                    let r = u.report;
                    assert!(r.regime[0] >= JOINTLIN_REGIME_MICROSLIP, "{r:?}");
                    // Host: a* = δ* (1 ± k ulp), alternating per point and direction.
                    let ulps = (i % 5) as f64 - 2.0;
                    let amp = [
                        a0 * (1.0 + ulps * f64::EPSILON),
                        a0 * (1.0 - ulps * f64::EPSILON),
                    ];
                    let s = unsafe { jointlin_store_report(store, r.point, kinc, amp.as_ptr()) };
                    assert_eq!(s, JOINTLIN_OK);
                }
                assert_eq!(uexternaldb(store, 2, 0, 2, kinc), 0);
            }
            assert_eq!(uexternaldb(store, 3, 0, 2, 0), 0);
        }
        let mut n = 0;
        assert_eq!(unsafe { jointlin_store_point_count(store, &mut n) }, 0);
        assert_eq!(n, N as i64);
        unsafe { jointlin_store_free(store) };
        // Pass 1 converges at once (estimate δ*, reports within 2 ulps), then the final.
        assert_eq!(passes, 2);
    });
}

/// The block of 4.2 (N, mm, s, t) driven near its stick resonance, where a ← a*
/// 2-cycles (Fig. 4.13) and at ω = 750 rad/s even the thesis's relaxation overshoots
/// forever; the default scheme converges in both, through `jointlin::iterate` and through
/// the store's passes.
fn block(omega: f64, forcing: f64) -> PointProblem {
    PointProblem {
        contact: Contact {
            law: TangentialLaw::Mindlin,
            rule: Rule::Thesis,
            mu: MU,
            normal_force: FN,
            k_t0: KT0,
        },
        mass: MASS,
        forcing,
        omega,
        ground_stiffness: 0.0,
        ground_damping: 0.0,
    }
}

fn opts(scheme: Scheme) -> Options {
    Options {
        scheme,
        tolerance: 1e-10,
        ..Options::default()
    }
}

#[test]
fn oscillating_iteration_converges_with_the_default_scheme_through_iterate() {
    deadline(30, "iterate", || {
        for omega in [700.0, 750.0] {
            let p = block(omega, 0.2);
            let s = solve_point(&p, &opts(Scheme::Secant)).expect("default converges");
            assert!(s.linearizations <= 20, "{}", s.linearizations);
            let (again, _) = p.response(s.amplitude, Method::default()).unwrap();
            assert!((again / s.amplitude - 1.0).abs() < 1e-9);
            assert!(matches!(
                solve_point(&p, &opts(Scheme::Direct)),
                Err(IterateError::TwoCycle { .. })
            ));
        }
        assert!(matches!(
            solve_point(&block(750.0, 0.2), &opts(Scheme::Relaxation)),
            Err(IterateError::MaxIterations { .. })
        ));
    });
}

/// One point, one frequency, iterated over passes by the store: the host's a* is the
/// block's response (4.2) to the k*, d* that jointlin_uinter returns (area 1, p = F_N).
/// Returns the final action, the passes and the last estimate.
fn store_block(scheme: i32, omega: f64, max_passes: i32) -> (i32, i32, f64) {
    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = 1e-4;
    cfg.rtol = 1e-9;
    cfg.scheme = scheme;
    cfg.max_passes = max_passes;
    let mut store = std::ptr::null_mut();
    assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
    let mut last = 0.0;
    for _ in 0..max_passes + 2 {
        let (action, _) = next_action(store);
        if !matches!(
            action,
            JOINTLIN_ACTION_RUN_SWEEP | JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL
        ) {
            break;
        }
        assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0);
        assert_eq!(uexternaldb(store, 1, 0, 1, 1), 0);
        let mut u = Uinter::new(block_props(), 2);
        u.stress[0] = FN;
        u.linper = 1;
        u.freqr = omega / (2.0 * PI);
        assert_eq!(uinter_checked(&mut u, store), JOINTLIN_OK);
        let (k, d) = (u.ddsddr[3], u.dviscous[3]);
        let a_star = 0.2 / (k - MASS * omega * omega).hypot(omega * d); // (4.2)
        last = u.report.amplitude[0];
        let amp = [a_star, 0.0];
        assert_eq!(
            unsafe { jointlin_store_report(store, u.report.point, 1, amp.as_ptr()) },
            0
        );
        assert_eq!(uexternaldb(store, 2, 0, 1, 1), 0);
        assert_eq!(uexternaldb(store, 3, 0, 1, 0), 0);
    }
    let (action, passes) = next_action(store);
    unsafe { jointlin_store_free(store) };
    (action, passes, last)
}

#[test]
fn oscillating_iteration_converges_with_the_default_scheme_through_the_store() {
    deadline(30, "store passes", || {
        for omega in [700.0, 750.0] {
            let reference = solve_point(&block(omega, 0.2), &opts(Scheme::Secant))
                .unwrap()
                .amplitude;
            let (action, passes, a) = store_block(JOINTLIN_SCHEME_SECANT, omega, 30);
            assert_eq!(action, JOINTLIN_ACTION_DONE, "ω = {omega}");
            assert!(passes <= 15, "ω = {omega}: {passes} passes");
            assert!(
                (a / reference - 1.0).abs() < 1e-8,
                "ω = {omega}: {a} vs {reference}"
            );
            // The thesis's a ← a* flips between two amplitudes until max_passes.
            let (action, passes, _) = store_block(JOINTLIN_SCHEME_DIRECT, omega, 30);
            assert_eq!(
                (action, passes),
                (JOINTLIN_ACTION_FAILED, 30),
                "ω = {omega}"
            );
        }
        let (action, _, _) = store_block(JOINTLIN_SCHEME_RELAXATION, 750.0, 30);
        assert_eq!(action, JOINTLIN_ACTION_FAILED);
    });
}

#[test]
fn sliding_mass_without_a_first_harmonic_solution_is_named() {
    deadline(30, "sliding mass", || {
        let friction = MU * FN;
        let limit = 4.0 * friction / PI;
        for scheme in [Scheme::Secant, Scheme::Relaxation, Scheme::Direct] {
            // The thesis's slip case F̂ = 0.75 N and both ends of the gap (μF_N, 4μF_N/π].
            for forcing in [0.75, friction * (1.0 + f64::EPSILON), limit] {
                match solve_point(&block(1.3, forcing), &opts(scheme)) {
                    Err(IterateError::NoFirstHarmonicSolution { limit: l, .. }) => {
                        assert!((l - limit).abs() < 1e-15);
                    }
                    other => panic!("{scheme:?} F̂ = {forcing}: {other:?}"),
                }
            }
            // Exactly at μF_N (not above it) and just above 4μF_N/π: an answer or a named
            // error, within the iteration bound.
            for forcing in [friction, limit * (1.0 + 1e-12), 0.8] {
                match solve_point(&block(1.3, forcing), &opts(scheme)) {
                    Ok(s) => assert!(s.amplitude.is_finite() && s.amplitude > 0.0),
                    Err(e) => assert!(
                        matches!(
                            e,
                            IterateError::MaxIterations { .. }
                                | IterateError::TwoCycle { .. }
                                | IterateError::NoBracket { .. }
                                | IterateError::Jump { .. }
                        ),
                        "{scheme:?} F̂ = {forcing}: {e:?}"
                    ),
                }
            }
        }
    });
}

#[test]
fn store_survives_extreme_reported_amplitudes() {
    deadline(30, "extreme reports", || {
        for scheme in [
            JOINTLIN_SCHEME_DIRECT,
            JOINTLIN_SCHEME_RELAXATION,
            JOINTLIN_SCHEME_SECANT,
        ] {
            let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
            assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
            cfg.initial_amplitude = 1e-4;
            cfg.scheme = scheme;
            cfg.max_passes = 8;
            let mut store = std::ptr::null_mut();
            assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
            let name = b"X";
            let mut id = 0;
            let reports = [0.0, 1e-300, 1e300, f64::MAX, 5e-324, 0.0, 1e-4, 1e300];
            for (pass, &r) in reports.iter().enumerate() {
                let (action, _) = next_action(store);
                if !matches!(
                    action,
                    JOINTLIN_ACTION_RUN_SWEEP
                        | JOINTLIN_ACTION_RUN_PASS
                        | JOINTLIN_ACTION_RUN_FINAL
                ) {
                    break;
                }
                assert_eq!(uexternaldb(store, 0, 0, 1, 0), 0, "pass {pass}");
                assert_eq!(uexternaldb(store, 1, 0, 1, 1), 0);
                let coords = [0.0];
                unsafe {
                    assert_eq!(
                        jointlin_store_register_point(
                            store,
                            name.as_ptr().cast(),
                            1,
                            0,
                            coords.as_ptr(),
                            1,
                            &mut id
                        ),
                        0
                    );
                    let mut est = [0.0; 2];
                    assert_eq!(jointlin_store_estimate(store, id, 1, est.as_mut_ptr()), 0);
                    assert!(
                        est.iter().all(|a| a.is_finite() && *a > 0.0),
                        "scheme {scheme} pass {pass}: {est:?}"
                    );
                    assert_eq!(jointlin_store_report(store, id, 1, [r, r].as_ptr()), 0);
                }
                assert_eq!(uexternaldb(store, 2, 0, 1, 1), 0);
                assert_eq!(uexternaldb(store, 3, 0, 1, 0), 0);
            }
            let (action, passes) = next_action(store);
            assert!(passes <= 9, "{passes}");
            assert!(
                action == JOINTLIN_ACTION_FAILED
                    || action == JOINTLIN_ACTION_RUN_PASS
                    || action == JOINTLIN_ACTION_DONE
                    || action == JOINTLIN_ACTION_RUN_FINAL
            );
            unsafe { jointlin_store_free(store) };
        }
    });
}

/// Library-level versions of two FE hard cases (the FE-model versions are the
/// harness's): all contacts open at an undamped eigenfrequency is a named singular system,
/// and near-zero damping at that resonance gives a finite amplitude or the same name.
#[test]
fn open_contacts_at_an_undamped_resonance_are_named_singular() {
    deadline(30, "resonance", || {
        let omega = 1.3;
        for damping in [0.0, 1e-300, 1e-200, 1e-12] {
            let p = PointProblem {
                contact: Contact {
                    normal_force: 0.0, // open
                    ..block(omega, 0.5).contact
                },
                ground_stiffness: MASS * omega * omega, // undamped eigenfrequency = ω
                ground_damping: damping,
                ..block(omega, 0.5)
            };
            for scheme in [Scheme::Secant, Scheme::Relaxation, Scheme::Direct] {
                match solve_point(&p, &opts(scheme)) {
                    Ok(s) => {
                        assert!(damping > 0.0, "{scheme:?}");
                        let want = 0.5 / (omega * damping);
                        assert!(s.amplitude.is_finite() && (s.amplitude / want - 1.0).abs() < 1e-6);
                    }
                    Err(e) => assert_eq!(e, IterateError::Singular, "{scheme:?} d {damping:e}"),
                }
            }
        }
    });
}
