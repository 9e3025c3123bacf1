//! Ties: two boxes that touch along (part of) a face move as one body there. Their
//! coincident boundary nodes are paired and the assembly gives each pair one set of
//! DOFs ([`crate::fe::assembly::DofMap::new`]): exact node merging, no penalty.
//!
//! The meshes must conform where the boxes touch: every boundary node of one box that
//! lies on the other box's surface needs a coincident node there (else the tie would
//! leave a hanging node, a crack in the mesh).

use std::collections::HashMap;

use thiserror::Error;

use crate::fe::mesh::{Body, Face, MeshError, Model};

/// Errors tying two boxes.
#[derive(Debug, Error, PartialEq)]
pub enum TieError {
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error("bodies {a} and {b} share no node: they do not touch")]
    NotTouching { a: usize, b: usize },
    #[error("node {node} at {at:?} lies on the other body's surface but has no coincident node there (meshes must conform; tolerance {tol})")]
    NonConforming { node: usize, at: [f64; 3], tol: f64 },
}

fn boundary_nodes(b: &Body) -> Vec<usize> {
    let mut v: Vec<usize> = Face::ALL.iter().flat_map(|&f| b.face_nodes(f)).collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// Whether `p` lies on the surface of box `b` (within `tol`).
fn on_surface(b: &Body, p: [f64; 3], tol: f64) -> bool {
    let lo = b.spec.origin;
    let hi = [0, 1, 2].map(|a| lo[a] + b.spec.size[a]);
    let inside = (0..3).all(|a| p[a] >= lo[a] - tol && p[a] <= hi[a] + tol);
    let on_a_face = (0..3).any(|a| (p[a] - lo[a]).abs() <= tol || (p[a] - hi[a]).abs() <= tol);
    inside && on_a_face
}

/// The tied node pairs `[node of a, node of b]` of boxes `a` and `b`: coincident
/// boundary nodes (distance below `rel_tol` × the smallest element edge of either).
pub fn find_ties(
    model: &Model,
    a: usize,
    b: usize,
    rel_tol: f64,
) -> Result<Vec<[usize; 2]>, TieError> {
    let ba = *model.body(a)?;
    let bb = *model.body(b)?;
    let tol = rel_tol * ba.smallest_element_edge().min(bb.smallest_element_edge());
    let cell = |p: [f64; 3]| p.map(|v| (v / tol).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let nodes_b = boundary_nodes(&bb);
    for &n in &nodes_b {
        grid.entry(cell(model.nodes[n])).or_default().push(n);
    }
    let partner = |p: [f64; 3]| -> Option<usize> {
        let c = cell(p);
        let mut best: Option<(f64, usize)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &m in grid
                        .get(&[c[0] + dx, c[1] + dy, c[2] + dz])
                        .into_iter()
                        .flatten()
                    {
                        let q = model.nodes[m];
                        let d = (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt();
                        if d < tol && best.is_none_or(|x| d < x.0) {
                            best = Some((d, m));
                        }
                    }
                }
            }
        }
        best.map(|x| x.1)
    };
    let mut out = Vec::new();
    for n in boundary_nodes(&ba) {
        let p = model.nodes[n];
        match partner(p) {
            Some(m) => out.push([n, m]),
            None if on_surface(&bb, p, tol) => {
                return Err(TieError::NonConforming {
                    node: n,
                    at: p,
                    tol,
                })
            }
            None => {}
        }
    }
    if out.is_empty() {
        return Err(TieError::NotTouching { a, b });
    }
    // The other direction: b's nodes on a's surface must all be paired too.
    let paired: std::collections::HashSet<usize> = out.iter().map(|t| t[1]).collect();
    for n in nodes_b {
        let p = model.nodes[n];
        if !paired.contains(&n) && on_surface(&ba, p, tol) {
            return Err(TieError::NonConforming {
                node: n,
                at: p,
                tol,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::mesh::{BoxSpec, Material};

    fn steel() -> Material {
        Material::new(210_000.0, 0.3, 7.85e-9).unwrap()
    }

    fn bx(m: &mut Model, origin: [f64; 3], size: [f64; 3], div: [usize; 3]) -> usize {
        m.add_box(BoxSpec {
            origin,
            size,
            divisions: div,
            material: 0,
        })
        .unwrap()
    }

    #[test]
    fn partial_faces_tie_and_non_conforming_meshes_are_errors() {
        let mut m = Model::new(vec![steel()]);
        // A 2 mm thick jaw on the upper part of a 4 mm bar's end face.
        let bar = bx(&mut m, [0.0; 3], [10.0, 2.0, 4.0], [5, 2, 4]);
        let jaw = bx(&mut m, [10.0, 0.0, 2.0], [6.0, 2.0, 2.0], [3, 2, 2]);
        let ties = find_ties(&m, bar, jaw, 1e-6).unwrap();
        assert_eq!(ties.len(), 3 * 3);
        for [p, q] in &ties {
            assert_eq!(m.nodes[*p], m.nodes[*q]);
            assert!(m.nodes[*p][2] >= 2.0);
        }
        // A jaw meshed with 3 divisions through 2 mm: nodes at z = 2.67 have no partner.
        let bad = bx(&mut m, [10.0, 0.0, 2.0], [6.0, 2.0, 2.0], [3, 2, 3]);
        assert!(matches!(
            find_ties(&m, bar, bad, 1e-6),
            Err(TieError::NonConforming { .. })
        ));
        let far = bx(&mut m, [30.0, 0.0, 0.0], [1.0; 3], [1; 3]);
        assert_eq!(
            find_ties(&m, bar, far, 1e-6),
            Err(TieError::NotTouching { a: bar, b: far })
        );
    }
}
