//! Isoparametric solid elements for linear isotropic elasticity, in the Abaqus/CalculiX
//! node order and with their face numbering S1…S6: C3D4, C3D10 (tetrahedra), C3D6, C3D15
//! (wedges), C3D8, C3D8I, C3D20, C3D20R (hexahedra), all behind [`SolidElement`]: one
//! file per type
//! (`c3d4.rs`, …) with its node layout, faces (each with its own shape), shape functions
//! and quadrature, registered in [`ElementKind::element`].
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
//! | C3D6 | 6 | 2 points (centroid × 2) | 3-point triangle × 2 (exact for straight prisms) |
//! | C3D15 | 15 | 9 points (3-point triangle × 3) | collapsed 3×3 triangle × 3 (exact for straight prisms) |
//! | C3D8 | 8 | 2×2×2 | 2×2×2 |
//! | C3D8I | 8 | 2×2×2 + 9 incompatible modes ([`crate::fe::hex8`]) | 2×2×2 |
//! | C3D20 | 20 | 3×3×3 | 3×3×3 |
//! | C3D20R | 20 | 2×2×2 (reduced) | 3×3×3 |

pub mod box_mesh;
pub mod c3d10;
pub mod c3d15;
pub mod c3d20;
pub mod c3d20r;
pub mod c3d4;
pub mod c3d6;
pub mod c3d8;
pub mod face;
pub mod face_shape;
pub mod hex;
pub mod isoparametric;
pub mod rules;
pub mod tet;
pub mod wedge;

#[cfg(test)]
mod tests;

use nalgebra::DMatrix;
use thiserror::Error;

use crate::fe::material::Material;
use face_shape::FaceDef;
use isoparametric::{check_nodes, jacobian};
pub use isoparametric::{integrated_mass, integrated_stiffness};
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
    C3D6,
    C3D15,
    C3D8,
    C3D8I,
    C3D20,
    C3D20R,
}

impl ElementKind {
    /// All supported types.
    pub const ALL: [ElementKind; 8] = [
        ElementKind::C3D4,
        ElementKind::C3D10,
        ElementKind::C3D6,
        ElementKind::C3D15,
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
            ElementKind::C3D6 => "C3D6",
            ElementKind::C3D15 => "C3D15",
            ElementKind::C3D8 => "C3D8",
            ElementKind::C3D8I => "C3D8I",
            ElementKind::C3D20 => "C3D20",
            ElementKind::C3D20R => "C3D20R",
        }
    }

    /// The element routines of this type.
    pub fn element(self) -> &'static dyn SolidElement {
        match self {
            ElementKind::C3D4 => &*c3d4::C3D4,
            ElementKind::C3D10 => &*c3d10::C3D10,
            ElementKind::C3D6 => &*c3d6::C3D6,
            ElementKind::C3D15 => &*c3d15::C3D15,
            ElementKind::C3D8 => &*c3d8::C3D8,
            ElementKind::C3D8I => &*c3d8::C3D8I,
            ElementKind::C3D20 => &*c3d20::C3D20,
            ElementKind::C3D20R => &*c3d20r::C3D20R,
        }
    }

    /// Number of nodes.
    pub fn node_count(self) -> usize {
        self.element().node_count()
    }

    /// Number of faces (S1…S4 for tetrahedra, S1…S5 for wedges, S1…S6 for hexahedra).
    pub fn face_count(self) -> usize {
        self.element().faces().len()
    }

    /// Face `s` (0 = S1): its local nodes and shape; None for an impossible face.
    pub fn face(self, s: usize) -> Option<&'static FaceDef> {
        self.element().faces().get(s)
    }

    /// Local node indices (0-based) of face `s` (0 = S1), corners then midpoints, in
    /// the Abaqus order (normal into the element); None for an impossible face.
    pub fn face_nodes(self, s: usize) -> Option<&'static [usize]> {
        self.face(s).map(|f| f.nodes)
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
    /// Number of corner nodes (the first nodes of the Abaqus order).
    fn corner_count(&self) -> usize;
    /// The corner pairs of the edge midpoints, in the node order after the corners
    /// (empty for the linear types).
    fn edges(&self) -> &'static [(usize, usize)];
    /// Faces S1, S2, … with their shapes.
    fn faces(&self) -> &'static [FaceDef];
    /// The VTK cell type whose node order is this type's Abaqus order.
    fn vtk_cell(&self) -> u8;
    /// Shape functions `n[i]` and natural derivatives `dn[i] = ∂Nᵢ/∂(ξ, η, ζ)` at `p`.
    fn shape(&self, p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]);
    /// Quadrature rule of the stiffness.
    fn stiffness_rule(&self) -> &[QuadPoint];
    /// Quadrature rule of the mass (and volume).
    fn mass_rule(&self) -> &[QuadPoint];

    /// Number of nodes: corners and edge midpoints.
    fn node_count(&self) -> usize {
        self.corner_count() + self.edges().len()
    }

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
