//! Isoparametric solid elements for linear isotropic elasticity, in the Abaqus/CalculiX
//! node order and with their face numbering S1…S6: C3D4, C3D10 (tetrahedra), C3D8,
//! C3D8I, C3D20, C3D20R (hexahedra), all behind [`SolidElement`].
//!
//! Element DOF order: node i, component c → local DOF `3i + c`. Strains in Voigt order
//! (εxx, εyy, εzz, γxy, γyz, γzx) with engineering shear strains. Stiffness
//! K = ∫ Bᵀ D B dV and consistent mass M = ∫ ρ Nᵀ N dV (model.md §2, the linear FE
//! model the joint forces are added to), with these quadrature rules:
//!
//! | type | nodes | stiffness rule | mass rule |
//! |---|---:|---|---|
//! | C3D4 | 4 | 1 point | 4 points (exact) |
//! | C3D10 | 10 | 4 points | collapsed 4×4×4 (exact for straight edges) |
//! | C3D8 | 8 | 2×2×2 | 2×2×2 |
//! | C3D8I | 8 | 2×2×2 + 9 incompatible modes ([`crate::fe::hex8`]) | 2×2×2 |
//! | C3D20 | 20 | 3×3×3 | 3×3×3 |
//! | C3D20R | 20 | 2×2×2 (reduced) | 3×3×3 |

pub mod box_mesh;
pub mod face;
pub mod hex;
pub mod rules;
pub mod tet;

#[cfg(test)]
mod tests;

use std::sync::LazyLock;

use nalgebra::{DMatrix, Matrix3, Matrix6};
use thiserror::Error;

use crate::fe::hex8;
use crate::fe::material::Material;
use rules::QuadPoint;

/// Errors of the element routines.
#[derive(Debug, Error, PartialEq)]
pub enum ElementError {
    /// The element is inverted or degenerate at a quadrature point.
    #[error("{kind} Jacobian determinant {det:e} <= 0 at natural point {at:?} (inverted or degenerate element)")]
    NonPositiveJacobian {
        kind: ElementKind,
        det: f64,
        at: [f64; 3],
    },
    /// The connectivity has the wrong number of nodes for the type.
    #[error("{kind} needs {expected} nodes, got {got}")]
    NodeCount {
        kind: ElementKind,
        expected: usize,
        got: usize,
    },
}

/// The supported solid element types (Abaqus names).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ElementKind {
    C3D4,
    C3D10,
    C3D8,
    C3D8I,
    C3D20,
    C3D20R,
}

impl ElementKind {
    /// All supported types.
    pub const ALL: [ElementKind; 6] = [
        ElementKind::C3D4,
        ElementKind::C3D10,
        ElementKind::C3D8,
        ElementKind::C3D8I,
        ElementKind::C3D20,
        ElementKind::C3D20R,
    ];

    /// The type of an Abaqus element name (case-insensitive), if supported.
    pub fn from_name(name: &str) -> Option<ElementKind> {
        Self::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(name.trim()))
    }

    /// The Abaqus name, e.g. "C3D20R".
    pub fn name(self) -> &'static str {
        match self {
            ElementKind::C3D4 => "C3D4",
            ElementKind::C3D10 => "C3D10",
            ElementKind::C3D8 => "C3D8",
            ElementKind::C3D8I => "C3D8I",
            ElementKind::C3D20 => "C3D20",
            ElementKind::C3D20R => "C3D20R",
        }
    }

    /// The element routines of this type.
    pub fn element(self) -> &'static dyn SolidElement {
        static RULES: LazyLock<[Rules; 6]> = LazyLock::new(|| {
            ElementKind::ALL.map(|k| {
                let (stiff, mass) = match k {
                    ElementKind::C3D4 => (rules::tet_1(), rules::tet_4()),
                    ElementKind::C3D10 => (rules::tet_4(), rules::tet_collapsed_4()),
                    ElementKind::C3D8 | ElementKind::C3D8I => {
                        (rules::hex_gauss(2), rules::hex_gauss(2))
                    }
                    ElementKind::C3D20 => (rules::hex_gauss(3), rules::hex_gauss(3)),
                    ElementKind::C3D20R => (rules::hex_gauss(2), rules::hex_gauss(3)),
                };
                Rules {
                    kind: k,
                    stiff,
                    mass,
                }
            })
        });
        &RULES[self as usize]
    }

    /// Number of nodes.
    pub fn node_count(self) -> usize {
        match self {
            ElementKind::C3D4 => 4,
            ElementKind::C3D10 => 10,
            ElementKind::C3D8 | ElementKind::C3D8I => 8,
            ElementKind::C3D20 | ElementKind::C3D20R => 20,
        }
    }

    /// True for the tetrahedra.
    pub fn is_tet(self) -> bool {
        matches!(self, ElementKind::C3D4 | ElementKind::C3D10)
    }

    /// True for the quadratic (mid-edge node) types.
    pub fn is_quadratic(self) -> bool {
        matches!(
            self,
            ElementKind::C3D10 | ElementKind::C3D20 | ElementKind::C3D20R
        )
    }

    /// Number of faces (S1…S4 for tetrahedra, S1…S6 for hexahedra).
    pub fn face_count(self) -> usize {
        if self.is_tet() {
            4
        } else {
            6
        }
    }

    /// Local node indices (0-based) of face `s` (0 = S1), corners then midpoints, in
    /// the Abaqus order (normal into the element); None for an impossible face.
    pub fn face_nodes(self, s: usize) -> Option<&'static [usize]> {
        let corners_only = !self.is_quadratic();
        let nodes: &'static [usize] = if self.is_tet() {
            tet::FACES10.get(s)?
        } else {
            hex::FACES20.get(s)?
        };
        Some(if corners_only {
            &nodes[..nodes.len() / 2]
        } else {
            nodes
        })
    }
}

impl std::fmt::Display for ElementKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A solid element type: its shape functions, quadrature and element matrices.
pub trait SolidElement: Sync {
    /// The type.
    fn kind(&self) -> ElementKind;
    /// Shape functions `n[i]` and natural derivatives `dn[i] = ∂Nᵢ/∂(ξ, η, ζ)` at `p`.
    fn shape(&self, p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]);
    /// Quadrature rule of the stiffness.
    fn stiffness_rule(&self) -> &[QuadPoint];
    /// Quadrature rule of the mass (and volume).
    fn mass_rule(&self) -> &[QuadPoint];

    /// Element stiffness K = ∫ Bᵀ D B dV (3n × 3n, force/length) for node coordinates
    /// `x` (length units).
    fn stiffness(&self, x: &[[f64; 3]], mat: &Material) -> Result<DMatrix<f64>, ElementError> {
        integrated_stiffness(self, x, mat)
    }

    /// Consistent mass M = ∫ ρ Nᵀ N dV (3n × 3n, mass units).
    fn mass(&self, x: &[[f64; 3]], density: f64) -> Result<DMatrix<f64>, ElementError> {
        integrated_mass(self, x, density)
    }

    /// Volume ∫ dV (mass rule).
    fn volume(&self, x: &[[f64; 3]]) -> Result<f64, ElementError> {
        let kind = self.kind();
        check_nodes(kind, x)?;
        let (mut n, mut dn) = (vec![0.0; x.len()], vec![[0.0; 3]; x.len()]);
        let mut v = 0.0;
        for &(p, w) in self.mass_rule() {
            self.shape(p, &mut n, &mut dn);
            v += w * jacobian(kind, x, &dn, p)?.0;
        }
        Ok(v)
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

/// The routines of one type: its kind and quadrature rules.
struct Rules {
    kind: ElementKind,
    stiff: Vec<QuadPoint>,
    mass: Vec<QuadPoint>,
}

impl SolidElement for Rules {
    fn kind(&self) -> ElementKind {
        self.kind
    }

    fn shape(&self, p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        match self.kind {
            ElementKind::C3D4 => tet::shape4(p, n, dn),
            ElementKind::C3D10 => tet::shape10(p, n, dn),
            ElementKind::C3D8 | ElementKind::C3D8I => hex::shape8(p, n, dn),
            ElementKind::C3D20 | ElementKind::C3D20R => hex::shape20(p, n, dn),
        }
    }

    fn stiffness_rule(&self) -> &[QuadPoint] {
        &self.stiff
    }

    fn mass_rule(&self) -> &[QuadPoint] {
        &self.mass
    }

    fn mass(&self, x: &[[f64; 3]], density: f64) -> Result<DMatrix<f64>, ElementError> {
        if !matches!(self.kind, ElementKind::C3D8 | ElementKind::C3D8I) {
            return integrated_mass(self, x, density);
        }
        // The 2×2×2 consistent mass of the structured meshes' hexahedron (hex8.rs): the
        // same rule, so the box scenes' M is the one they always had, bit for bit.
        check_nodes(self.kind, x)?;
        let corners: [[f64; 3]; 8] = std::array::from_fn(|i| x[i]);
        let m = hex8::mass(&corners, density).map_err(|e| hex8_error(self.kind, e))?;
        Ok(DMatrix::from_column_slice(24, 24, m.as_slice()))
    }

    fn stiffness(&self, x: &[[f64; 3]], mat: &Material) -> Result<DMatrix<f64>, ElementError> {
        if self.kind != ElementKind::C3D8I {
            return integrated_stiffness(self, x, mat);
        }
        // The incompatible-modes hexahedron of the structured meshes (hex8.rs).
        check_nodes(self.kind, x)?;
        let corners: [[f64; 3]; 8] = std::array::from_fn(|i| x[i]);
        let k = hex8::stiffness(&corners, mat, hex8::Formulation::IncompatibleModes)
            .map_err(|e| hex8_error(self.kind, e))?;
        Ok(DMatrix::from_column_slice(24, 24, k.as_slice()))
    }
}

/// A hex8 routine's error as this module's, for element type `kind`.
fn hex8_error(kind: ElementKind, e: hex8::ElementError) -> ElementError {
    let hex8::ElementError::NonPositiveJacobian { det, at } = e;
    ElementError::NonPositiveJacobian { kind, det, at }
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
    let d = elasticity_matrix(mat);
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

fn check_nodes(kind: ElementKind, x: &[[f64; 3]]) -> Result<(), ElementError> {
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
fn jacobian(
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

/// Isotropic elasticity matrix D (σ = D ε): λ = Eν/((1+ν)(1−2ν)), G = E/(2(1+ν)).
pub fn elasticity_matrix(m: &Material) -> Matrix6<f64> {
    hex8::elasticity_matrix(m)
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
