//! C3D4: the 4-node linear tetrahedron; stiffness by the centroid rule, mass by the
//! symmetric 4-point rule (exact). VTK_TETRA (10) has its node order.

use std::sync::LazyLock;

use super::isoparametric::Isoparametric;
use super::{rules, tet, ElementKind};

/// The C3D4 routines.
pub static C3D4: LazyLock<Isoparametric> = LazyLock::new(|| Isoparametric {
    kind: ElementKind::C3D4,
    corner_count: 4,
    edges: &[],
    faces: &tet::FACES4,
    vtk_cell: 10,
    shape: tet::shape4,
    stiffness_rule: rules::tet_1(),
    mass_rule: rules::tet_4(),
});
