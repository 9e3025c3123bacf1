//! Linear isotropic elastic 8-node hexahedron: stiffness with incompatible modes
//! (default) or plain full integration, and the consistent mass matrix.
//!
//! Element DOF order: node i (C3D8 order, see [`crate::fe::mesh`]), component c →
//! local DOF `3i + c`. Strains in Voigt order (εxx, εyy, εzz, γxy, γyz, γzx), engineering
//! shear strains (γ = 2ε). Stiffness in force/length, mass in mass units.
//!
//! Incompatible modes (Wilson, Taylor, Doherty, Ghaboussi 1973; Taylor, Beresford,
//! Wilson 1976, the "QM6" idea in 3D): u = Σᵢ Nᵢ uᵢ + Σₐ Pₐ αₐ with the 3 bubbles
//! P = (1−ξ², 1−η², 1−ζ²) per displacement component, i.e. 9 internal DOFs α.
//! Their strain matrix uses the centre Jacobian J₀ and is scaled by det J₀ / det J(ξ)
//! (Taylor's modification), so ∫ B̃ₐ dV = Σ_g w_g det J₀ J₀⁻¹ ∂P/∂ξ = 0 exactly and the
//! element passes the patch test on distorted meshes. 2×2×2 Gauss throughout; the
//! internal DOFs are condensed statically: K = K_cc − K_ca K_aa⁻¹ K_ac.
//!
//! Full integration (plain trilinear, 2×2×2 Gauss) is kept as
//! [`Formulation::FullIntegration`] only to show in tests why it is not used: it
//! locks in bending (the `solve::modal` cantilever test measures how much).

use nalgebra::{Matrix3, Matrix6, SMatrix, Vector3};
use thiserror::Error;

use crate::fe::mesh::Material;

/// 24×24 element matrix.
pub type Mat24 = SMatrix<f64, 24, 24>;

/// Errors of the element routines.
#[derive(Debug, Error, PartialEq)]
pub enum ElementError {
    /// The element is inverted or degenerate at a Gauss point or its centre.
    #[error("hex8 Jacobian determinant {det} <= 0 at natural point {at:?}")]
    NonPositiveJacobian { det: f64, at: [f64; 3] },
}

/// Stiffness formulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Formulation {
    /// 9 incompatible modes, Taylor-corrected, statically condensed (default).
    #[default]
    IncompatibleModes,
    /// Plain trilinear element, 2×2×2 Gauss. Locks in bending; for comparison only.
    FullIntegration,
}

/// Natural coordinates (ξ, η, ζ) of the 8 corners, C3D8 order.
pub const CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// 2-point Gauss abscissa 1/√3 (weights 1): exact for cubics per direction.
const G2: f64 = 0.577_350_269_189_625_8;

/// The 8 points of the 2×2×2 Gauss rule (all weights 1).
pub fn gauss_2x2x2() -> [[f64; 3]; 8] {
    CORNERS.map(|c| [c[0] * G2, c[1] * G2, c[2] * G2])
}

/// Shape functions Nᵢ = ⅛(1+ξᵢξ)(1+ηᵢη)(1+ζᵢζ) and their natural derivatives
/// (row i = ∂Nᵢ/∂(ξ, η, ζ)).
pub fn shape(p: [f64; 3]) -> ([f64; 8], [[f64; 3]; 8]) {
    let mut n = [0.0; 8];
    let mut d = [[0.0; 3]; 8];
    for (i, c) in CORNERS.iter().enumerate() {
        let a = 1.0 + c[0] * p[0];
        let b = 1.0 + c[1] * p[1];
        let e = 1.0 + c[2] * p[2];
        n[i] = 0.125 * a * b * e;
        d[i] = [
            0.125 * c[0] * b * e,
            0.125 * a * c[1] * e,
            0.125 * a * b * c[2],
        ];
    }
    (n, d)
}

/// Jacobian J[a][b] = ∂x_b/∂ξ_a at natural point `p`.
fn jacobian(x: &[[f64; 3]; 8], dn: &[[f64; 3]; 8]) -> Matrix3<f64> {
    let mut j = Matrix3::zeros();
    for i in 0..8 {
        for a in 0..3 {
            for b in 0..3 {
                j[(a, b)] += dn[i][a] * x[i][b];
            }
        }
    }
    j
}

/// Jacobian, its determinant (checked > 0) and inverse at natural point `p`.
fn jacobian_checked(
    x: &[[f64; 3]; 8],
    p: [f64; 3],
) -> Result<(Matrix3<f64>, f64, Matrix3<f64>), ElementError> {
    let (_, dn) = shape(p);
    let j = jacobian(x, &dn);
    let det = j.determinant();
    // Written so that a NaN determinant is rejected too.
    if det.is_nan() || det <= 0.0 {
        return Err(ElementError::NonPositiveJacobian { det, at: p });
    }
    // det > 0 was checked, so the inverse exists.
    let inv = j
        .try_inverse()
        .ok_or(ElementError::NonPositiveJacobian { det, at: p })?;
    Ok((j, det, inv))
}

/// Isotropic elasticity matrix D (σ = D ε, Voigt order above):
/// λ = Eν/((1+ν)(1−2ν)), G = E/(2(1+ν)).
pub fn elasticity_matrix(m: &Material) -> Matrix6<f64> {
    let e = m.youngs_modulus;
    let nu = m.poisson_ratio;
    let lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let g = m.shear_modulus();
    let mut d = Matrix6::zeros();
    for a in 0..3 {
        for b in 0..3 {
            d[(a, b)] = if a == b { lam + 2.0 * g } else { lam };
        }
        d[(a + 3, a + 3)] = g;
    }
    d
}

/// Writes the 6×3 strain block of one displacement "node" with spatial gradient `g`
/// into columns `col..col+3` of `b`.
fn put_b_block<const C: usize>(b: &mut SMatrix<f64, 6, C>, col: usize, g: Vector3<f64>) {
    let (dx, dy, dz) = (g[0], g[1], g[2]);
    b[(0, col)] = dx;
    b[(1, col + 1)] = dy;
    b[(2, col + 2)] = dz;
    b[(3, col)] = dy;
    b[(3, col + 1)] = dx;
    b[(4, col + 1)] = dz;
    b[(4, col + 2)] = dy;
    b[(5, col)] = dz;
    b[(5, col + 2)] = dx;
}

/// Element stiffness (24×24, force/length) for corner coordinates `x` (C3D8 order).
pub fn stiffness(
    x: &[[f64; 3]; 8],
    mat: &Material,
    form: Formulation,
) -> Result<Mat24, ElementError> {
    stiffness_impl(x, mat, form, true)
}

/// `taylor = false` drops Taylor's correction (uses J(ξ) for the bubbles); only the
/// patch-test test uses it, to show that the correction is what makes the test pass.
fn stiffness_impl(
    x: &[[f64; 3]; 8],
    mat: &Material,
    form: Formulation,
    taylor: bool,
) -> Result<Mat24, ElementError> {
    let d = elasticity_matrix(mat);
    let (_, det0, inv0) = jacobian_checked(x, [0.0; 3])?;
    let mut kcc = Mat24::zeros();
    let mut kac = SMatrix::<f64, 9, 24>::zeros();
    let mut kaa = SMatrix::<f64, 9, 9>::zeros();
    for p in gauss_2x2x2() {
        let (_, dn) = shape(p);
        let (_, det, inv) = jacobian_checked(x, p)?;
        let mut bc = SMatrix::<f64, 6, 24>::zeros();
        for (i, dni) in dn.iter().enumerate() {
            put_b_block(&mut bc, 3 * i, inv * Vector3::from(*dni));
        }
        let dbc = d * bc;
        kcc += bc.transpose() * dbc * det;
        if form == Formulation::IncompatibleModes {
            // ∂Pₐ/∂ξ for P = (1−ξ², 1−η², 1−ζ²).
            let dp = [
                Vector3::new(-2.0 * p[0], 0.0, 0.0),
                Vector3::new(0.0, -2.0 * p[1], 0.0),
                Vector3::new(0.0, 0.0, -2.0 * p[2]),
            ];
            let mut ba = SMatrix::<f64, 6, 9>::zeros();
            for (a, dpa) in dp.iter().enumerate() {
                // B̃ₐ = (det J₀/det J) · B(J₀⁻¹ ∂Pₐ/∂ξ)   (Taylor's modification)
                let g = if taylor {
                    inv0 * dpa * (det0 / det)
                } else {
                    inv * dpa
                };
                put_b_block(&mut ba, 3 * a, g);
            }
            kac += ba.transpose() * dbc * det;
            kaa += ba.transpose() * d * ba * det;
        }
    }
    if form == Formulation::FullIntegration {
        return Ok(kcc);
    }
    // K_aa is SPD for a valid element (the bubbles' strains are independent).
    let chol = kaa.cholesky().ok_or(ElementError::NonPositiveJacobian {
        det: det0,
        at: [0.0; 3],
    })?;
    let kaa_inv_kac = chol.solve(&kac);
    let mut k = kcc - kac.transpose() * kaa_inv_kac;
    // Restore exact symmetry lost to round-off in the condensation.
    k = (k + k.transpose()) * 0.5;
    Ok(k)
}

/// Consistent mass matrix M = ∫ ρ Nᵀ N dV (24×24), 2×2×2 Gauss. Exact for
/// parallelepipeds (integrand of degree ≤ 2 per direction, times constant det J).
pub fn mass(x: &[[f64; 3]; 8], density: f64) -> Result<Mat24, ElementError> {
    let mut m8 = SMatrix::<f64, 8, 8>::zeros();
    for p in gauss_2x2x2() {
        let (n, _) = shape(p);
        let (_, det, _) = jacobian_checked(x, p)?;
        for i in 0..8 {
            for j in i..8 {
                let v = density * n[i] * n[j] * det;
                m8[(i, j)] += v;
                if j != i {
                    m8[(j, i)] += v;
                }
            }
        }
    }
    let mut m = Mat24::zeros();
    for i in 0..8 {
        for j in 0..8 {
            for c in 0..3 {
                m[(3 * i + c, 3 * j + c)] = m8[(i, j)];
            }
        }
    }
    Ok(m)
}

/// Element volume ∫ dV by 2×2×2 Gauss (exact for trilinear hexahedra: det J has
/// degree ≤ 2 in each natural coordinate).
pub fn volume(x: &[[f64; 3]; 8]) -> Result<f64, ElementError> {
    let mut v = 0.0;
    for p in gauss_2x2x2() {
        v += jacobian_checked(x, p)?.1;
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::rng::Rng;
    use nalgebra::{DMatrix, DVector, SVector};

    fn steel() -> Material {
        Material::new(210_000.0, 0.3, 7.85e-9).unwrap()
    }

    /// A visibly distorted (non-parallelepiped) element around the unit cube.
    fn distorted() -> [[f64; 3]; 8] {
        let mut x = CORNERS.map(|c| c.map(|v| 0.5 * (v + 1.0)));
        let mut rng = Rng::new(7);
        for p in x.iter_mut() {
            for v in p.iter_mut() {
                *v += rng.uniform(-0.2, 0.2);
            }
        }
        x
    }

    fn rigid_modes(x: &[[f64; 3]; 8]) -> Vec<SVector<f64, 24>> {
        let mut out = Vec::new();
        for c in 0..3 {
            let mut u = SVector::<f64, 24>::zeros();
            for i in 0..8 {
                u[3 * i + c] = 1.0;
            }
            out.push(u);
        }
        // Infinitesimal rotations u = ω × x.
        for axis in 0..3 {
            let mut w = Vector3::zeros();
            w[axis] = 1.0;
            let mut u = SVector::<f64, 24>::zeros();
            for i in 0..8 {
                let r = w.cross(&Vector3::from(x[i]));
                for c in 0..3 {
                    u[3 * i + c] = r[c];
                }
            }
            out.push(u);
        }
        out
    }

    #[test]
    fn rigid_body_modes_give_zero_force_and_rank_is_18() {
        let x = distorted();
        for form in [Formulation::IncompatibleModes, Formulation::FullIntegration] {
            let k = stiffness(&x, &steel(), form).unwrap();
            let scale = k.abs().max();
            for u in rigid_modes(&x) {
                // Round-off level: entries ~E·h, sums of 24 terms → ~1e-16·24·|K||u|.
                let f = k * u;
                assert!(
                    f.abs().max() < 1e-11 * scale * u.abs().max(),
                    "{form:?}: {}",
                    f.abs().max()
                );
            }
            // 6 zero eigenvalues (rigid modes), 18 positive: no spurious zero-energy mode.
            let eig = DMatrix::from_column_slice(24, 24, k.as_slice()).symmetric_eigenvalues();
            let max = eig.max();
            let zeros = eig.iter().filter(|&&l| l.abs() < 1e-10 * max).count();
            assert_eq!(zeros, 6, "{form:?}");
            assert!(eig.iter().all(|&l| l > -1e-10 * max));
        }
    }

    #[test]
    fn stiffness_is_symmetric() {
        let x = distorted();
        for form in [Formulation::IncompatibleModes, Formulation::FullIntegration] {
            let k = stiffness(&x, &steel(), form).unwrap();
            // Incompatible modes are symmetrised explicitly; full integration is
            // symmetric to round-off (BᵀDB with D symmetric).
            assert!((k - k.transpose()).abs().max() <= 1e-13 * k.abs().max());
        }
    }

    /// Patch test: a 3×3×3 patch of the cube [0,3]³ with every node moved randomly by up
    /// to ±0.2 (so no element is a parallelepiped); boundary nodes get a linear field
    /// u = u₀ + G x; the 8 interior nodes are solved for. A consistent element
    /// reproduces the linear field there exactly (to round-off).
    fn patch_test_error(taylor: bool) -> f64 {
        let n = 4; // nodes per direction
        let mut rng = Rng::new(42);
        let mut xs = vec![[0.0; 3]; n * n * n];
        let id = |i: usize, j: usize, k: usize| i + n * (j + n * k);
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    xs[id(i, j, k)] = [i, j, k].map(|v| v as f64 + rng.uniform(-0.2, 0.2));
                }
            }
        }
        let g = Matrix3::new(1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 4e-4);
        let u0 = Vector3::new(0.01, -0.02, 0.03);
        let exact = |p: [f64; 3]| u0 + g * Vector3::from(p);
        let ndof = 3 * xs.len();
        let mut kg = DMatrix::<f64>::zeros(ndof, ndof);
        for k in 0..n - 1 {
            for j in 0..n - 1 {
                for i in 0..n - 1 {
                    let conn = CORNERS.map(|c| {
                        let o = c.map(|v| if v > 0.0 { 1 } else { 0 });
                        id(i + o[0], j + o[1], k + o[2])
                    });
                    let x = conn.map(|a| xs[a]);
                    let ke = stiffness_impl(&x, &steel(), Formulation::IncompatibleModes, taylor)
                        .unwrap();
                    for a in 0..8 {
                        for b in 0..8 {
                            for c in 0..3 {
                                for d in 0..3 {
                                    kg[(3 * conn[a] + c, 3 * conn[b] + d)] +=
                                        ke[(3 * a + c, 3 * b + d)];
                                }
                            }
                        }
                    }
                }
            }
        }
        let interior: Vec<usize> = (0..xs.len())
            .filter(|&a| {
                let (i, j, k) = (a % n, (a / n) % n, a / (n * n));
                [i, j, k].iter().all(|&v| v > 0 && v < n - 1)
            })
            .collect();
        assert_eq!(interior.len(), 8);
        let free: Vec<usize> = interior
            .iter()
            .flat_map(|&a| (0..3).map(move |c| 3 * a + c))
            .collect();
        let mut u = DVector::<f64>::zeros(ndof);
        for (a, p) in xs.iter().enumerate() {
            let e = exact(*p);
            for c in 0..3 {
                u[3 * a + c] = e[c];
            }
        }
        let exact_free = DVector::from_iterator(free.len(), free.iter().map(|&r| u[r]));
        for &r in &free {
            u[r] = 0.0;
        }
        // K_ff u_f = −K_fp u_p
        let rhs = -DVector::from_iterator(free.len(), free.iter().map(|&r| (kg.row(r) * &u)[0]));
        let kff = DMatrix::from_fn(free.len(), free.len(), |a, b| kg[(free[a], free[b])]);
        let uf = kff.lu().solve(&rhs).unwrap();
        (uf - &exact_free).norm() / exact_free.norm()
    }

    #[test]
    fn patch_test_reproduces_linear_field() {
        // Requirement: 1e-10 relative; measured about 1e-15 (round-off).
        let err = patch_test_error(true);
        eprintln!("patch test relative error {err:.2e}");
        assert!(err < 1e-10, "patch test error {err}");
    }

    #[test]
    fn patch_test_fails_without_taylor_correction() {
        // Documents why Taylor's modification is there: without it the distorted
        // patch is not reproduced (error is orders of magnitude above round-off).
        let err = patch_test_error(false);
        eprintln!("patch test without Taylor correction: relative error {err:.2e}");
        assert!(err > 1e-6, "uncorrected element unexpectedly passed: {err}");
    }

    #[test]
    fn mass_sums_to_rho_v() {
        let rho = 7.85e-9;
        // Box 2×3×4 and a sheared parallelepiped with edge vectors a, b, c:
        // V = |det[a b c]| exactly.
        let a = Vector3::new(2.0, 0.0, 0.0);
        let b = Vector3::new(0.5, 3.0, 0.0);
        let c = Vector3::new(0.3, -0.4, 4.0);
        let vol = Matrix3::from_columns(&[a, b, c]).determinant();
        for shear in [false, true] {
            let (b2, c2) = if shear {
                (b, c)
            } else {
                (Vector3::new(0.0, 3.0, 0.0), Vector3::new(0.0, 0.0, 4.0))
            };
            let x = CORNERS.map(|p| {
                let r = a * (0.5 * (p[0] + 1.0))
                    + b2 * (0.5 * (p[1] + 1.0))
                    + c2 * (0.5 * (p[2] + 1.0));
                [r[0], r[1], r[2]]
            });
            let v = if shear { vol } else { 24.0 };
            let m = mass(&x, rho).unwrap();
            for comp in 0..3 {
                let mut s = 0.0;
                for i in 0..8 {
                    for j in 0..8 {
                        s += m[(3 * i + comp, 3 * j + comp)];
                    }
                }
                approx::assert_relative_eq!(s, rho * v, max_relative = 1e-14);
            }
            approx::assert_relative_eq!(volume(&x).unwrap(), v, max_relative = 1e-14);
            assert!((m - m.transpose()).abs().max() == 0.0);
        }
        // Distorted element: the mass still sums to ρ·(its own exact volume).
        let x = distorted();
        let m = mass(&x, rho).unwrap();
        approx::assert_relative_eq!(
            m.sum() / 3.0,
            rho * volume(&x).unwrap(),
            max_relative = 1e-13
        );
    }

    #[test]
    fn uniaxial_stress_single_element() {
        // Unit cube, nodes on x=0 held in x, one node fully, another in y/z to stop
        // rotation; face x=1 pulled with σ·A/4 per node. Exact: u_x = σ/E at x=1,
        // lateral contraction −νσ/E. Holds for any element passing the patch test.
        let x = CORNERS.map(|c| c.map(|v| 0.5 * (v + 1.0)));
        let mat = steel();
        let k = stiffness(&x, &mat, Formulation::IncompatibleModes).unwrap();
        let sigma = 100.0;
        let mut fixed = [false; 24];
        for i in 0..8 {
            if x[i][0] == 0.0 {
                fixed[3 * i] = true;
            }
        }
        fixed[1] = true; // node 0: y, z
        fixed[2] = true;
        fixed[3 * 4 + 1] = true; // node 4 (0,0,1): y, stops rotation about x
        fixed[3 * 3 + 2] = true; // node 3 (0,1,0): z, stops rotation about y... and x
        let mut f = DVector::<f64>::zeros(24);
        for i in 0..8 {
            if x[i][0] == 1.0 {
                f[3 * i] = sigma / 4.0;
            }
        }
        let free: Vec<usize> = (0..24).filter(|&r| !fixed[r]).collect();
        let kff = DMatrix::from_fn(free.len(), free.len(), |a, b| k[(free[a], free[b])]);
        let ff = DVector::from_iterator(free.len(), free.iter().map(|&r| f[r]));
        let uf = kff.lu().solve(&ff).unwrap();
        let mut u = DVector::<f64>::zeros(24);
        for (a, &r) in free.iter().enumerate() {
            u[r] = uf[a];
        }
        let eps = sigma / mat.youngs_modulus;
        for i in 0..8 {
            approx::assert_relative_eq!(u[3 * i], eps * x[i][0], epsilon = 1e-12 * eps);
            approx::assert_relative_eq!(
                u[3 * i + 1],
                -mat.poisson_ratio * eps * x[i][1],
                epsilon = 1e-12 * eps
            );
            approx::assert_relative_eq!(
                u[3 * i + 2],
                -mat.poisson_ratio * eps * x[i][2],
                epsilon = 1e-12 * eps
            );
        }
    }

    #[test]
    fn inverted_element_is_an_error() {
        let mut x = CORNERS.map(|c| c.map(|v| 0.5 * (v + 1.0)));
        x.swap(0, 6);
        assert!(matches!(
            stiffness(&x, &steel(), Formulation::IncompatibleModes),
            Err(ElementError::NonPositiveJacobian { .. })
        ));
        assert!(mass(&x, 1.0).is_err());
    }
}
