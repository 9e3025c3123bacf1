//! C3D10: the 10-node quadratic tetrahedron; stiffness by the 4-point rule, mass by the
//! collapsed 4×4×4 rule (exact for straight edges). VTK_QUADRATIC_TETRA (24) has its node
//! order.

use std::sync::LazyLock;

use super::isoparametric::Isoparametric;
use super::{rules, tet, ElementKind};

/// The C3D10 routines.
pub static C3D10: LazyLock<Isoparametric> = LazyLock::new(|| Isoparametric {
    kind: ElementKind::C3D10,
    corner_count: 4,
    edges: &tet::EDGES,
    faces: &tet::FACES10,
    vtk_cell: 24,
    shape: tet::shape10,
    stiffness_rule: rules::tet_4(),
    mass_rule: rules::tet_collapsed_4(),
});
