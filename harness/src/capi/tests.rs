use super::*;
use crate::names::{ContactLaw, LawName, NormalLawName, RuleName};

#[test]
fn limits_of_the_linearization_through_the_c_api() {
    // Block of Appendix C: μ = 0.3, F_N = 2 N, k_T0 = 1282.7 N/mm.
    let t = Tangential {
        law: LawName::Mindlin,
        rule: RuleName::Thesis,
        mu: 0.3,
        normal: 2.0,
        k_t0: 1282.7,
    };
    let small = linearize(&t, 1e-12, 1.3).unwrap();
    // A → 0: k* → k_T0 (relative deviation ~A/δ*), d* → 0.
    assert!((small.k_star / 1282.7 - 1.0).abs() < 1e-6);
    // δ* = 1.5 μ F_N / k_T0 (2.46).
    approx::assert_relative_eq!(small.slip_limit, 1.5 * 0.6 / 1282.7, max_relative = 1e-12);
    let before = counts().linearize;
    let bad = linearize(&t, -1.0, 1.3).unwrap_err();
    assert_eq!(counts().linearize, before + 1);
    assert!(bad.detail.contains("amplitude"), "{bad}");
}

#[test]
fn quadrature_setting_reaches_the_library() {
    let t = Tangential {
        law: LawName::Mindlin,
        rule: RuleName::Thesis,
        mu: 0.3,
        normal: 2.0,
        k_t0: 1282.7,
    };
    // A/δ* = 0.8 (microslip): Simpson with 16 intervals is off by 4e-6 here (README
    // table: worst 2.5e-2 over A/δ*), the default by < 1e-12, so they must differ.
    let a = 0.8 * 1.5 * 0.6 / 1282.7;
    let d = linearize(&t, a, 1.3).unwrap();
    assert_eq!(set_quadrature(Some(Quadrature::Simpson(16))), None);
    let s = linearize(&t, a, 1.3).unwrap();
    let pr = props::encode(&ContactLaw {
        law: LawName::Mindlin,
        rule: RuleName::Thesis,
        mu: 0.3,
        k_t0_per_area: 1.0,
        normal_law: NormalLawName::Linear,
        normal_stiffness_per_area: Some(1.0),
        hertz_radius: None,
        hertz_e_star: None,
    });
    assert_eq!(set_quadrature(None), Some(Quadrature::Simpson(16)));
    assert_eq!((pr[10], pr[11]), (1.0, 16.0));
    let rel = (s.k_star / d.k_star - 1.0).abs();
    assert!(rel > 1e-7 && rel < 5e-2, "{rel}");
    assert_eq!(linearize(&t, a, 1.3).unwrap(), d);
}

#[test]
fn uinter_general_linear_normal_law() {
    let pr = props::encode(&ContactLaw {
        law: LawName::Mindlin,
        rule: RuleName::Thesis,
        mu: 0.3,
        k_t0_per_area: 100.0,
        normal_law: NormalLawName::Linear,
        normal_stiffness_per_area: Some(1e4),
        hertz_radius: None,
        hertz_e_star: None,
    });
    let p = UinterPoint {
        name: "joint",
        props: &pr,
        coords: [0.0; 3],
        area: 2.0,
    };
    let mut sv = [0.0; NSTATV];
    let out = uinter_general(&p, &mut sv, [1e-3, 0.0, 0.0], [1e-3, 0.0, 0.0], 1, 1).unwrap();
    // p = k_N h, dp/dh = k_N, stick tangent k_T0.
    assert_eq!(out.stress[0], 10.0);
    assert_eq!(out.ddsddr[0][0], 1e4);
    assert_eq!(out.ddsddr[1][1], 100.0);
    assert!(out.closed);
    let open = uinter_general(&p, &mut sv, [-1e-3, 0.0, 0.0], [-2e-3, 0.0, 0.0], 1, 2).unwrap();
    assert!(!open.closed && open.stress == [0.0; 3]);
}
