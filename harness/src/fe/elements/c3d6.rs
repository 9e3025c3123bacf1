//! C3D6: the 6-node linear wedge; stiffness by 2 points (the triangle's centroid × 2-point
//! Gauss along the prism, as Abaqus and CalculiX integrate it), mass by the 3-point
//! triangle rule × 2-point Gauss (exact for straight prisms). VTK_WEDGE (13) has its node
//! order.

use std::sync::LazyLock;

use super::isoparametric::Isoparametric;
use super::{rules, wedge, ElementKind};

/// The C3D6 routines.
pub static C3D6: LazyLock<Isoparametric> = LazyLock::new(|| Isoparametric {
    kind: ElementKind::C3D6,
    corner_count: 6,
    edges: &[],
    faces: &wedge::FACES6,
    // VTK_WEDGE: VTK's points 0 (0,0,0), 1 (1,0,0), 2 (0,1,0) and 3–5 above them are
    // Abaqus's nodes 1–6 in order (positive Jacobian), so the cell is written as read.
    vtk_cell: 13,
    shape: wedge::shape6,
    stiffness_rule: rules::wedge(&rules::tri_1(), 2),
    mass_rule: rules::wedge(&rules::tri_3(), 2),
});
