//! UMFPACK against dense LU on random complex systems, the symmetric strategy, symbolic
//! reuse, singular matrices and wrong lengths as named errors, real SPD matrices.

use super::*;
use crate::util::rng::Rng;
use nalgebra::{DMatrix, DVector};

/// Random n×n complex matrix with ~`per_col` off-diagonal entries per column and a
/// nonzero diagonal of random phase (not diagonally dominant: pivoting matters).
fn random_matrix(rng: &mut Rng, n: usize, per_col: usize) -> Csc<C64> {
    let mut entries = Vec::new();
    for j in 0..n {
        entries.push((j, j));
        for _ in 0..per_col {
            entries.push((rng.below(n), j));
        }
    }
    let pattern = Arc::new(CscPattern::from_entries(n, entries));
    random_values(rng, pattern)
}

fn random_values(rng: &mut Rng, pattern: Arc<CscPattern>) -> Csc<C64> {
    let mut a = Csc::zeros(pattern);
    for v in a.values.iter_mut() {
        *v = C64::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    }
    a
}

fn random_vec(rng: &mut Rng, n: usize) -> Vec<C64> {
    (0..n)
        .map(|_| C64::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)))
        .collect()
}

/// ‖x − x_dense‖ / ‖x_dense‖ against nalgebra's dense partial-pivoting LU.
fn rel_err_vs_dense(a: &Csc<C64>, b: &[C64], x: &[C64]) -> f64 {
    let xd = a
        .to_dense()
        .lu()
        .solve(&DVector::from_column_slice(b))
        .expect("dense LU");
    let diff: f64 = x
        .iter()
        .zip(xd.iter())
        .map(|(p, q)| (p - q).norm_sqr())
        .sum();
    diff.sqrt() / xd.norm()
}

/// Largest relative difference seen in the tests below (measured ~1e-14 … 1e-13 on
/// these random systems; the limit 1e-10 leaves room for condition numbers ~1e4).
const TOL: f64 = 1e-10;

#[test]
fn random_systems_match_dense_lu_with_several_rhs() {
    let mut rng = Rng::new(2024);
    let mut worst: f64 = 0.0;
    for (n, per_col) in [(1, 0), (7, 2), (40, 3), (150, 4)] {
        let a = random_matrix(&mut rng, n, per_col);
        let sym = Symbolic::new(a.pattern.clone()).unwrap();
        let num = sym.factor(&a).unwrap();
        assert!(num.rcond() > 0.0);
        let k = 3;
        let b = random_vec(&mut rng, n * k);
        let x = num.solve_many(&b).unwrap();
        for c in 0..k {
            let (bc, xc) = (&b[c * n..(c + 1) * n], &x[c * n..(c + 1) * n]);
            let err = rel_err_vs_dense(&a, bc, xc);
            // Residual relative to ‖A‖_F ‖x‖: backward error at round-off level.
            let r: f64 = a
                .mul_vec(xc)
                .iter()
                .zip(bc)
                .map(|(p, q)| (p - q).norm_sqr())
                .sum::<f64>()
                .sqrt();
            let an = a.values.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
            let xn = xc.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
            assert!(
                r / (an * xn) < 1e-14,
                "n={n}: backward error {}",
                r / (an * xn)
            );
            worst = worst.max(err);
            assert!(err < TOL, "n={n} rhs {c}: {err}");
        }
    }
    eprintln!("umfpack vs dense LU, worst relative difference {worst:.2e}");
    // Without iterative refinement: still round-off level on these systems.
    let a = random_matrix(&mut rng, 150, 4);
    let mut sym = Symbolic::new(a.pattern.clone()).unwrap();
    sym.set_refinement_steps(0);
    let b = random_vec(&mut rng, 150);
    let x = sym.factor(&a).unwrap().solve(&b).unwrap();
    let err = rel_err_vs_dense(&a, &b, &x);
    assert!(err < TOL, "no refinement: {err}");
}

#[test]
fn the_symmetric_analysis_uses_the_symmetric_strategy() {
    // The automatic choice is unsymmetric for this pattern (as for the knife's
    // static tangent, see `Symbolic::symmetric`); both solve it.
    let mut rng = Rng::new(7);
    let a = random_matrix(&mut rng, 40, 3);
    let b = random_vec(&mut rng, 40);
    let auto = Symbolic::new(a.pattern.clone()).unwrap();
    let sym = Symbolic::symmetric(a.pattern.clone()).unwrap();
    assert_eq!(auto.strategy_used, 1.0);
    assert_eq!(sym.strategy_used, ffi::UMFPACK_STRATEGY_SYMMETRIC);
    for s in [&auto, &sym] {
        let x = s.factor(&a).unwrap().solve(&b).unwrap();
        assert!(rel_err_vs_dense(&a, &b, &x) < TOL);
    }
}

#[test]
fn symbolic_is_reused_for_new_values() {
    let mut rng = Rng::new(99);
    let a1 = random_matrix(&mut rng, 60, 3);
    let sym = Symbolic::new(a1.pattern.clone()).unwrap();
    let b = random_vec(&mut rng, 60);
    let x1 = sym.factor(&a1).unwrap().solve(&b).unwrap();
    assert!(rel_err_vs_dense(&a1, &b, &x1) < TOL);
    // New values, same pattern object, same Symbolic: several "frequencies".
    let mut a2 = Csc::zeros(a1.pattern.clone());
    for step in 0..3 {
        for (v2, v1) in a2.values.iter_mut().zip(&a1.values) {
            *v2 = v1 * C64::new(1.0 + step as f64, 0.3) + C64::new(rng.uniform(-0.5, 0.5), 0.0);
        }
        let x2 = sym.factor(&a2).unwrap().solve(&b).unwrap();
        let err = rel_err_vs_dense(&a2, &b, &x2);
        assert!(err < TOL, "step {step}: {err}");
        let moved: f64 = x1.iter().zip(&x2).map(|(p, q)| (p - q).norm()).sum();
        assert!(moved > 1e-3, "solution did not change with the values");
    }
    // An equal pattern in a different Arc is accepted too; a different one is not.
    let copy = Csc {
        pattern: Arc::new((*a1.pattern).clone()),
        values: a1.values.clone(),
    };
    assert!(sym.factor(&copy).is_ok());
    let other = random_matrix(&mut rng, 60, 3);
    assert_eq!(
        sym.factor(&other).err(),
        Some(UmfpackError::PatternMismatch)
    );
}

#[test]
fn singular_matrix_is_a_named_error() {
    // Rows 0 and 1 equal: numerically singular, structurally fine.
    let p = Arc::new(CscPattern::from_entries(
        3,
        [(0, 0), (1, 0), (0, 1), (1, 1), (2, 2), (0, 2), (1, 2)],
    ));
    let mut a = Csc::zeros(p.clone());
    for (slot, v) in [
        ((0, 0), 1.0),
        ((1, 0), 1.0),
        ((0, 1), 2.0),
        ((1, 1), 2.0),
        ((2, 2), 3.0),
        ((0, 2), 1.0),
        ((1, 2), 1.0),
    ] {
        a.values[p.find(slot.0, slot.1).unwrap()] = C64::new(v, 0.5 * v);
    }
    let sym = Symbolic::new(p.clone()).unwrap();
    let err = sym.factor(&a).unwrap_err();
    assert_eq!(
        err,
        UmfpackError::Singular {
            call: "umfpack_zl_numeric",
            code: 1
        }
    );
    assert!(err.to_string().contains("UMFPACK_WARNING_singular_matrix"));
    // Structurally singular: an empty column.
    let p2 = Arc::new(CscPattern::from_entries(2, [(0, 0), (1, 0)]));
    let mut a2 = Csc::zeros(p2.clone());
    a2.values.fill(C64::new(1.0, 0.0));
    let sym2 = Symbolic::new(p2).unwrap();
    assert!(matches!(
        sym2.factor(&a2),
        Err(UmfpackError::Singular { .. })
    ));
}

#[test]
fn wrong_lengths_and_empty_are_errors() {
    let mut rng = Rng::new(5);
    let a = random_matrix(&mut rng, 5, 1);
    let sym = Symbolic::new(a.pattern.clone()).unwrap();
    let num = sym.factor(&a).unwrap();
    assert_eq!(
        num.solve(&[C64::new(1.0, 0.0); 4]).err(),
        Some(UmfpackError::Length { got: 4, n: 5 })
    );
    assert!(num.solve_many(&[C64::new(1.0, 0.0); 7]).is_err());
    let empty = Arc::new(CscPattern::from_entries(0, []));
    assert_eq!(Symbolic::<C64>::new(empty).err(), Some(UmfpackError::Empty));
}

#[test]
fn real_spd_matrix_through_complex_interface() {
    // Dense SPD 30×30 (all entries stored) via to_complex vs nalgebra Cholesky.
    let mut rng = Rng::new(3);
    let n = 30;
    let g = DMatrix::from_fn(n, n, |_, _| rng.uniform(-1.0, 1.0));
    let s = &g * g.transpose() + DMatrix::identity(n, n) * n as f64;
    let p = Arc::new(CscPattern::from_entries(
        n,
        (0..n).flat_map(|j| (0..n).map(move |i| (i, j))),
    ));
    let mut a = Csc::<f64>::zeros(p.clone());
    for j in 0..n {
        for i in 0..n {
            a.values[p.find(i, j).unwrap()] = s[(i, j)];
        }
    }
    let ac = to_complex(&a);
    let sym = Symbolic::new(p).unwrap();
    let b: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
    let bc: Vec<C64> = b.iter().map(|&v| C64::new(v, 0.0)).collect();
    let x = sym.factor(&ac).unwrap().solve(&bc).unwrap();
    let xr = s.cholesky().unwrap().solve(&DVector::from_vec(b));
    for i in 0..n {
        assert!((x[i].re - xr[i]).abs() < TOL * xr.norm());
        assert!(x[i].im.abs() < TOL * xr.norm());
    }
}

#[test]
fn real_interface_solves_as_the_complex_one_and_names_its_errors() {
    // A random sparse real system: umfpack_dl against umfpack_zl on the same values.
    let mut rng = Rng::new(11);
    let c = random_matrix(&mut rng, 40, 4);
    let a = Csc {
        pattern: c.pattern.clone(),
        values: c.values.iter().map(|v| v.re).collect::<Vec<f64>>(),
    };
    let b: Vec<f64> = (0..40).map(|i| (0.3 * i as f64).sin()).collect();
    let real = Symbolic::<f64>::new(a.pattern.clone()).unwrap();
    let x = real.factor(&a).unwrap().solve(&b).unwrap();
    let complex = Symbolic::new(a.pattern.clone()).unwrap();
    let bc: Vec<C64> = b.iter().map(|&v| C64::new(v, 0.0)).collect();
    let xc = complex.factor(&to_complex(&a)).unwrap().solve(&bc).unwrap();
    let scale = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (r, z) in x.iter().zip(&xc) {
        assert!((r - z.re).abs() < 1e-12 * scale, "{r} vs {z}");
    }
    // Its residual, independently: ‖A x − b‖ at round-off.
    let ax = a.mul_vec(&x);
    let res = ax
        .iter()
        .zip(&b)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max);
    assert!(res < 1e-12 * scale.max(1.0), "residual {res}");
    // A singular real matrix is the named error of the real family.
    let p = Arc::new(CscPattern::from_entries(
        2,
        [(0, 0), (1, 0), (0, 1), (1, 1)],
    ));
    let s = Csc {
        pattern: p.clone(),
        values: vec![1.0, 2.0, 2.0, 4.0],
    };
    let sym = Symbolic::<f64>::new(p).unwrap();
    assert_eq!(
        sym.factor(&s).unwrap_err(),
        UmfpackError::Singular {
            call: "umfpack_dl_numeric",
            code: 1
        }
    );
}

#[test]
fn the_adjoint_solve_and_the_condition_estimate_match_the_dense_inverse() {
    let mut rng = Rng::new(77);
    for (n, per_col) in [(1, 0), (12, 2), (60, 3)] {
        let a = random_matrix(&mut rng, n, per_col);
        let sym = Symbolic::new(a.pattern.clone()).unwrap();
        let num = sym.factor(&a).unwrap();
        let dense = a.to_dense();
        // Aᴴ x = b.
        let b = random_vec(&mut rng, n);
        let mut x = vec![C64::new(0.0, 0.0); n];
        num.solve_adjoint_into(&b, &mut x).unwrap();
        let xd = dense
            .adjoint()
            .lu()
            .solve(&DVector::from_column_slice(&b))
            .unwrap();
        let err = x
            .iter()
            .zip(xd.iter())
            .map(|(p, q)| (p - q).norm_sqr())
            .sum::<f64>();
        assert!(err.sqrt() <= TOL * xd.norm(), "n={n}: adjoint solve");
        // κ₁⁻¹ = 1/(‖A‖₁‖A⁻¹‖₁): the estimate of ‖A⁻¹‖₁ is a lower bound, within 3.
        let norm1 = |m: &DMatrix<C64>| {
            (0..m.ncols())
                .map(|j| m.column(j).iter().map(|v| v.norm()).sum::<f64>())
                .fold(0.0f64, f64::max)
        };
        let inverse = dense.clone().try_inverse().unwrap();
        let exact = 1.0 / (norm1(&dense) * norm1(&inverse));
        let estimate = num.rcond1_estimate().unwrap();
        assert!(
            estimate >= exact * (1.0 - 1e-10) && estimate <= 3.0 * exact,
            "n={n}: estimate {estimate:e}, exact {exact:e}"
        );
    }
}

#[test]
fn the_condition_estimate_holds_on_a_long_chain() {
    // A fixed–free chain of n unit springs with small damped masses, K − ω²M below its
    // first eigenfrequency: regular, 1-norm condition ~n² (3e5 here); the estimate
    // stays within 3 of the exact one.
    let n = 400;
    let mut entries = Vec::new();
    for j in 0..n {
        entries.push((j, j));
        if j > 0 {
            entries.push((j - 1, j));
            entries.push((j, j - 1));
        }
    }
    let pattern = Arc::new(CscPattern::from_entries(n, entries));
    let mut a = Csc::zeros(pattern.clone());
    for j in 0..n {
        for k in pattern.col_ptr[j] as usize..pattern.col_ptr[j + 1] as usize {
            let i = pattern.row_idx[k] as usize;
            a.values[k] = match i == j {
                true if j + 1 < n => C64::new(2.0 - 1e-7, 1e-9),
                true => C64::new(1.0 - 1e-7, 1e-9),
                false => C64::new(-1.0, 0.0),
            };
        }
    }
    let sym = Symbolic::new(pattern).unwrap();
    let num = sym.factor(&a).unwrap();
    let dense = a.to_dense();
    let norm1 = |m: &DMatrix<C64>| {
        (0..m.ncols())
            .map(|j| m.column(j).iter().map(|v| v.norm()).sum::<f64>())
            .fold(0.0f64, f64::max)
    };
    let exact = 1.0 / (norm1(&dense) * norm1(&dense.clone().try_inverse().unwrap()));
    let estimate = num.rcond1_estimate().unwrap();
    assert!(estimate >= exact * (1.0 - 1e-10) && estimate <= 3.0 * exact);
}

#[test]
fn the_row_equilibrated_estimate_matches_the_dense_one_and_ignores_row_scales() {
    // κ₁(DA)⁻¹ with D = diag(1/Σⱼ|aᵢⱼ|): within 3 of the exact value (an upper
    // estimate), and the same after every row of A is multiplied by 10^(±8): a
    // stiff equation is not a near-singular one.
    let mut rng = Rng::new(91);
    let norm1 = |m: &DMatrix<C64>| {
        (0..m.ncols())
            .map(|j| m.column(j).iter().map(|v| v.norm()).sum::<f64>())
            .fold(0.0f64, f64::max)
    };
    for (n, per_col) in [(1, 0), (12, 2), (60, 3)] {
        let a = random_matrix(&mut rng, n, per_col);
        let mut scaled = a.clone();
        let p = a.pattern.clone();
        for j in 0..n {
            for k in p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize {
                let i = p.row_idx[k] as usize;
                scaled.values[k] *= if i.is_multiple_of(2) { 1e8 } else { 1e-8 };
            }
        }
        let sym = Symbolic::new(p).unwrap();
        let (num, num_scaled) = (sym.factor(&a).unwrap(), sym.factor(&scaled).unwrap());
        let mut da = a.to_dense();
        for mut row in da.row_iter_mut() {
            let sum: f64 = row.iter().map(|v| v.norm()).sum();
            row /= C64::new(sum, 0.0);
        }
        let exact = 1.0 / (norm1(&da) * norm1(&da.clone().try_inverse().unwrap()));
        let (e, e_scaled) = (
            num.rcond1_row_equilibrated_estimate().unwrap(),
            num_scaled.rcond1_row_equilibrated_estimate().unwrap(),
        );
        assert!(
            e >= exact * (1.0 - 1e-10) && e <= 3.0 * exact,
            "n={n}: {e:e} vs {exact:e}"
        );
        assert!(
            (e_scaled / e - 1.0).abs() < 1e-6,
            "n={n}: {e_scaled:e} vs {e:e}"
        );
        // The unscaled 1-norm estimate sees the 1e16 between the rows.
        if n > 1 {
            assert!(num_scaled.rcond1_estimate().unwrap() < 1e-10 * e);
        }
    }
}
