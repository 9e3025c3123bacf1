//! The isoparametric element of a type's shape functions and quadrature rules:
//! K = ∫ Bᵀ D B dV and M = ∫ ρ Nᵀ N dV summed over the rules' points (model.md §2), with
//! the Jacobian checked at every point.

use nalgebra::{DMatrix, Matrix3};

use super::face_shape::FaceDef;
use super::rules::QuadPoint;
use super::{ElementError, ElementKind, SolidElement};
use crate::fe::hex8;
use crate::fe::material::Material;

/// Shape functions `n[i]` and natural derivatives `dn[i] = ∂Nᵢ/∂(ξ, η, ζ)` at a point.
pub type ShapeFn = fn([f64; 3], &mut [f64], &mut [[f64; 3]]);

/// A type's data: node layout, faces, shape functions and quadrature rules. Its element
/// matrices are the integrated ones.
#[derive(Clone)]
pub struct Isoparametric {
    pub kind: ElementKind,
    pub corner_count: usize,
    pub edges: &'static [(usize, usize)],
    pub faces: &'static [FaceDef],
    pub vtk_cell: u8,
    pub shape: ShapeFn,
    pub stiffness_rule: Vec<QuadPoint>,
    pub mass_rule: Vec<QuadPoint>,
}

impl SolidElement for Isoparametric {
    fn kind(&self) -> ElementKind {
        self.kind
    }

    fn corner_count(&self) -> usize {
        self.corner_count
    }

    fn edges(&self) -> &'static [(usize, usize)] {
        self.edges
    }

    fn faces(&self) -> &'static [FaceDef] {
        self.faces
    }

    fn vtk_cell(&self) -> u8 {
        self.vtk_cell
    }

    fn shape(&self, p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        (self.shape)(p, n, dn)
    }

    fn stiffness_rule(&self) -> &[QuadPoint] {
        &self.stiffness_rule
    }

    fn mass_rule(&self) -> &[QuadPoint] {
        &self.mass_rule
    }
}

/// M = ∫ ρ Nᵀ N dV by the element's mass rule (the trait's default mass).
pub fn integrated_mass<E: SolidElement + ?Sized>(
    e: &E,
    x: &[[f64; 3]],
    density: f64,
) -> Result<DMatrix<f64>, ElementError> {
    let kind = e.kind();
    check_nodes(kind, x)?;
    let nn = x.len();
    let mut m = DMatrix::zeros(nn, nn);
    let (mut n, mut dn) = (vec![0.0; nn], vec![[0.0; 3]; nn]);
    for &(p, w) in e.mass_rule() {
        e.shape(p, &mut n, &mut dn);
        let (det, _) = jacobian(kind, x, &dn, p)?;
        let f = density * w * det;
        for i in 0..nn {
            for j in i..nn {
                let v = f * n[i] * n[j];
                m[(i, j)] += v;
                if j != i {
                    m[(j, i)] += v;
                }
            }
        }
    }
    Ok(DMatrix::from_fn(3 * nn, 3 * nn, |r, c| {
        if r % 3 == c % 3 {
            m[(r / 3, c / 3)]
        } else {
            0.0
        }
    }))
}

/// K = ∫ Bᵀ D B dV by the element's stiffness rule (the trait's default stiffness).
pub fn integrated_stiffness<E: SolidElement + ?Sized>(
    e: &E,
    x: &[[f64; 3]],
    mat: &Material,
) -> Result<DMatrix<f64>, ElementError> {
    let kind = e.kind();
    check_nodes(kind, x)?;
    let nn = x.len();
    // Isotropic D (σ = D ε): λ = Eν/((1+ν)(1−2ν)), G = E/(2(1+ν)).
    let d = hex8::elasticity_matrix(mat);
    let mut k = DMatrix::zeros(3 * nn, 3 * nn);
    let mut b = DMatrix::zeros(6, 3 * nn);
    let (mut n, mut dn) = (vec![0.0; nn], vec![[0.0; 3]; nn]);
    for &(p, w) in e.stiffness_rule() {
        e.shape(p, &mut n, &mut dn);
        let (det, inv) = jacobian(kind, x, &dn, p)?;
        b.fill(0.0);
        for i in 0..nn {
            let g = inv * nalgebra::Vector3::from(dn[i]);
            put_b_block(&mut b, 3 * i, [g[0], g[1], g[2]]);
        }
        let db = d * &b;
        k.gemm_tr(w * det, &b, &db, 1.0);
    }
    symmetrize(&mut k);
    Ok(k)
}

pub(super) fn check_nodes(kind: ElementKind, x: &[[f64; 3]]) -> Result<(), ElementError> {
    if x.len() != kind.node_count() {
        return Err(ElementError::NodeCount {
            kind,
            expected: kind.node_count(),
            got: x.len(),
        });
    }
    Ok(())
}

/// det J and J⁻¹ (`J[a][b]` = ∂x_b/∂ξ_a) at natural point `p`; det J > 0 checked (a NaN
/// determinant is rejected too).
pub(super) fn jacobian(
    kind: ElementKind,
    x: &[[f64; 3]],
    dn: &[[f64; 3]],
    p: [f64; 3],
) -> Result<(f64, Matrix3<f64>), ElementError> {
    let mut j = Matrix3::zeros();
    for (xi, di) in x.iter().zip(dn) {
        for a in 0..3 {
            for b in 0..3 {
                j[(a, b)] += di[a] * xi[b];
            }
        }
    }
    let det = j.determinant();
    let bad = ElementError::NonPositiveJacobian { kind, det, at: p };
    if det.is_nan() || det <= 0.0 {
        return Err(bad);
    }
    Ok((det, j.try_inverse().ok_or(bad)?))
}

/// Writes the 6×3 strain block of one node with spatial gradient `g` into columns
/// `col..col+3` of `b`.
fn put_b_block(b: &mut DMatrix<f64>, col: usize, g: [f64; 3]) {
    let [dx, dy, dz] = g;
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

/// Restores the exact symmetry lost to round-off.
fn symmetrize(k: &mut DMatrix<f64>) {
    let n = k.nrows();
    for r in 0..n {
        for c in r + 1..n {
            let v = 0.5 * (k[(r, c)] + k[(c, r)]);
            k[(r, c)] = v;
            k[(c, r)] = v;
        }
    }
}

/// A hex8 routine's error as this module's, for element type `kind`.
pub(super) fn hex8_error(kind: ElementKind, e: hex8::ElementError) -> ElementError {
    let hex8::ElementError::NonPositiveJacobian { det, at } = e;
    ElementError::NonPositiveJacobian { kind, det, at }
}
