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

use crate::fe::material::Material;

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

/// Jacobian `J[a][b]` = ∂x_b/∂ξ_a at natural point `p`.
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
#[path = "hex8_tests.rs"]
mod tests;
