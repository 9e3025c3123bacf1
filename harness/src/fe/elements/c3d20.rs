//! C3D20: the 20-node serendipity hexahedron, 3×3×3 Gauss for stiffness and mass.
//! VTK_QUADRATIC_HEXAHEDRON (25) has its node order.

use std::sync::LazyLock;

use super::isoparametric::Isoparametric;
use super::{hex, rules, ElementKind};

/// The C3D20 routines.
pub static C3D20: LazyLock<Isoparametric> = LazyLock::new(|| Isoparametric {
    kind: ElementKind::C3D20,
    corner_count: 8,
    edges: &hex::EDGES,
    faces: &hex::FACES20,
    vtk_cell: 25,
    shape: hex::shape20,
    stiffness_rule: rules::hex_gauss(3),
    mass_rule: rules::hex_gauss(3),
});
