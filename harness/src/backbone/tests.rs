//! Validation of the backbones on Jenkins chains.

use nalgebra::{Complex, DMatrix};

use super::first_order::{stick_limit, stuck_mode};
use super::modes::complex_modes;
use super::ringdown::{cycles, free_decay};
use super::{epmc, first_order, log_space, BackbonePoint, C64};
use crate::capi::Tangential;
use crate::mhb::{first_order as fo_forced, Element, Law, System};
use crate::names::{LawName, RuleName};

/// The validation chain of `jointlin mhb` (bench::mhb_chain): ground –1– m₁ –1– m₂ –1– m₃,
/// D = 0.01 K, Jenkins elements (μF_N = 0.1, k_T0 = 2) m₁–ground and m₃–m₂, force
/// f cos ωt on m₃.
fn jenkins_chain(f: f64) -> System {
    let k = DMatrix::from_row_slice(3, 3, &[2.0, -1.0, 0.0, -1.0, 2.0, -1.0, 0.0, -1.0, 1.0]);
    let law = Law::Point(Tangential {
        law: LawName::Jenkins,
        rule: RuleName::Masing,
        mu: 1.0,
        normal: 0.1,
        k_t0: 2.0,
    });
    let z = C64::new(0.0, 0.0);
    System {
        m: DMatrix::identity(3, 3),
        d: &k * 0.01,
        k,
        f0: vec![0.0; 3],
        f1: vec![z, z, C64::new(f, 0.0)],
        elements: vec![
            Element { i: 0, j: None, law },
            Element {
                i: 2,
                j: Some(1),
                law,
            },
        ],
    }
}

fn chain() -> System {
    jenkins_chain(0.0)
}

/// Modal amplitude at which the stuck mode 1 first reaches a slip limit.
fn q_stick(sys: &System) -> f64 {
    let st = stuck_mode(sys, 1).unwrap();
    stick_limit(sys, &st.shape).unwrap()
}

/// K with every contact stuck (k_T0 between its DOFs).
fn stuck_k(sys: &System) -> DMatrix<f64> {
    let mut k = sys.k.clone();
    for e in &sys.elements {
        let Law::Point(t) = e.law else { continue };
        k[(e.i, e.i)] += t.k_t0;
        if let Some(j) = e.j {
            k[(j, j)] += t.k_t0;
            k[(e.i, j)] -= t.k_t0;
            k[(j, e.i)] -= t.k_t0;
        }
    }
    k
}

#[test]
fn small_amplitude_is_the_stuck_mode_large_the_sliding_mode() {
    // 3(a): far below the slip limit every contact sticks (k* = k_T0, d* = 0): the
    // backbone is the stuck linear mode exactly; far above, the contacts slide (k*, ωd*
    // fall like δ*/A): the backbone tends to the mode of the system without contacts.
    let sys = chain();
    let qs = q_stick(&sys);
    let stuck = &complex_modes(&sys.m, &sys.d, &stuck_k(&sys)).unwrap()[0];
    let free = &complex_modes(&sys.m, &sys.d, &sys.k).unwrap()[0];
    let q = [1e-3 * qs, 1e4 * qs];
    let fo = first_order::backbone(&sys, 1, &q).unwrap();
    let ep = epmc::backbone(&sys, 1, 3, &q).unwrap();
    for (name, lo, hi) in [
        ("first order", &fo[0], &fo[1]),
        ("EPMC H=3", &ep[0].point, &ep[1].point),
    ] {
        let e_stuck = (lo.omega / stuck.omega() - 1.0).abs();
        let z_stuck = (lo.damping_ratio / stuck.damping_ratio() - 1.0).abs();
        let e_free = (hi.omega / free.omega() - 1.0).abs();
        let z_free = (hi.damping_ratio / free.damping_ratio() - 1.0).abs();
        eprintln!(
            "3a {name}: stuck {e_stuck:.2e} {z_stuck:.2e}, sliding {e_free:.2e} {z_free:.2e}"
        );
        assert!(e_stuck < 1e-6 && z_stuck < 1e-4, "{name}");
        assert!(e_free < 1e-3 && z_free < 5e-2, "{name}");
    }
}

/// A unit mass on a ground spring (k = 1, c = 0.01) with a Jenkins element to ground
/// (k_T0 = 2, μF_N = 0.1).
fn single_dof() -> System {
    let mut s = chain();
    s.m = DMatrix::identity(1, 1);
    s.k = DMatrix::from_element(1, 1, 1.0);
    s.d = DMatrix::from_element(1, 1, 0.01);
    s.f0 = vec![0.0];
    s.f1 = vec![C64::new(0.0, 0.0)];
    s.elements.truncate(1);
    s
}

#[test]
fn epmc_at_one_harmonic_is_the_first_order_backbone() {
    // 3(b): H = 1 EPMC (the loop's own first harmonic, N = 1024 samples so the sampling
    // of the loop's kinks is below 1e-4) against the first-order eigenvalues (k*, d* of
    // the library) across the stick–slip transition. One DOF: the two are the same
    // equations (k + k* − ω²m = 0, ξ = c + d*), so they agree to the sampling. Several
    // DOFs with damping at the contacts only (not proportional to M): EPMC compensates
    // it by −ξM, the complex mode decays with its own shape; the two definitions then
    // differ at second order in ζ (measured here ≤ 0.60 ζ² in ω and ≤ 0.89 ζ² in ζ; on
    // the 2-DOF chain of 3(e) 1.01 ζ² and 1.70 ζ²).
    let sys = single_dof();
    let qs = q_stick(&sys);
    let q = log_space(0.3 * qs, 300.0 * qs, 25);
    let fo = first_order::backbone(&sys, 1, &q).unwrap();
    let ep = epmc::backbone_sampled(&sys, 1, 1, 1024, &q).unwrap();
    for (a, b) in fo.iter().zip(&ep) {
        let (ew, ez) = (
            b.point.omega / a.omega - 1.0,
            b.point.damping_ratio - a.damping_ratio,
        );
        assert!(
            ew.abs() < 1e-4 && ez.abs() < 1e-4 * a.damping_ratio,
            "1 DOF: {ew:e} {ez:e}"
        );
    }
    let sys = chain();
    let qs = q_stick(&sys);
    let q = log_space(0.3 * qs, 300.0 * qs, 25);
    let (ew, ez) = h1_against_first_order(&sys, &q);
    eprintln!("3b: 3 DOF: |Δω/ω| ≤ {ew:.2} ζ², |Δζ| ≤ {ez:.2} ζ²");
    assert!(ew < 1.0 && ez < 1.5, "ω {ew} ζ {ez}");
}

/// The largest |Δω/ω| and |Δζ| of mode 1's H = 1 EPMC (N = 1024) from its first-order
/// backbone at `q`, in units of ζ² (at least 1e-6).
fn h1_against_first_order(sys: &System, q: &[f64]) -> (f64, f64) {
    let fo = first_order::backbone(sys, 1, q).unwrap();
    let ep = epmc::backbone_sampled(sys, 1, 1, 1024, q).unwrap();
    let (mut ew, mut ez) = (0.0f64, 0.0f64);
    for (a, b) in fo.iter().zip(&ep) {
        let z2 = a.damping_ratio.powi(2).max(1e-6);
        ew = ew.max((b.point.omega / a.omega - 1.0).abs() / z2);
        ez = ez.max((b.point.damping_ratio - a.damping_ratio).abs() / z2);
    }
    (ew, ez)
}

/// Backbone ω_d and ζ at the DOF-`dof` first-harmonic amplitude `a` (log interpolation).
fn at_amplitude(bb: &[BackbonePoint], dof: usize, a: f64) -> Option<(f64, f64)> {
    bb.windows(2).find_map(|p| {
        let (a0, a1) = (p[0].shape[dof].norm(), p[1].shape[dof].norm());
        if (a - a0) * (a - a1) > 0.0 {
            return None;
        }
        let s = (a / a0).ln() / (a1 / a0).ln();
        let wd = |b: &BackbonePoint| b.omega * (1.0 - b.damping_ratio.powi(2)).sqrt();
        Some((
            wd(&p[0]) + s * (wd(&p[1]) - wd(&p[0])),
            p[0].damping_ratio + s * (p[1].damping_ratio - p[0].damping_ratio),
        ))
    })
}

#[test]
fn ring_down_follows_the_backbone() {
    // 3(c): free decay from the first-order mode at 30 q_stick (x = Re qφ, ẋ = Re λqφ),
    // RK4 with 512 steps per stuck period through jointlin_point_step; per cycle of m₃
    // the damped frequency and the log-decrement damping ratio against both backbones
    // at the cycle's first-harmonic amplitude.
    let sys = chain();
    let qs = q_stick(&sys);
    let q = log_space(0.1 * qs, 60.0 * qs, 60);
    let fo = first_order::backbone(&sys, 1, &q).unwrap();
    let ep: Vec<BackbonePoint> = epmc::backbone(&sys, 1, 3, &q)
        .map_err(|e| e.to_string())
        .unwrap()
        .into_iter()
        .map(|p| p.point)
        .collect();
    let start = first_order::backbone(&sys, 1, &[30.0 * qs])
        .unwrap()
        .remove(0);
    let lambda = C64::new(
        -start.damping_ratio * start.omega,
        start.omega * (1.0 - start.damping_ratio.powi(2)).sqrt(),
    );
    let x0: Vec<f64> = start.shape.iter().map(|v| v.re).collect();
    let v0: Vec<f64> = start.shape.iter().map(|v| (lambda * v).re).collect();
    let period = 2.0 * std::f64::consts::PI / stuck_mode(&sys, 1).unwrap().omega();
    let dt = period / 512.0;
    let dec = free_decay(&sys, &x0, &v0, dt, 512 * 40, 2).unwrap();
    let cyc = cycles(&dec);
    // Where the decay is slow (backbone ζ < 0.045, amplitude falling < 25 % per cycle)
    // and the contacts slip, each cycle is compared; once stuck the decay is linear and
    // beats with the other modes' remainder (±30 % per cycle), so the stuck cycles are
    // compared on average. Cycles through the transition (ζ up to 0.12, half the
    // amplitude lost per cycle) have no single amplitude and are not compared.
    let a_stick = stuck_mode(&sys, 1).unwrap().shape[2].norm() * qs;
    let (mut slipping, mut worst) = (0, [0.0f64; 4]);
    let (mut stuck, mut stuck_w, mut stuck_z) = (0, 0.0, 0.0);
    for c in &cyc {
        let (Some(a), Some(b)) = (
            at_amplitude(&fo, 2, c.amplitude),
            at_amplitude(&ep, 2, c.amplitude),
        ) else {
            continue;
        };
        if c.amplitude < 0.9 * a_stick {
            stuck += 1;
            stuck_w += c.omega_d / a.0 - 1.0;
            stuck_z += c.damping_ratio / a.1 - 1.0;
            continue;
        }
        if a.1 > 0.045 || c.amplitude < 2.0 * a_stick {
            continue;
        }
        slipping += 1;
        let errs = [
            (c.omega_d / a.0 - 1.0).abs(),
            (c.damping_ratio - a.1).abs() / a.1,
            (c.omega_d / b.0 - 1.0).abs(),
            (c.damping_ratio - b.1).abs() / b.1,
        ];
        for (w, e) in worst.iter_mut().zip(errs) {
            *w = w.max(e);
        }
    }
    let (stuck_w, stuck_z) = (stuck_w / stuck as f64, stuck_z / stuck as f64);
    eprintln!(
        "3c: {slipping} slipping cycles, worst ω_d, ζ: first order {:.2e} {:.2e}, H=3 {:.2e} \
         {:.2e}; {stuck} stuck cycles, mean {stuck_w:.2e} {stuck_z:.2e}",
        worst[0], worst[1], worst[2], worst[3]
    );
    assert!(slipping >= 3 && stuck >= 10, "{slipping} {stuck}");
    assert!(worst[0] < 1e-2 && worst[1] < 0.1, "first order: {worst:?}");
    assert!(worst[2] < 1e-2 && worst[3] < 0.1, "H = 3: {worst:?}");
    assert!(
        stuck_w.abs() < 1e-3 && stuck_z.abs() < 0.15,
        "stuck {stuck_w} {stuck_z}"
    );
}

#[test]
fn backbone_threads_the_forced_response_peaks() {
    // 3(d): first-order forced responses of the chain (force f cos Ωt on m₃) at four
    // force levels; the peak of |x̂₃(Ω)| (grid of 4000 Ω, parabola through the top
    // three) lies on the first-order backbone: its ω_d at the peak amplitude.
    let sys = chain();
    let qs = q_stick(&sys);
    let bb = first_order::backbone(&sys, 1, &log_space(0.1 * qs, 1e3 * qs, 120)).unwrap();
    for f in [0.002, 0.01, 0.03, 0.06] {
        let forced = jenkins_chain(f);
        let omegas: Vec<f64> = (0..4000).map(|i| 0.35 + 0.4 * i as f64 / 3999.0).collect();
        let mut a = vec![1e-3; 2];
        let amp: Vec<f64> = omegas
            .iter()
            .map(|&w| {
                let x = fo_forced::solve(&forced, w, &a).unwrap();
                a = fo_forced::element_amplitudes(&forced, &x);
                x[2].norm()
            })
            .collect();
        let k = (1..amp.len() - 1)
            .max_by(|&i, &j| amp[i].total_cmp(&amp[j]))
            .unwrap();
        let (y0, y1, y2) = (amp[k - 1], amp[k], amp[k + 1]);
        let h = omegas[1] - omegas[0];
        let off = 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2);
        let (w_peak, a_peak) = (omegas[k] + off * h, y1 - 0.25 * (y0 - y2) * off);
        let (wd, z) = at_amplitude(&bb, 2, a_peak).expect("peak amplitude on the backbone");
        let w0 = wd / (1.0 - z * z).sqrt();
        let e = w_peak / w0 - 1.0;
        eprintln!(
            "3d: f {f}: peak Ω {w_peak:.5} A {a_peak:.4e}, backbone ω {w0:.5} ζ {z:.4}: {e:.2e}"
        );
        assert!(e.abs() < 5e-3, "f {f}: {e:e}");
    }
}

/// Jenkins k* and ωd* in closed form (Caughey 1960, bilinear hysteresis with zero
/// post-slip stiffness): stuck below δ* = μF_N/k_T0; above, cos θ = 1 − 2δ*/A,
/// k* = (k_T0/π)(θ − ½ sin 2θ), ωd* = 4μF_N(A − δ*)/(πA²) (loop area over πA²).
fn jenkins_closed_form(kt: f64, mun: f64, a: f64) -> (f64, f64) {
    let ds = mun / kt;
    if a <= ds {
        return (kt, 0.0);
    }
    let th = (1.0 - 2.0 * ds / a).acos();
    (
        kt / std::f64::consts::PI * (th - 0.5 * (2.0 * th).sin()),
        4.0 * mun * (a - ds) / (std::f64::consts::PI * a * a),
    )
}

#[test]
fn two_dof_chain_against_an_independent_reference() {
    // 3(e): ground –k₁– m₁ –k₂– m₂ with a Jenkins element m₁–ground (k_T0 = 3, μF_N = 0.2)
    // and no viscous damping. Reference, parametrized by the element amplitude A: k*,
    // ωd* in closed form; the eigenvalue from Newton on the 2×2 determinant in complex
    // arithmetic with ω = |λ| iterated; q = A/|φ₁| with φᴴMφ = 1. The backbones at those
    // q must give the same ω and ζ.
    let (m1, m2, k1, k2, kt, mun) = (1.0, 0.5, 1.0, 0.8, 3.0, 0.2);
    let sys = System {
        m: DMatrix::from_row_slice(2, 2, &[m1, 0.0, 0.0, m2]),
        d: DMatrix::zeros(2, 2),
        k: DMatrix::from_row_slice(2, 2, &[k1 + k2, -k2, -k2, k2]),
        f0: vec![0.0; 2],
        f1: vec![Complex::new(0.0, 0.0); 2],
        elements: vec![Element {
            i: 0,
            j: None,
            law: Law::Point(Tangential {
                law: LawName::Jenkins,
                rule: RuleName::Masing,
                mu: 1.0,
                normal: mun,
                k_t0: kt,
            }),
        }],
    };
    let ds = mun / kt;
    let mut lam = C64::new(0.0, ((k1 + kt) / m1).sqrt() * 0.5);
    let (mut qs, mut refs) = (Vec::new(), Vec::new());
    for i in 0..30 {
        let a = ds * 0.5 * 1.3f64.powi(i);
        let (ks, wds) = jenkins_closed_form(kt, mun, a);
        // det[(m₁λ² + λ d + k₁ + k₂ + k*)(m₂λ² + k₂) − k₂²], d = ωd*/ω with ω = |λ|.
        for _ in 0..50 {
            let c = wds / lam.norm();
            let p = |l: C64| (m1 * l * l + c * l + k1 + k2 + ks) * (m2 * l * l + k2) - k2 * k2;
            let dp = |l: C64| {
                (2.0 * m1 * l + c) * (m2 * l * l + k2)
                    + (m1 * l * l + c * l + k1 + k2 + ks) * 2.0 * m2 * l
            };
            lam -= p(lam) / dp(lam);
        }
        // Shape: second row gives φ₂ = k₂ φ₁/(m₂λ² + k₂).
        let r = k2 / (m2 * lam * lam + k2);
        let phi1 = 1.0 / (m1 + m2 * r.norm_sqr()).sqrt();
        qs.push(a / phi1);
        refs.push((lam.norm(), -lam.re / lam.norm()));
    }
    let fo = first_order::backbone(&sys, 1, &qs).unwrap();
    let ep = epmc::backbone_sampled(&sys, 1, 1, 1024, &qs).unwrap();
    let (mut e1, mut ew, mut ez) = (0.0f64, 0.0f64, 0.0f64);
    for ((b, e), (w, z)) in fo.iter().zip(&ep).zip(&refs) {
        e1 = e1
            .max((b.omega / w - 1.0).abs())
            .max((b.damping_ratio - z).abs());
        // EPMC: equal up to the second-order difference of the definitions (3(b)).
        let z2 = (z * z).max(1e-6);
        ew = ew.max((e.point.omega / w - 1.0).abs() / z2);
        ez = ez.max((e.point.damping_ratio - z).abs() / z2);
    }
    eprintln!("3e: first order {e1:.2e}; EPMC H=1 |Δω/ω| ≤ {ew:.2} ζ², |Δζ| ≤ {ez:.2} ζ²");
    assert!(e1 < 1e-8, "first order {e1:e}");
    assert!(ew < 1.2 && ez < 2.0, "EPMC H=1 {ew} {ez}");
}

#[test]
fn bad_inputs_are_named() {
    let sys = chain();
    assert!(matches!(
        first_order::backbone(&sys, 4, &[1.0]),
        Err(super::BackboneError::NoMode { mode: 4, count: 3 })
    ));
    for q in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            first_order::backbone(&sys, 1, &[q]),
            Err(super::BackboneError::Amplitude(_))
        ));
        assert!(matches!(
            epmc::backbone(&sys, 1, 3, &[q]),
            Err(super::BackboneError::Amplitude(_))
        ));
    }
}

#[test]
fn epmc_passes_the_turning_point_where_the_second_joint_slips() {
    // 4 (regression): at H ≥ 3 the chain's backbone turns back in q where the joint
    // m₃–m₂ starts to slip (before, the continuation in q stopped at q ≈ 0.46 at
    // H = 5 and 7). Followed by arclength, the path rises to the turning point, falls
    // while the second joint begins to slip and rises again on the slipping branch; an
    // amplitude in between is met three times. The same turning points with 4× and 16×
    // the samples: a property of the balance, not of the sampling.
    let sys = chain();
    let q = log_space(0.3, 0.7, 41);
    let mut ranges = Vec::new();
    for n in [128usize, 512, 2048] {
        let t = epmc::trace(&sys, 1, 7, n, &q).unwrap();
        assert!(t.stopped.is_none(), "N = {n}: {:?}", t.stopped);
        let lo = t
            .turning_points
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let hi = t.turning_points.iter().copied().fold(0.0, f64::max);
        eprintln!(
            "N = {n}: {} points, {} turning points, q in [{lo:.5}, {hi:.5}]",
            t.points.len(),
            t.turning_points.len()
        );
        assert!(t.turning_points.len() >= 2 && t.turning_points.len().is_multiple_of(2));
        ranges.push((lo, hi));
        assert!(lo > 0.44 && hi < 0.47, "N = {n}: [{lo}, {hi}]");
        // Every amplitude once, some near the turning points three times.
        let passages = |a: f64| {
            t.points
                .iter()
                .filter(|p| p.point.modal_amplitude == a)
                .count()
        };
        let thrice: Vec<f64> = q.iter().copied().filter(|a| passages(*a) == 3).collect();
        assert!(q.iter().all(|a| [1, 3].contains(&passages(*a))), "N = {n}");
        assert!(!thrice.is_empty() && thrice.iter().all(|a| *a > 0.44 && *a < 0.47));
        if n != 128 {
            continue;
        }
        // The second joint dissipates nothing before the turning point, and does after.
        let last = &t.points[t.points.len() - 1].point;
        let turn = t
            .points
            .windows(2)
            .position(|w| w[1].point.modal_amplitude <= w[0].point.modal_amplitude)
            .unwrap();
        let j1 = t.points[turn].point.energy_per_cycle[0];
        let j2 = t.points[turn].point.energy_per_cycle[1];
        eprintln!(
            "before the turning point: joint energies {j1:.3e}, {j2:.3e}; last {:?}",
            last.energy_per_cycle
        );
        assert!(j1 > 0.0 && j2 < 1e-9 * j1, "{j1:e} {j2:e}");
        assert!(last.energy_per_cycle[1] > 0.1 * last.energy_per_cycle[0]);
        // At an amplitude inside, three different damping ratios in path order: the
        // lower branch damps least.
        let mid = thrice[0];
        let z: Vec<f64> = t
            .points
            .iter()
            .filter(|p| p.point.modal_amplitude == mid)
            .map(|p| p.point.damping_ratio)
            .collect();
        eprintln!("q = {mid:.5}: ζ = {z:?}");
        assert_eq!(z.len(), 3);
        assert!(z[0] < z[1] && z[1] < z[2], "{z:?}");
    }
    for (lo, hi) in &ranges[..2] {
        assert!((lo / ranges[2].0 - 1.0).abs() < 1e-2 && (hi / ranges[2].1 - 1.0).abs() < 1e-2);
    }
}

#[test]
fn amplitude_stepping_follows_the_arclength_path_where_it_does_not_turn() {
    // The fallback where the arclength path stops (stepping in q alone) must land on the
    // same backbone where the backbone does not turn back: one DOF at H = 5 across the
    // whole stick–slip transition, the 3-DOF chain at H = 3 before its second joint slips.
    for (sys, h, to) in [(single_dof(), 5, 300.0), (chain(), 3, 3.0)] {
        let qs = q_stick(&sys);
        let q = log_space(0.6 * qs, to * qs, 15);
        let arc = epmc::backbone(&sys, 1, h, &q).unwrap();
        let step =
            epmc::amplitude_stepping(&sys, 1, h, crate::mhb::default_samples(h), &q).unwrap();
        assert_eq!(arc.len(), step.len());
        for (a, b) in arc.iter().zip(&step) {
            let (a, b) = (&a.point, &b.point);
            assert!((a.modal_amplitude / b.modal_amplitude - 1.0).abs() < 1e-14);
            let ew = (b.omega / a.omega - 1.0).abs();
            let ez = (b.damping_ratio - a.damping_ratio).abs() / a.damping_ratio;
            assert!(
                ew < 1e-8 && ez < 1e-6,
                "q = {}: ω {ew:e}, ζ {ez:e}",
                a.modal_amplitude
            );
        }
    }
}

/// A thesis-rule Mindlin point to ground (μF_N = 0.1, k_T0 = 2) on each DOF in `on`.
fn thesis_points(on: &[usize]) -> Vec<Element> {
    let law = Law::Point(Tangential {
        law: LawName::Mindlin,
        rule: RuleName::Thesis,
        mu: 1.0,
        normal: 0.1,
        k_t0: 2.0,
    });
    on.iter().map(|&i| Element { i, j: None, law }).collect()
}

/// Unit masses with stiffness `k`, no damping, no load, and the thesis points `on`.
fn undamped(k: DMatrix<f64>, on: &[usize]) -> System {
    let n = k.nrows();
    System {
        m: DMatrix::identity(n, n),
        d: DMatrix::zeros(n, n),
        k,
        f0: vec![0.0; n],
        f1: vec![C64::new(0.0, 0.0); n],
        elements: thesis_points(on),
    }
}

#[test]
fn a_structure_held_only_by_friction_has_a_multi_harmonic_backbone() {
    // m₁ –1– m₂ with the point on m₁ and nothing else to ground: K is singular (the pair
    // translates freely) and the thesis rule's closed loop is the same for every mean
    // offset, so the mean rows of the balance vanish and the Jacobian was singular at the
    // first amplitude ("Newton did not converge"). The gauge spring on the free mean
    // picks the motion without offset: the backbone converges (H = 1 and 3 under the
    // thesis rule, 3 and 7 under Masing's; the thesis rule at H ≥ 5 crawls over its
    // loop's jumps, docs/backbone-fe.md), the mean stays zero, and H = 1 is the
    // first-order backbone up to the O(ζ²) of contact-only damping (3(b)).
    let sys = undamped(DMatrix::from_row_slice(2, 2, &[1.0, -1.0, -1.0, 1.0]), &[0]);
    let qs = q_stick(&sys);
    let q = log_space(0.3 * qs, 30.0 * qs, 9);
    for (h, rule) in [
        (1, RuleName::Thesis),
        (3, RuleName::Thesis),
        (3, RuleName::Masing),
        (7, RuleName::Masing),
    ] {
        let mut sys = sys.clone();
        for e in &mut sys.elements {
            if let Law::Point(t) = &mut e.law {
                t.rule = rule;
            }
        }
        let ep =
            epmc::backbone(&sys, 1, h, &q).unwrap_or_else(|e| panic!("H = {h}, {rule:?}: {e}"));
        let m = 2 * h + 1;
        let mean = ep
            .iter()
            .map(|p| (p.u[0].abs().max(p.u[m].abs())) / p.point.modal_amplitude)
            .fold(0.0, f64::max);
        eprintln!("free pair H = {h}, {rule:?}: largest mean / q = {mean:.1e}");
        assert!(mean < 1e-9, "H = {h}, {rule:?}: mean {mean:e}");
    }
    // The first-order backbone ends where the sliding pair nears critical damping
    // (ζ = 0.95 at 0.59); compared below it.
    let q = log_space(0.3 * qs, 0.5, 9);
    let (ew, ez) = h1_against_first_order(&sys, &q);
    eprintln!("free pair H = 1 against first order: |Δω/ω| ≤ {ew:.2} ζ², |Δζ| ≤ {ez:.2} ζ²");
    assert!(ew < 1.0 && ez < 1.5, "ω {ew} ζ {ez}");
}

#[test]
fn a_pair_of_modes_at_one_frequency_starts_each_on_its_own_branch() {
    // Three unit masses in a ring of unit springs, each on a thesis point to ground: the
    // modes 2 and 3 share ω² = k_T0 + 3 and the eigen solver returns any two of their
    // plane. The nonlinear modes start where Σ|a|³ is stationary. Its largest is one mass
    // at rest and the other two in antiphase, (1, −1, 0)/√2 up to symmetry: a single DOF
    // on its point with the spring 3 (the mass at rest feels no force), so mode 2 equals
    // that system's backbone at the same mass amplitude. Mode 3 starts M-orthogonal to
    // it, at (2, −1, −1)/√6, the branch symmetric in the two moving alike: it keeps
    // their amplitudes equal. (Started from the eigen solver's vector instead, mode 2
    // followed the (2, −1, −1) branch; the block on the plane's modes 1 and 2 both
    // followed its diagonal.)
    let ring = DMatrix::from_row_slice(3, 3, &[2.0, -1.0, -1.0, -1.0, 2.0, -1.0, -1.0, -1.0, 2.0]);
    let sys = undamped(ring, &[0, 1, 2]);
    let single = undamped(DMatrix::from_element(1, 1, 3.0), &[0]);
    let qs = q_stick(&single);
    let q = log_space(0.3 * qs, 30.0 * qs, 7);
    let reference = epmc::backbone(&single, 1, 3, &q).unwrap();
    let q_ring: Vec<f64> = q.iter().map(|v| v * 2f64.sqrt()).collect();
    let amp = |p: &epmc::EpmcPoint, d: usize| p.u[d * 7 + 1].hypot(p.u[d * 7 + 2]);
    let order = |p: &epmc::EpmcPoint| {
        let mut d = [0, 1, 2];
        d.sort_by(|&a, &b| amp(p, a).total_cmp(&amp(p, b)));
        d
    };
    let two = epmc::backbone(&sys, 2, 3, &q_ring).unwrap();
    let still = order(&two[0])[0];
    let (mut rest, mut worst) = (0.0f64, 0.0f64);
    for (p, r) in two.iter().zip(&reference) {
        rest = rest.max(amp(p, still) / p.point.modal_amplitude);
        worst = worst
            .max((p.point.omega / r.point.omega - 1.0).abs())
            .max((p.point.damping_ratio / r.point.damping_ratio - 1.0).abs());
    }
    eprintln!("ring mode 2: mass {still} at rest ({rest:.1e} of q), ω and ζ within {worst:.1e} of the single DOF");
    assert!(rest < 1e-9 && worst < 1e-7, "mode 2: {rest:e} {worst:e}");
    let three = epmc::backbone(&sys, 3, 3, &q_ring).unwrap();
    let [lo, mid, hi] = order(&three[0]);
    let alike = three
        .iter()
        .map(|p| (amp(p, mid) - amp(p, lo)).abs() / p.point.modal_amplitude)
        .fold(0.0, f64::max);
    eprintln!("ring mode 3: masses {lo} and {mid} alike to {alike:.1e} of q, mass {hi} largest");
    assert!(alike < 1e-9, "mode 3: {alike:e}");
    assert!(amp(&three[0], hi) > 1.5 * amp(&three[0], mid));
}
