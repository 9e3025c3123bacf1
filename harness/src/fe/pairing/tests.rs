//! Pairing tests: non-conforming boxes of every element type (all slave nodes on the
//! master, weights interpolating the slave position, areas summing to the contact
//! area), coincident meshes (one weight 1), and slave nodes off the master reported.

use super::*;
use crate::fe::elements::box_mesh::{box_mesh, SolidMesh};
use crate::fe::elements::ElementKind;

/// The faces of `mesh` (node indices offset by `offset`) lying in the plane z = `z`.
fn faces_at(mesh: &SolidMesh, offset: usize, z: f64) -> Vec<MeshFace> {
    let mut out = Vec::new();
    for (e, conn) in mesh.elements.iter().enumerate() {
        let conn: Vec<usize> = conn.iter().map(|n| n + offset).collect();
        for s in 0..mesh.kind.face_count() {
            let f = MeshFace::new(mesh.kind, e, &conn, s).unwrap();
            if f.nodes
                .iter()
                .all(|&n| (mesh.nodes[n - offset][2] - z).abs() < 1e-12)
            {
                out.push(f);
            }
        }
    }
    out
}

/// A lower box [0,2]×[0,1]×[0,1] (master: its top) and an upper box of a different
/// mesh, footprint [x0, x0+1]×[0,1], on top of it (slave: its bottom).
fn stack(
    kind: ElementKind,
    x0: f64,
    upper_cells: [usize; 3],
) -> (Vec<[f64; 3]>, Vec<MeshFace>, Vec<MeshFace>) {
    let lower = box_mesh(kind, [2.0, 1.0, 1.0], [3, 2, 1], 0.0, 1);
    let mut upper = box_mesh(kind, [1.0, 1.0, 0.5], upper_cells, 0.0, 1);
    upper.nodes.iter_mut().for_each(|p| {
        p[0] += x0;
        p[2] += 1.0;
    });
    let master = faces_at(&lower, 0, 1.0);
    let slave = faces_at(&upper, lower.nodes.len(), 1.0);
    let mut coords = lower.nodes.clone();
    coords.extend_from_slice(&upper.nodes);
    (coords, slave, master)
}

#[test]
fn non_conforming_faces_pair_every_slave_node() {
    for kind in ElementKind::ALL {
        let (coords, slave, master) = stack(kind, 0.5, [4, 3, 1]);
        let p = pair(&coords, &slave, &master, 1e-6);
        assert!(p.unmatched.is_empty(), "{kind}: {:?}", p.unmatched);
        let area: f64 = p.nodes.iter().map(|n| n.area).sum();
        approx::assert_relative_eq!(area, 1.0, max_relative = 1e-12);
        for n in &p.nodes {
            let sum: f64 = n.weights.iter().map(|w| w.1).sum();
            approx::assert_relative_eq!(sum, 1.0, epsilon = 1e-12);
            let x: Vector3<f64> = n
                .weights
                .iter()
                .map(|&(m, w)| Vector3::from(coords[m]) * w)
                .sum();
            assert!(
                (x - Vector3::from(coords[n.slave])).norm() < 1e-10,
                "{kind}"
            );
            assert!(n.gap.abs() < 1e-12);
            assert!(
                (Vector3::from(n.frame[0]) - Vector3::z()).norm() < 1e-12,
                "{kind}"
            );
            let t = n.frame.map(Vector3::from);
            assert!((t[0].cross(&t[1]) - t[2]).norm() < 1e-12);
        }
    }
}

#[test]
fn coincident_nodes_get_a_single_unit_weight() {
    // The upper box is the lower mesh shifted up: every slave node sits on a master node.
    let lower = box_mesh(ElementKind::C3D8, [2.0, 1.0, 1.0], [3, 2, 1], 0.0, 1);
    let mut upper = lower.clone();
    upper.nodes.iter_mut().for_each(|p| p[2] += 1.0);
    let master = faces_at(&lower, 0, 1.0);
    let slave = faces_at(&upper, lower.nodes.len(), 1.0);
    let mut coords = lower.nodes.clone();
    coords.extend_from_slice(&upper.nodes);
    let p = pair(&coords, &slave, &master, 1e-6);
    assert_eq!(p.nodes.len(), 12);
    for n in &p.nodes {
        let big: Vec<f64> = n
            .weights
            .iter()
            .map(|w| w.1)
            .filter(|w| w.abs() > 1e-12)
            .collect();
        assert_eq!(big.len(), 1);
        approx::assert_relative_eq!(big[0], 1.0, epsilon = 1e-12);
    }
}

#[test]
fn slave_nodes_off_the_master_are_reported() {
    // Upper footprint [1.5, 2.5]: the nodes with x > 2 have no master face.
    let (coords, slave, master) = stack(ElementKind::C3D20, 1.5, [4, 2, 1]);
    let p = pair(&coords, &slave, &master, 1e-6);
    let off: Vec<usize> = p.unmatched.clone();
    assert!(!off.is_empty());
    assert!(off.iter().all(|&n| coords[n][0] > 2.0 + 1e-9));
    assert!(p.nodes.iter().all(|n| coords[n.slave][0] <= 2.0 + 1e-9));
    let msg = p.unmatched_report(|n| n as u64 + 1).unwrap();
    assert!(
        msg.starts_with(&format!(
            "{} slave nodes project onto no master face",
            off.len()
        )),
        "{msg}"
    );
    // A gap larger than the tolerance leaves every node unmatched.
    let lifted: Vec<[f64; 3]> = coords
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if slave.iter().any(|f| f.nodes.contains(&i)) {
                [p[0], p[1], p[2] + 0.1]
            } else {
                *p
            }
        })
        .collect();
    let p = pair(&lifted, &slave, &master, 0.01);
    assert!(p.nodes.is_empty());
    // Within the tolerance, the gap is measured (open: positive).
    let p = pair(&lifted, &slave, &master, 0.2);
    assert!(p.nodes.iter().all(|n| (n.gap - 0.1).abs() < 1e-12));
}
