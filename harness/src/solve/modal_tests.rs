//! Tests of the shift-invert modal solver ([`super`]).

use super::*;
use crate::fe::assembly::assemble;
use crate::fe::csc::CscPattern;
use crate::fe::elements::ElementKind;
use crate::fe::mesh::{BoxSpec, Face, Material, Model};
use nalgebra::DVector;
use std::sync::Arc;

/// Units N, mm, s, t: E in MPa, ρ in t/mm³, λ in (rad/s)².
fn steel() -> Material {
    Material::new(210_000.0, 0.3, 7.85e-9).unwrap()
}

fn cantilever(kind: ElementKind, nx: usize) -> (f64, f64, Modes) {
    let (l, b) = (100.0, 4.0);
    let mut model = Model::new(vec![steel()]);
    model
        .add_box(BoxSpec {
            origin: [0.0; 3],
            size: [l, b, b],
            divisions: [nx, 2, 2],
            material: 0,
        })
        .unwrap();
    let clamp = model.bodies[0].face_nodes(Face::XMin);
    model.fix(&clamp, [true; 3]).unwrap();
    for e in &mut model.elements {
        e.kind = kind;
    }
    let sys = assemble(&model, &[]).unwrap();
    let modes = lowest_modes(
        &sys.k,
        &sys.m,
        &ModalOptions {
            n_modes: 2,
            ..Default::default()
        },
    )
    .unwrap();
    // Euler–Bernoulli: f₁ = (1.8751²/2π) √(EI/(ρAL⁴)), I = b⁴/12, A = b².
    let (e, rho) = (210_000.0, 7.85e-9);
    let i = b.powi(4) / 12.0;
    let beta = 1.875_104_068_711_961;
    let f_eb =
        beta * beta / (2.0 * std::f64::consts::PI) * (e * i / (rho * b * b * l.powi(4))).sqrt();
    let f1 = modes.frequencies_hz()[0];
    (f1, f_eb, modes)
}

#[test]
fn cantilever_first_bending_within_1_percent_of_euler_bernoulli() {
    // Steel 100×4×4 mm, 25×2×2 incompatible-mode hex8 (2×2×2 Gauss, 9 condensed
    // bubbles), clamped face x = 0. Measured: f₁ = 335.72 Hz vs 334.21 Hz (EB),
    // +0.45 % (clamped Poisson contraction and discretisation stiffen, shear
    // flexibility softens); limit 1 % as asked of the element.
    let (f1, f_eb, modes) = cantilever(ElementKind::C3D8I, 25);
    let err = (f1 - f_eb) / f_eb;
    eprintln!(
        "cantilever f1 = {f1:.3} Hz, Euler-Bernoulli {f_eb:.3} Hz, error {:+.3} %",
        100.0 * err
    );
    assert!(err.abs() < 0.01, "f1 {f1} vs {f_eb}");
    // Square section: the y- and z-bending modes are a degenerate pair.
    let f = modes.frequencies_hz();
    assert!((f[1] - f[0]).abs() / f[0] < 1e-6, "{f:?}");
    // Every pair an eigenpair to working accuracy (backward error ~1e-16).
    assert!(modes.converged);
    assert!(
        modes.residuals.iter().all(|&r| r < 1e-8),
        "{:?}",
        modes.residuals
    );
}

#[test]
fn full_integration_locks_in_bending() {
    // Same beam, plain trilinear hex8: shear locking makes it far too stiff.
    // Measured: f₁ = 400.1 Hz, +19.7 % (vs +0.45 % with incompatible modes).
    let (f1, f_eb, _) = cantilever(ElementKind::C3D8, 25);
    let err = (f1 - f_eb) / f_eb;
    eprintln!(
        "full integration f1 = {f1:.3} Hz, error {:+.1} %",
        100.0 * err
    );
    assert!(err > 0.1, "full integration only {err} too stiff");
}

fn dense_pattern(n: usize) -> Arc<CscPattern> {
    Arc::new(CscPattern::from_entries(
        n,
        (0..n).flat_map(|j| (0..n).map(move |i| (i, j))),
    ))
}

fn to_csc(a: &DMatrix<f64>, p: &Arc<CscPattern>) -> Csc<f64> {
    let mut c = Csc::zeros(p.clone());
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            c.values[p.find(i, j).unwrap()] = a[(i, j)];
        }
    }
    c
}

#[test]
fn random_pencil_matches_dense_generalized_eigen() {
    // K, M random SPD 40×40; reference: L⁻¹ K L⁻ᵀ eigenvalues (M = LLᵀ), dense.
    let n = 40;
    let mut rng = Rng::new(11);
    let g = DMatrix::from_fn(n, n, |_, _| rng.uniform(-1.0, 1.0));
    let h = DMatrix::from_fn(n, n, |_, _| rng.uniform(-1.0, 1.0));
    let kd = &g * g.transpose() + DMatrix::identity(n, n);
    let md = &h * h.transpose() / n as f64 + DMatrix::identity(n, n);
    let l = md.clone().cholesky().unwrap().l();
    let a = l.solve_lower_triangular(&kd).unwrap();
    let c = l.solve_lower_triangular(&a.transpose()).unwrap();
    let mut reference: Vec<f64> = SymmetricEigen::new((&c + c.transpose()) * 0.5)
        .eigenvalues
        .iter()
        .copied()
        .collect();
    reference.sort_by(f64::total_cmp);
    let p = dense_pattern(n);
    let modes = lowest_modes(
        &to_csc(&kd, &p),
        &to_csc(&md, &p),
        &ModalOptions {
            n_modes: 4,
            ..Default::default()
        },
    )
    .unwrap();
    for i in 0..4 {
        // Residual < 1e-8 ⇒ Rayleigh-quotient eigenvalue error ~1e-16·cond; 1e-10 leaves
        // room for the spread of this random pencil. Measured: 18 iterations.
        approx::assert_relative_eq!(modes.eigenvalues[i], reference[i], max_relative = 1e-10);
        assert!(modes.converged && modes.residuals[i] < 1e-8);
        // M-normalized.
        let phi = DVector::from_column_slice(&modes.shapes[i]);
        approx::assert_relative_eq!((phi.transpose() * &md * &phi)[0], 1.0, max_relative = 1e-10);
    }
}

#[test]
fn free_body_has_six_rigid_modes_with_negative_shift() {
    let mut model = Model::new(vec![steel()]);
    model
        .add_box(BoxSpec {
            origin: [0.0; 3],
            size: [20.0, 4.0, 4.0],
            divisions: [5, 1, 1],
            material: 0,
        })
        .unwrap();
    let sys = assemble(&model, &[]).unwrap();
    let modes = lowest_modes(
        &sys.k,
        &sys.m,
        &ModalOptions {
            n_modes: 7,
            shift: -1e6,
            ..Default::default()
        },
    )
    .unwrap();
    let l7 = modes.eigenvalues[6];
    // Rigid modes: λ = 0 up to round-off relative to the first elastic one.
    for &l in &modes.eigenvalues[..6] {
        assert!(l.abs() < 1e-8 * l7, "{l} vs {l7}");
    }
    assert!(l7 > 1e6);
    // The default shift 0 finds the singular K and shifts by itself (it stopped with
    // "projected mass matrix not positive definite"): the same spectrum.
    let auto = lowest_modes(
        &sys.k,
        &sys.m,
        &ModalOptions {
            n_modes: 9,
            ..Default::default()
        },
    )
    .unwrap();
    for &l in &auto.eigenvalues[..6] {
        assert!(l.abs() < 1e-8 * l7, "{l} vs {l7}");
    }
    approx::assert_relative_eq!(auto.eigenvalues[6], l7, max_relative = 1e-10);
}

/// A cantilever 100×4×4 mm cut at x = 40 into two tied boxes has exactly the
/// frequencies of the uncut one (same nodes, same elements: node merging is exact,
/// so only solver round-off may differ).
#[test]
fn tied_halves_are_one_body() {
    let bx = |m: &mut Model, origin: [f64; 3], size: [f64; 3], divisions: [usize; 3]| {
        m.add_box(BoxSpec {
            origin,
            size,
            divisions,
            material: 0,
        })
        .unwrap()
    };
    let mut one = Model::new(vec![steel()]);
    let b = bx(&mut one, [0.0; 3], [100.0, 4.0, 4.0], [25, 2, 2]);
    let clamp = one.bodies[b].face_nodes(Face::XMin);
    one.fix(&clamp, [true; 3]).unwrap();

    let mut two = Model::new(vec![steel()]);
    let a = bx(&mut two, [0.0; 3], [40.0, 4.0, 4.0], [10, 2, 2]);
    let c = bx(&mut two, [40.0, 0.0, 0.0], [60.0, 4.0, 4.0], [15, 2, 2]);
    let clamp = two.bodies[a].face_nodes(Face::XMin);
    two.fix(&clamp, [true; 3]).unwrap();
    let ties = crate::fe::ties::find_ties(&two, a, c, 1e-6).unwrap();
    assert_eq!(ties.len(), 3 * 3);
    two.ties = ties;

    let opts = ModalOptions {
        n_modes: 4,
        ..Default::default()
    };
    let f = |m: &Model| {
        let s = assemble(m, &[]).unwrap();
        assert_eq!(s.dofs.n_free(), 3 * 26 * 9 - 27);
        lowest_modes(&s.k, &s.m, &opts).unwrap().frequencies_hz()
    };
    for (x, y) in f(&one).iter().zip(f(&two)) {
        approx::assert_relative_eq!(*x, y, max_relative = 1e-8);
    }
}

/// A fixed–fixed chain of `n` unit masses and springs: λⱼ = 4 sin²(jπ / 2(n+1)).
pub(crate) fn chain(n: usize) -> (Csc<f64>, Csc<f64>, Vec<f64>) {
    let p = Arc::new(CscPattern::from_entries(
        n,
        (0..n).flat_map(|j| (j.saturating_sub(1)..(j + 2).min(n)).map(move |i| (i, j))),
    ));
    let (mut k, mut m) = (Csc::zeros(p.clone()), Csc::zeros(p.clone()));
    for j in 0..n {
        k.values[p.find(j, j).unwrap()] = 2.0;
        m.values[p.find(j, j).unwrap()] = 1.0;
        if j + 1 < n {
            k.values[p.find(j, j + 1).unwrap()] = -1.0;
            k.values[p.find(j + 1, j).unwrap()] = -1.0;
        }
    }
    let exact = (1..=n)
        .map(|j| {
            let s = (j as f64 * std::f64::consts::PI / (2.0 * (n + 1) as f64)).sin();
            4.0 * s * s
        })
        .collect();
    (k, m, exact)
}

#[test]
fn any_number_of_modes_up_to_every_dof() {
    // Lanczos (basis 2p + 1 < n) for 40 of 300 modes; the dense route for 70 and all
    // 100 of a 100-DOF chain (a basis of 2p + 1 would span every DOF), where the
    // eigensolver once failed beyond a third of the DOFs.
    for (n, p) in [(300, 40), (100, 70), (100, 100)] {
        let (k, m, exact) = chain(n);
        let modes = lowest_modes(
            &k,
            &m,
            &ModalOptions {
                n_modes: p,
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(modes.eigenvalues.len(), p);
        assert_eq!(modes.solves == 0, 2 * p + 1 >= n, "route for {p} of {n}");
        assert!(modes.converged, "{:?}", modes.residuals);
        for (a, e) in modes.eigenvalues.iter().zip(&exact) {
            approx::assert_relative_eq!(*a, *e, max_relative = 1e-10);
        }
        // M-orthonormal shapes.
        for (i, phi) in modes.shapes.iter().enumerate().step_by(7) {
            let mp = m.mul_vec(phi);
            let norm: f64 = phi.iter().zip(&mp).map(|(a, b)| a * b).sum();
            approx::assert_relative_eq!(norm, 1.0, max_relative = 1e-10);
            let other = &modes.shapes[(i + 1) % p];
            let cross: f64 = other.iter().zip(&mp).map(|(a, b)| a * b).sum();
            assert!(cross.abs() < 1e-8, "φ{i}ᵀMφ = {cross}");
        }
    }
}

#[test]
fn a_lanczos_run_out_of_restarts_says_how_far_it_got() {
    // λᵢ = 1 + 1e-6·i: a cluster the shift-inverted operator barely separates.
    let n = 500;
    let p = Arc::new(CscPattern::from_entries(n, (0..n).map(|j| (j, j))));
    let k = Csc {
        pattern: p.clone(),
        values: (0..n).map(|i| 1.0 + 1e-6 * i as f64).collect(),
    };
    let m = Csc {
        pattern: p,
        values: vec![1.0; n],
    };
    let err = lowest_modes(
        &k,
        &m,
        &ModalOptions {
            n_modes: 30,
            max_restarts: 1,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            ModalError::Lanczos(LanczosError::NotConverged { wanted: 30, .. })
        ),
        "{err}"
    );
    assert!(err.to_string().contains("of 30 eigenpairs"), "{err}");
}
