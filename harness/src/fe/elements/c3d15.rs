//! C3D15: the 15-node quadratic wedge; stiffness by 9 points (the 3-point triangle rule ×
//! 3-point Gauss along the prism, as Abaqus and CalculiX integrate it), mass by the
//! collapsed 3×3 triangle rule × 3-point Gauss (exact for straight prisms). The node
//! order of VTK_QUADRATIC_WEDGE (26) lists the vertical edges' midpoints after the top
//! edges' too, so it is this order.

use std::sync::LazyLock;

use super::isoparametric::Isoparametric;
use super::{rules, wedge, ElementKind};

/// The C3D15 routines.
pub static C3D15: LazyLock<Isoparametric> = LazyLock::new(|| Isoparametric {
    kind: ElementKind::C3D15,
    corner_count: 6,
    edges: &wedge::EDGES,
    faces: &wedge::FACES15,
    // VTK_QUADRATIC_WEDGE: corners as C3D6's, then the mid-edge points on (0,1), (1,2),
    // (2,0), (3,4), (4,5), (5,3), (0,3), (1,4), (2,5): Abaqus's nodes 7–15 in order.
    vtk_cell: 26,
    shape: wedge::shape15,
    stiffness_rule: rules::wedge(&rules::tri_3(), 3),
    mass_rule: rules::wedge(&rules::tri_collapsed_3(), 3),
});
