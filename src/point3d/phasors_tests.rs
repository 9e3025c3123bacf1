use std::f64::consts::PI;

use super::describing::Method;
use super::phasors::{describe_phasors, ellipse};
use super::table::TABLE_TOLERANCE;
use super::tests::{contact, K_N, K_T, MU};
use super::*;
use crate::iterate::Complex64;

/// Normal force (force): x = μN/k_T0 = 1e-3 length for a Jenkins point.
const N: f64 = 2.0;

/// û = e^{iθ₀} R(φ) (A₁, −iA₂): the ellipse of semi-axes A₁, A₂ turned by φ, started at
/// phase θ₀.
fn phasors(a1: f64, a2: f64, phi: f64, theta0: f64) -> [Complex64; 2] {
    let shift = Complex64::from_polar(1.0, theta0);
    let v = [Complex64::new(a1, 0.0), Complex64::new(0.0, -a2)];
    let (s, c) = phi.sin_cos();
    [(v[0] * c - v[1] * s) * shift, (v[0] * s + v[1] * c) * shift]
}

/// Steps the point along u(θ) = Re(û e^{iθ}) from a virgin start (straight ramp to u(0))
/// until the sliders repeat; the last cycle's complex force harmonics
/// t̂ⱼ = (1/π)∮ tⱼ e^{−iθ} dθ (force) and energy.
fn stepped(c: &Contact3d, u: [Complex64; 2], steps: usize) -> ([Complex64; 2], f64) {
    let h = N / K_N;
    let at = |th: f64| {
        let e = Complex64::from_polar(1.0, th);
        [(u[0] * e).re, (u[1] * e).re, h]
    };
    let (mut st, _) = c.step(&State3d::default(), at(0.0)).unwrap();
    let (mut harm, mut energy) = ([Complex64::new(0.0, 0.0); 2], 0.0);
    for _ in 0..400 {
        let start = st;
        (harm, energy) = ([Complex64::new(0.0, 0.0); 2], 0.0);
        for j in 1..=steps {
            let th = 2.0 * PI * j as f64 / steps as f64;
            let (next, r) = c.step(&st, at(th)).unwrap();
            st = next;
            energy += r.dissipated;
            let w = Complex64::from_polar(2.0 / steps as f64, -th);
            harm[0] += w * r.force[0];
            harm[1] += w * r.force[1];
        }
        let moved = (0..c.cell_count())
            .flat_map(|i| (0..2).map(move |k| (i, k)))
            .map(|(i, k)| (st.sliders[i][k] - start.sliders[i][k]).abs())
            .fold(0.0, f64::max);
        if moved < 1e-13 * u[0].norm().max(u[1].norm()) {
            break;
        }
    }
    (harm, energy)
}

fn force(m: &phasors::DescribingMatrix, u: [Complex64; 2], omega: f64) -> [Complex64; 2] {
    std::array::from_fn(|i| {
        (0..2)
            .map(|j| Complex64::new(m.k_star[i][j], omega * m.d_star[i][j]) * u[j])
            .sum()
    })
}

#[test]
fn the_ellipse_of_two_phasors_is_recovered_turned_and_shifted() {
    for (a1, a2, phi, th) in [
        (3.0, 1.0, 0.4, 1.1),
        (2.0, 2.0, -1.0, 0.3),
        (5.0, 0.0, 1.2, -2.0),
        (1.0, 1e-12, -0.7, 0.5),
        (1e300, 3e299, 0.2, 2.5),
    ] {
        let (axes, angle) = ellipse(phasors(a1, a2, phi, th));
        assert!((axes[0] - a1).abs() <= 1e-14 * a1, "{axes:?}");
        // The phasors carry round-off of 1e-16 a1 from their construction.
        assert!((axes[1] - a2).abs() <= 1e-13 * a1, "{axes:?} vs {a2}");
        if a1 != a2 {
            let d = (angle - phi).rem_euclid(PI);
            assert!(d.min(PI - d) < 1e-9, "{angle} vs {phi}");
        }
    }
}

/// The matrices give the stepped point's first harmonics on turned, phase-shifted
/// ellipses (Jenkins and 8 Mindlin cells, 8192 steps per cycle): integrated within 1e-6
/// μN, tabulated within TABLE_TOLERANCE μN; energies likewise.
#[test]
fn the_matrix_describing_function_is_the_stepped_point_on_any_ellipse() {
    let x = MU * N / K_T;
    let omega = 7.0;
    for (model, paths) in [
        (
            Tangential3d::Jenkins,
            [(3.0, 1.5, 0.6, 0.9), (1.1, 0.3, -1.2, 2.0)],
        ),
        (
            Tangential3d::MindlinMasing { cells: 8 },
            [(2.0, 1.0, 0.3, -0.4), (0.9, 0.2, 2.0, 1.0)],
        ),
    ] {
        let c = contact(model);
        for (a1, a2, phi, th) in paths {
            let u = phasors(a1 * x, a2 * x, phi, th);
            let (h, e) = stepped(&c, u, 8192);
            for (method, tol) in [
                (Method::Integrated, 1e-6),
                (Method::Tabulated, TABLE_TOLERANCE),
            ] {
                let m = describe_phasors(&c, N, u, omega, method).unwrap();
                let t = force(&m, u, omega);
                for j in 0..2 {
                    assert!(
                        (t[j] - h[j]).norm() < tol * MU * N,
                        "{model:?} {method:?} ({a1}, {a2}) direction {j}: {} vs {}",
                        t[j],
                        h[j]
                    );
                }
                let perimeter = 2.0 * PI * a1 * x;
                assert!(
                    (m.energy_per_cycle - e).abs() < tol * MU * N * perimeter,
                    "{model:?} {method:?}: {} vs {e}",
                    m.energy_per_cycle
                );
                for k in [m.k_star, m.d_star] {
                    assert_eq!(k[0][1], k[1][0]);
                }
            }
        }
    }
}

/// A straight path gets the 1D element along it and, across it, the thin path's limit (a
/// positive stiffness, continuous with slightly open ellipses), not 0.
#[test]
fn a_straight_path_keeps_a_sideways_stiffness() {
    let c = contact(Tangential3d::MindlinMasing { cells: 32 });
    let x = MU * N / K_T;
    for method in [Method::Integrated, Method::Tabulated] {
        let line = describe_phasors(&c, N, phasors(2.0 * x, 0.0, 0.0, 0.3), 1.0, method).unwrap();
        let thin =
            describe_phasors(&c, N, phasors(2.0 * x, 2e-5 * x, 0.0, 0.3), 1.0, method).unwrap();
        let side = line.k_star[1][1];
        assert!(side > 0.0 && side <= K_T, "{method:?}: {side}");
        assert!(
            (thin.k_star[1][1] - side).abs() < 1e-3 * K_T,
            "{method:?}: {} vs {side}",
            thin.k_star[1][1]
        );
        // Along the line: the 1D Mindlin–Masing cells' k*.
        let along = super::describing::describe(&c, N, [2.0 * x, 0.0], 1.0).unwrap();
        assert!((line.k_star[0][0] - along.k_star[0]).abs() < 1e-3 * K_T);
    }
}

/// Hard inputs: no motion is stick (k_T0 I), an open point is all zeros, amplitudes up to
/// 1e300 stay finite, non-finite phasors are refused.
#[test]
fn hard_phasors_give_finite_matrices_or_named_errors() {
    let c = contact(Tangential3d::MindlinMasing { cells: 32 });
    for method in [Method::Integrated, Method::Tabulated] {
        let zero = [Complex64::new(0.0, 0.0); 2];
        let m = describe_phasors(&c, N, zero, 1.0, method).unwrap();
        assert_eq!(m.k_star, [[K_T, 0.0], [0.0, K_T]]);
        let open = describe_phasors(&c, 0.0, phasors(1.0, 0.5, 0.1, 0.0), 1.0, method).unwrap();
        assert_eq!(open.k_star, [[0.0; 2]; 2]);
        for scale in [1e-300, 1e-3, 1e300] {
            let m = describe_phasors(&c, N, phasors(scale, 0.3 * scale, 0.5, 1.0), 1.0, method)
                .unwrap();
            assert!(m
                .k_star
                .iter()
                .chain(&m.d_star)
                .flatten()
                .all(|v| v.is_finite()));
            assert!(
                m.energy_per_cycle.is_finite() && m.energy_per_cycle >= 0.0,
                "{method:?} {scale}: {m:?}"
            );
        }
        let nan = [Complex64::new(f64::NAN, 0.0), Complex64::new(0.0, 0.0)];
        assert!(describe_phasors(&c, N, nan, 1.0, method).is_err());
        assert!(describe_phasors(&c, N, phasors(1.0, 0.5, 0.1, 0.0), 0.0, method).is_err());
    }
}
