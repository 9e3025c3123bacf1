use super::describing::{describe, unit_cell};
use super::ellipse::cell_on_ellipse;
use super::*;
use crate::hysteresis::{Point, PointState, Rule};
use crate::law::{Backbone, TangentialLaw};
use std::f64::consts::PI;

pub(super) const MU: f64 = 0.5;
pub(super) const K_T: f64 = 1000.0;
pub(super) const K_N: f64 = 2000.0;

/// A point with μ = 0.5, k_T0 = 1000 and a linear normal law k_N = 2000 (force form).
pub(super) fn contact(tangential: Tangential3d) -> Contact3d {
    Contact3d {
        tangential,
        mu: MU,
        k_t0: K_T,
        normal: NormalLaw::Linear {
            stiffness_per_area: K_N,
        },
    }
}

/// Overclosure giving the normal force `n` with the linear law.
fn h_for(n: f64) -> f64 {
    n / K_N
}

/// Steps `c` through `path`, returning the final state, the forces at every point and the
/// dissipation summed over the steps.
fn run(c: &Contact3d, path: &[[f64; 3]]) -> (State3d, Vec<Step3d>, f64) {
    let mut st = State3d::default();
    let mut out = Vec::new();
    let mut diss = 0.0;
    for &d in path {
        let (next, r) = c.step(&st, d).unwrap();
        st = next;
        diss += r.dissipated;
        out.push(r);
    }
    (st, out, diss)
}

#[test]
fn jenkins_on_a_straight_path_is_the_one_dimensional_element() {
    // Any direction α, a path with reversals: force along the path = the 1D Jenkins force
    // (Masing rule), perpendicular force 0, dissipation equal, to 1e-14 μN.
    let n = 3.0;
    let limit = MU * n;
    let one_d = Point::new(
        Backbone::new(TangentialLaw::Jenkins, limit, K_T).unwrap(),
        Rule::Masing,
    );
    let slips = [
        0.0, 1e-3, 2.5e-3, 0.4e-3, -3e-3, -2.9e-3, 1e-4, 5e-3, 4.999e-3,
    ];
    for alpha in [0.0, 0.3, PI / 4.0, 2.0] {
        let dir = [f64::cos(alpha), f64::sin(alpha)];
        let mut st3 = State3d::default();
        let mut st1 = PointState::virgin(Rule::Masing, 0.0);
        for w in slips.windows(2) {
            for i in 1..=5 {
                let s = w[0] + (w[1] - w[0]) * i as f64 / 5.0;
                let (n3, r3) = contact(Tangential3d::Jenkins)
                    .step(&st3, [s * dir[0], s * dir[1], h_for(n)])
                    .unwrap();
                let (n1, r1) = one_d.step(&st1, s).unwrap();
                let along = r3.force[0] * dir[0] + r3.force[1] * dir[1];
                let perp = -r3.force[0] * dir[1] + r3.force[1] * dir[0];
                assert!((along - r1.force).abs() <= 1e-14 * limit, "{alpha} {s}");
                assert!(perp.abs() <= 1e-14 * limit);
                assert!((r3.dissipated - r1.dissipated).abs() <= 1e-14 * limit * 1e-3);
                assert!((r3.force[2] - n).abs() <= 1e-15 * n);
                (st3, st1) = (n3, n1);
            }
        }
    }
}

/// Steps a point on the ellipse (a cos θ, b sin θ) at constant overclosure: a straight
/// ramp from the centre to (a, 0), then cycles of `steps` steps until the sliders repeat to
/// 1e-13 of the amplitude (at most `cycles`). Returns the last cycle's energy and the force
/// harmonics (1/π)Σ tⱼ{cos, sin} Δθ as (c1, s1, c2, s2).
fn steady_cycle(
    c: &Contact3d,
    h: f64,
    a: f64,
    b: f64,
    steps: usize,
    cycles: usize,
) -> (f64, [f64; 4]) {
    let (mut st, _) = c.step(&State3d::default(), [a, 0.0, h]).unwrap();
    let mut energy = 0.0;
    let mut harm = [0.0; 4];
    for _ in 0..cycles {
        let start = st;
        energy = 0.0;
        harm = [0.0; 4];
        for j in 1..=steps {
            let th = 2.0 * PI * j as f64 / steps as f64;
            let (next, r) = c.step(&st, [a * th.cos(), b * th.sin(), h]).unwrap();
            st = next;
            energy += r.dissipated;
            let w = 2.0 / steps as f64;
            harm[0] += w * r.force[0] * th.cos();
            harm[1] += w * r.force[0] * th.sin();
            harm[2] += w * r.force[1] * th.cos();
            harm[3] += w * r.force[1] * th.sin();
        }
        let moved = (0..c.cell_count())
            .flat_map(|i| (0..2).map(move |k| (i, k)))
            .map(|(i, k)| (st.sliders[i][k] - start.sliders[i][k]).abs())
            .fold(0.0, f64::max);
        if moved < 1e-13 * a.max(b) {
            break;
        }
    }
    (energy, harm)
}

#[test]
fn jenkins_on_a_circle_slides_above_k_r_equal_mu_n_and_loses_two_pi_r_slip_mu_n() {
    // Closed form (docs/contact3d.md §4): the slider runs on a circle of radius
    // r_slip = √(R² − x²), x = μN/k; energy per cycle 2π r_slip μN.
    let n = 2.0;
    let x = MU * n / K_T;
    let c = contact(Tangential3d::Jenkins);
    let (e_stick, _) = steady_cycle(&c, h_for(n), 0.99 * x, 0.99 * x, 512, 3);
    assert_eq!(e_stick, 0.0);
    for ratio in [1.05, 2.0, 10.0] {
        let r = ratio * x;
        let exact = 2.0 * PI * ((r * r - x * x).sqrt()) * MU * n;
        // Polygon error O(Δθ²), smooth on a circle (steady slip): Richardson from 2048
        // and 4096 steps per cycle.
        let (e1, _) = steady_cycle(&c, h_for(n), r, r, 2048, 12);
        let (e2, _) = steady_cycle(&c, h_for(n), r, r, 4096, 12);
        let e = (4.0 * e2 - e1) / 3.0;
        assert!(
            ((e - exact) / exact).abs() < 2e-6,
            "{ratio}: {e} vs {exact}"
        );
        // Two independent 1D limits on the same circle lose 2·4μN(R − x) (model.md §10).
        let independent = 8.0 * MU * n * (r - x);
        assert!((independent - exact).abs() > 0.05 * exact);
    }
}

#[test]
fn an_oblique_straight_path_slips_where_independent_limits_still_stick() {
    // Amplitude R at 45°: each component R/√2. With x < R < √2 x, the coupled limit slides
    // and independent limits (each μN at component amplitude ≥ x) would not.
    let n = 2.0;
    let x = MU * n / K_T;
    let r = 1.2 * x;
    let c = contact(Tangential3d::Jenkins);
    let d = std::f64::consts::FRAC_1_SQRT_2;
    let path: Vec<[f64; 3]> = (0..=400)
        .map(|j| {
            let s = r * (2.0 * PI * j as f64 / 200.0).sin();
            [s * d, s * d, h_for(n)]
        })
        .collect();
    let (_, _, diss) = run(&c, &path);
    assert!(r * d < x);
    // Second cycle of a centred 1D loop: 4μN(R − x) per cycle; first cycle a bit less.
    assert!(diss > 4.0 * MU * n * (r - x), "{diss}");
}

#[test]
fn separation_carries_no_force_and_reclosing_starts_from_zero() {
    let c = contact(Tangential3d::MindlinMasing { cells: 8 });
    let h = h_for(4.0);
    let (st, out, _) = run(&c, &[[1e-3, 5e-4, h], [1.5e-3, 5e-4, h]]);
    assert!(out[1].force[0] > 0.0);
    // Open: h ≤ 0.
    for gap in [0.0, -1e-3] {
        let (st_open, r) = c.step(&st, [2e-3, -1e-3, gap]).unwrap();
        assert_eq!(r.force, [0.0; 3]);
        assert_eq!(r.regime, Regime::Open);
        assert!(r.stiffness.iter().flatten().all(|&v| v == 0.0));
        // Released elastic energy is dissipated: Σ|tᵢ|²/(2kᵢ) > 0.
        assert!(r.dissipated > 0.0);
        // Reclosing anywhere: zero tangential force at the closing point.
        let (_, back) = c.step(&st_open, [2e-3, -1e-3, h]).unwrap();
        assert!(back.force[0].abs() < 1e-12 && back.force[1].abs() < 1e-12);
        assert!((back.force[2] - 4.0).abs() < 1e-14);
    }
}

#[test]
fn a_vanishing_normal_load_gives_a_vanishing_finite_friction_force() {
    let c = contact(Tangential3d::MindlinMasing { cells: 32 });
    for n in [1e-3, 1e-100, 1e-300, 5e-324] {
        let (_, out, diss) = run(&c, &[[1e-3, 1e-3, h_for(n)], [-1e-3, 2e-3, h_for(n)]]);
        for r in &out {
            let t = r.force[0].hypot(r.force[1]);
            assert!(t.is_finite() && t <= MU * n * (1.0 + 1e-12), "{n}: {t}");
        }
        assert!(diss.is_finite() && diss >= 0.0);
    }
}

#[test]
fn pure_normal_motion_does_not_load_the_tangential_directions() {
    let c = contact(Tangential3d::Jenkins);
    let path: Vec<[f64; 3]> = (0..50)
        .map(|j| [0.0, 0.0, 1e-3 * (j as f64 * 0.3).sin()])
        .collect();
    let (_, out, diss) = run(&c, &path);
    assert_eq!(diss, 0.0);
    assert!(out.iter().all(|r| r.force[0] == 0.0 && r.force[1] == 0.0));
    // A loaded spring whose normal load drops at fixed u releases down to the new limit:
    // energy (|t|² − (μN)²)/(2k).
    let (st, out, _) = run(&c, &[[1e-3, 0.0, h_for(10.0)]]);
    let t = out[0].force[0];
    let (_, r) = c.step(&st, [1e-3, 0.0, h_for(1.0)]).unwrap();
    assert!((r.force[0] - MU).abs() < 1e-15);
    let expect = (t * t - MU * MU) / (2.0 * K_T);
    assert!((r.dissipated - expect).abs() < 1e-15 * expect.max(1.0));
}

#[test]
fn stick_conserves_energy() {
    // A closed path inside every cell's limit: nothing dissipated, ∮t·du = 0 (the
    // trapezoidal work is exact for a linear spring on straight segments).
    let c = contact(Tangential3d::MindlinMasing { cells: 32 });
    let n = 5.0;
    let smallest = c.cells().strength[0] * MU * n / (K_T * c.cells().stiffness[0]);
    let r = 0.4 * smallest;
    let path: Vec<[f64; 3]> = (0..=300)
        .map(|j| {
            let th = 2.0 * PI * j as f64 / 100.0;
            [r * th.cos() - r, 0.5 * r * (2.0 * th).sin(), h_for(n)]
        })
        .collect();
    let (_, out, diss) = run(&c, &path);
    assert_eq!(diss, 0.0);
    let mut work = 0.0;
    for (j, w) in path.windows(2).enumerate() {
        let (f0, f1) = (out[j].force, out[j + 1].force);
        work += 0.5 * (f1[0] + f0[0]) * (w[1][0] - w[0][0]);
        work += 0.5 * (f1[1] + f0[1]) * (w[1][1] - w[0][1]);
    }
    assert!(work.abs() < 1e-12 * K_T * r * r, "{work}");
    assert!(out.iter().all(|o| o.regime == Regime::Stick));
}

#[test]
fn mindlin_cells_on_a_straight_path_approach_mindlin_masing_as_cells_are_added() {
    // Energy per cycle of the cells on a straight path vs the 1D Masing–Mindlin loop,
    // 4H(A) (model.md §4), worst over A/δ* = 10^(k/20) ∈ [0.01, 3.2] (the table of
    // docs/contact3d.md §2; `--nocapture` prints it): 19 %, 4.4 %, 1.2 %, 0.27 % for 16, 32,
    // 64, 128 cells, falling like n⁻².
    let n = 2.0;
    let b = Backbone::new(TangentialLaw::Mindlin, MU * n, K_T).unwrap();
    let delta = b.slip_limit();
    let counts = [16, 32, 64, 128];
    let mut worst = [0.0f64; 4];
    for (i, cells) in counts.into_iter().enumerate() {
        let c = contact(Tangential3d::MindlinMasing { cells });
        for k in -40..=10 {
            let a = 10f64.powf(k as f64 / 20.0) * delta;
            let d = describe(&c, n, [a, 0.0], 1.0).unwrap();
            let exact = 4.0 * b.iwan_dissipation(a);
            worst[i] = worst[i].max((d.energy_per_cycle - exact).abs() / exact);
        }
        println!(
            "{cells} cells: worst relative energy error {:.2e}",
            worst[i]
        );
    }
    for (w, bound) in worst.iter().zip([0.2, 0.05, 0.013, 0.003]) {
        assert!(*w < bound, "{worst:?}");
    }
    assert!(
        worst[3] < 0.3 * worst[2] && worst[2] < 0.3 * worst[1],
        "{worst:?}"
    );
}

#[test]
fn describing_function_of_a_unit_cell_matches_its_closed_forms() {
    // The ODE integration on a circle and on a line against the closed forms.
    for r in [1.2, 3.0] {
        let (h, ok) = cell_on_ellipse(r, r);
        let exact = unit_cell(r, r);
        assert!(ok);
        for (x, y) in [
            (h.c1, exact.c1),
            (h.s1, exact.s1),
            (h.c2, exact.c2),
            (h.s2, exact.s2),
        ] {
            assert!((x - y).abs() < 1e-9, "{r}: {x} vs {y}");
        }
        assert!((h.energy - exact.energy).abs() < 1e-9 * exact.energy);
        let (l, ok) = cell_on_ellipse(r, 0.0);
        let exact = unit_cell(r, 0.0);
        assert!(ok);
        assert!((l.c1 - exact.c1).abs() < 1e-9 && (l.s1 - exact.s1).abs() < 1e-9);
        assert!((l.energy - exact.energy).abs() < 1e-9 * exact.energy);
    }
}

#[test]
fn describing_function_matches_stepping_over_a_cycle() {
    // Jenkins and 8 Mindlin cells on ellipses: energy per cycle and first harmonics of
    // the stepped element (8192 steps per cycle) within 1e-6. (Stick–slip switches fall
    // anywhere inside the steps, so the O(Δθ²) error is not smooth enough for Richardson.)
    let n = 2.0;
    let x = MU * n / K_T;
    for (model, shapes) in [
        (Tangential3d::Jenkins, [(3.0, 1.5), (1.5, 2.5), (1.1, 0.3)]),
        (
            Tangential3d::MindlinMasing { cells: 8 },
            [(0.5, 0.3), (2.0, 1.0), (0.2, 0.9)],
        ),
    ] {
        let c = contact(model);
        for (a, b) in shapes {
            let (a, b) = (a * x, b * x);
            let d = describe(&c, n, [a, b], 1.0).unwrap();
            let (e, h) = steady_cycle(&c, h_for(n), a, b, 8192, 400);
            let scale = MU * n;
            assert!(
                (e - d.energy_per_cycle).abs() < 1e-6 * d.energy_per_cycle,
                "{model:?} {a} {b}: {e} vs {}",
                d.energy_per_cycle
            );
            // First harmonics (force units) within 1e-6 μN.
            let pairs = [
                (h[0], d.k_star[0] * a),
                (-h[1], d.d_star[0] * a),
                (h[3], d.k_star[1] * b),
                (h[2], d.d_star[1] * b),
            ];
            for (i, (stepped, described)) in pairs.into_iter().enumerate() {
                assert!(
                    (stepped - described).abs() < 1e-6 * scale,
                    "{model:?} {a} {b} harmonic {i}: {stepped} vs {described}"
                );
            }
        }
    }
}

#[test]
fn stepping_converges_at_second_order_in_the_step() {
    // Polygon error of the exact segment update on an ellipse: halving Δθ quarters it.
    let n = 2.0;
    let x = MU * n / K_T;
    let c = contact(Tangential3d::Jenkins);
    let exact = describe(&c, n, [3.0 * x, 1.5 * x], 1.0)
        .unwrap()
        .energy_per_cycle;
    let errs: Vec<f64> = [64, 128, 256, 512]
        .iter()
        .map(|&s| (steady_cycle(&c, h_for(n), 3.0 * x, 1.5 * x, s, 12).0 - exact).abs())
        .collect();
    for w in errs.windows(2) {
        let rate = (w[0] / w[1]).log2();
        assert!((1.7..2.3).contains(&rate), "{errs:?}");
    }
}

#[test]
fn normal_load_variation_converges_with_the_step() {
    // In-phase normal and tangential motion (N oscillates with u₁ on a circle): the energy
    // per cycle converges as the step is refined (first order: the limit is taken at the
    // end of each step).
    let c = contact(Tangential3d::Jenkins);
    let x = MU * 2.0 / K_T;
    let run_with = |steps: usize| -> f64 {
        let mut st = State3d::default();
        let mut e = 0.0;
        for cyc in 0..6 {
            e = 0.0;
            for j in 1..=steps {
                let th = 2.0 * PI * j as f64 / steps as f64;
                let h = h_for(2.0) * (1.0 + 0.5 * th.cos());
                let amp = if cyc == 0 {
                    j as f64 / steps as f64
                } else {
                    1.0
                };
                let (next, r) = c
                    .step(&st, [2.0 * x * amp * th.cos(), 2.0 * x * amp * th.sin(), h])
                    .unwrap();
                st = next;
                e += r.dissipated;
            }
        }
        e
    };
    let e: Vec<f64> = [256, 512, 1024, 2048]
        .iter()
        .map(|&s| run_with(s))
        .collect();
    let d1 = (e[1] - e[0]).abs();
    let d2 = (e[2] - e[1]).abs();
    let d3 = (e[3] - e[2]).abs();
    assert!(d2 < 0.7 * d1 && d3 < 0.7 * d2, "{e:?}");
}

#[test]
fn hard_inputs_give_named_errors() {
    let c = contact(Tangential3d::Jenkins);
    let st = State3d::default();
    assert!(matches!(
        c.step(&st, [f64::NAN, 0.0, 0.0]),
        Err(crate::Error::NonFinite(_))
    ));
    assert!(matches!(
        c.step(&st, [0.0, 0.0, f64::INFINITY]),
        Err(crate::Error::NonFinite(_))
    ));
    assert!(matches!(
        c.step(&st, [1e306, 0.0, 1.0]),
        Err(crate::Error::Overflow(_))
    ));
    let bad = Contact3d { mu: -1.0, ..c };
    assert!(matches!(
        bad.step(&st, [0.0; 3]),
        Err(crate::Error::OutOfRange(_))
    ));
    let bad = contact(Tangential3d::MindlinMasing { cells: 0 });
    assert!(bad.step(&st, [0.0; 3]).is_err());
    // State round trip and corrupt blocks.
    let c8 = contact(Tangential3d::MindlinMasing { cells: 8 });
    let (s1, _) = c8.step(&st, [1e-3, 2e-3, 1e-3]).unwrap();
    let mut buf = [0.0; STATE3D_LEN];
    s1.write(8, &mut buf);
    assert_eq!(State3d::read(&buf, 8).unwrap(), s1);
    assert!(State3d::read(&buf, 4).is_err());
    buf[STATE3D_LEN - 1] = 1.0;
    assert!(State3d::read(&buf, 8).is_err());
    // Describing function: negative amplitude, zero ω, open contact.
    assert!(describe(&c, 1.0, [-1.0, 0.0], 1.0).is_err());
    assert!(describe(&c, 1.0, [1.0, 0.0], 0.0).is_err());
    let open = describe(&c, -1.0, [1.0, 1.0], 1.0).unwrap();
    assert_eq!((open.k_star, open.regime), ([0.0; 2], Regime::Open));
}

#[test]
fn describing_function_is_fast_and_finite_for_a_vanishing_normal_load_and_continuous_at_the_rigid_limit(
) {
    use super::describing::RIGID_RATIO;
    // Just below and above the ratio where a cell is taken as rigid–plastic: the time
    // integration and the rigid–plastic sums agree to the O(x/R) of the model switch.
    // The switch is at the path's smallest radius of curvature min²/max = RIGID_RATIO.
    for (a, b) in [(1.0, 0.5), (1.0, 1.0), (0.5, 1.0)] {
        let scale = RIGID_RATIO * f64::max(a, b) / f64::min(a, b).powi(2);
        let below = cell_on_ellipse(0.999 * scale * a, 0.999 * scale * b).0;
        let above = unit_cell(1.001 * scale * a, 1.001 * scale * b);
        for (x, y) in [
            (below.c1, above.c1),
            (below.s1, above.s1),
            (below.c2, above.c2),
            (below.s2, above.s2),
        ] {
            assert!((x - y).abs() < 3e-4, "{a} {b}: {x} vs {y}");
        }
        // The energy grows with the path: compare per unit of the scale factor.
        let (eb, ea) = (below.energy / 0.999, above.energy / 1.001);
        assert!((eb - ea).abs() < 3e-4 * ea, "{a} {b}: {eb} vs {ea}");
    }
    let c = contact(Tangential3d::MindlinMasing { cells: 32 });
    for n in [1e-3, 1e-300] {
        let d = describe(&c, n, [1e-3, 4e-4], 1.0).unwrap();
        assert!(d
            .k_star
            .iter()
            .chain(&d.d_star)
            .all(|v| v.is_finite() && *v >= -1e-12 * K_T));
        assert!(d.energy_per_cycle <= 2.0 * PI * 1e-3 * MU * n * 1.0001);
    }
    // A straight path along direction 2 is the line's loop.
    let j = contact(Tangential3d::Jenkins);
    let along1 = describe(&j, 2.0, [3e-3, 0.0], 1.0).unwrap();
    let along2 = describe(&j, 2.0, [0.0, 3e-3], 1.0).unwrap();
    assert!((along1.k_star[0] - along2.k_star[1]).abs() < 1e-12 * K_T);
    assert!((along1.d_star[0] - along2.d_star[1]).abs() < 1e-12 * K_T);
    assert_eq!(along1.energy_per_cycle, along2.energy_per_cycle);
}

#[test]
fn the_stiffness_is_the_steps_derivative_after_the_normal_load_dropped() {
    // Slide along t₁ at N = 10 (|t| = μN = 5), then in one step the load drops to N = 8
    // (radial return to 4) while the displacement moves back by 2e-3 (elastic: 4 − 2 = 2,
    // inside the circle). The step's force is then k_T0 · Δu from the returned force, so
    // its derivative is k_T0 I; it used to be reported as the slip tangent k(I − t̂t̂ᵀ) with
    // the μ k_N coupling, because the cell had slipped (returned) during the step. A
    // Newton iteration in the time domain converged only linearly on such points.
    let c = contact(Tangential3d::Jenkins);
    let (st, _, _) = run(&c, &[[0.01, 0.0, h_for(10.0)], [0.02, 0.0, h_for(10.0)]]);
    let to = [0.018, 0.0005, h_for(8.0)];
    let (_, r) = c.step(&st, to).unwrap();
    assert!(
        r.force[0].hypot(r.force[1]) < MU * 8.0 * 0.9,
        "{:?}",
        r.force
    );
    let eps = 1e-9;
    for b in 0..3 {
        let mut d = to;
        d[b] += eps;
        let (_, r1) = c.step(&st, d).unwrap();
        for a in 0..3 {
            let fd = (r1.force[a] - r.force[a]) / eps;
            assert!(
                (fd - r.stiffness[a][b]).abs() <= 1e-5 * K_N,
                "∂F{a}/∂d{b}: reported {} vs {fd}",
                r.stiffness[a][b]
            );
        }
    }
}
