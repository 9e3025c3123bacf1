//! Surface loads on the faces of boxes: consistent nodal forces of a uniform pressure and
//! nodal tributary areas, computed by the element faces' own routines
//! ([`crate::fe::elements::face`]: one place for a face's integrals, whether the face
//! comes from a scene's box or a deck's surface, so both give the same numbers bit for
//! bit).
//!
//! A face is a bilinear quad `[n0, n1, n2, n3]` of global nodes, counter-clockwise seen
//! from outside (as `mesh::Body::face_quads` gives them); reversed, `[n0, n3, n2, n1]`,
//! it is the element face in the Abaqus order (normal into the element, `Face::
//! element_corners`). Pressure follows Abaqus: positive in compression, i.e. it pushes
//! against the outward normal.

use crate::fe::elements::face::{self, tributary_areas, FaceShape, MeshFace};
use crate::fe::mesh::Model;

/// The element face of quad `q` in the Abaqus node order.
fn mesh_face(q: &[usize; 4]) -> MeshFace {
    MeshFace {
        element: 0,
        face: 0,
        nodes: vec![q[0], q[3], q[2], q[1]],
        shape: FaceShape::Quad4,
    }
}

/// Adds the consistent nodal forces of uniform pressure `p` (force/length², positive
/// in compression) on `quads` to `loads` (full DOF vector): fᵢ = −p ∫ Nᵢ n dA.
pub fn add_pressure(model: &Model, quads: &[[usize; 4]], p: f64, loads: &mut [f64]) {
    for q in quads {
        face::add_pressure(&model.nodes, &mesh_face(q), p, loads);
    }
}

/// Tributary area of every node of `quads`: Aᵢ = ∫ Nᵢ dA summed over the quads
/// (a quarter of each rectangular face it touches). Sorted by node id.
pub fn nodal_areas(model: &Model, quads: &[[usize; 4]]) -> Vec<(usize, f64)> {
    let faces: Vec<MeshFace> = quads.iter().map(mesh_face).collect();
    tributary_areas(&faces, &model.nodes).into_iter().collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::mesh::{BoxSpec, Face, Material};
    use nalgebra::Vector3;

    fn model() -> Model {
        let mut m = Model::new(vec![Material::new(1.0, 0.3, 1.0).unwrap()]);
        m.add_box(BoxSpec {
            origin: [1.0, -2.0, 0.5],
            size: [6.0, 3.0, 2.0],
            divisions: [3, 3, 2],
            material: 0,
        })
        .unwrap();
        // Move one interior node of the z-max face off its plane: a warped face.
        let b = m.bodies[0];
        m.nodes[b.node(1, 1, 2)][2] += 0.3;
        m
    }

    fn quads(m: &Model, f: Face) -> Vec<[usize; 4]> {
        m.bodies[0].face_quads(f, &m.elements)
    }

    #[test]
    fn pressure_resultant_is_p_times_area_against_normal() {
        let m = model();
        let p = 2.5;
        for (face, area) in [(Face::XMin, 6.0), (Face::YMax, 12.0), (Face::ZMin, 18.0)] {
            let mut f = vec![0.0; m.n_dofs()];
            add_pressure(&m, &quads(&m, face), p, &mut f);
            let n = face.outward_normal();
            for c in 0..3 {
                let total: f64 = (0..m.nodes.len()).map(|i| f[3 * i + c]).sum();
                // Exact integration: only summation round-off.
                approx::assert_relative_eq!(total, -p * area * n[c], epsilon = 1e-13 * p * area);
            }
            // Resultant acts at the face centroid: Σ xᵢ × fᵢ = c × F.
            let mut moment = Vector3::zeros();
            let mut force = Vector3::zeros();
            for i in 0..m.nodes.len() {
                let fi = Vector3::new(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
                moment += Vector3::from(m.nodes[i]).cross(&fi);
                force += fi;
            }
            let centroid = match face {
                Face::XMin => Vector3::new(1.0, -0.5, 1.5),
                Face::YMax => Vector3::new(4.0, 1.0, 1.5),
                _ => Vector3::new(4.0, -0.5, 0.5),
            };
            assert!((moment - centroid.cross(&force)).norm() < 1e-12 * force.norm());
        }
    }

    #[test]
    fn pressure_on_closed_surface_balances_even_when_warped() {
        // ∮ n dA = 0 for a closed surface; the warped top face must still close it.
        let m = model();
        let mut f = vec![0.0; m.n_dofs()];
        for face in Face::ALL {
            add_pressure(&m, &quads(&m, face), 1.0, &mut f);
        }
        for c in 0..3 {
            let total: f64 = (0..m.nodes.len()).map(|i| f[3 * i + c]).sum();
            assert!(total.abs() < 1e-12, "component {c}: {total}");
        }
    }

    #[test]
    fn nodal_areas_sum_and_corner_values() {
        let m = model();
        let a = nodal_areas(&m, &quads(&m, Face::ZMin));
        assert_eq!(a.len(), 16);
        let total: f64 = a.iter().map(|x| x.1).sum();
        approx::assert_relative_eq!(total, 18.0, max_relative = 1e-14);
        let b = m.bodies[0];
        let area_of = |n: usize| a.iter().find(|x| x.0 == n).unwrap().1;
        // Element face 2×1: corner gets a quarter (0.5), interior node four quarters (2).
        approx::assert_relative_eq!(area_of(b.node(0, 0, 0)), 0.5, max_relative = 1e-14);
        approx::assert_relative_eq!(area_of(b.node(1, 1, 0)), 2.0, max_relative = 1e-14);
        approx::assert_relative_eq!(area_of(b.node(1, 0, 0)), 1.0, max_relative = 1e-14);
    }
}
