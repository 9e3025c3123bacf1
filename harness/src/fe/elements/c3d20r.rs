//! C3D20R: the 20-node hexahedron with reduced (2×2×2) integration of the stiffness;
//! mass by 3×3×3 Gauss. VTK_QUADRATIC_HEXAHEDRON (25) has its node order.

use std::sync::LazyLock;

use super::isoparametric::Isoparametric;
use super::{hex, rules, ElementKind};

/// The C3D20R routines.
pub static C3D20R: LazyLock<Isoparametric> = LazyLock::new(|| Isoparametric {
    kind: ElementKind::C3D20R,
    corner_count: 8,
    edges: &hex::EDGES,
    faces: &hex::FACES20,
    vtk_cell: 25,
    shape: hex::shape20,
    stiffness_rule: rules::hex_gauss(2),
    mass_rule: rules::hex_gauss(3),
});
