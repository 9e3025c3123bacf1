//! Contact points at the interface of two stacked bodies: coincident node pairs, each
//! with a local frame and a tributary area.
//!
//! Pair `[lower, upper]`: `lower` is on the lower body's z-max face, `upper` on the
//! upper body's z-min face. Frame columns (global coordinates): n = +z (outward normal
//! of the lower body, pointing into the upper one), t₁ = +x, t₂ = +y (right-handed:
//! n × t₁ = t₂). Relative displacement δ = u_upper − u_lower; its local components are
//! Qᵀδ, so δ_n > 0 opens the gap and the Abaqus overclosure is −δ_n. Used with
//! [`crate::fe::pair_blocks`], whose pair convention (δ = u_b − u_a) matches.

use std::collections::HashMap;

use nalgebra::Matrix3;
use thiserror::Error;

use crate::fe::mesh::{Face, MeshError, Model};
use crate::fe::surface::nodal_areas;

/// Errors finding contact pairs.
#[derive(Debug, Error, PartialEq)]
pub enum PairError {
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error("bodies {lower} and {upper} do not touch: top z {top} vs bottom z {bottom}")]
    NotTouching {
        lower: usize,
        upper: usize,
        top: f64,
        bottom: f64,
    },
    #[error("node {node} at {at:?} on the interface has no coincident partner (tolerance {tol})")]
    Unmatched { node: usize, at: [f64; 3], tol: f64 },
}

/// One contact point: two coincident nodes, local frame Q = [n t₁ t₂], tributary area.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPair {
    /// `[lower, upper]` node ids.
    pub nodes: [usize; 2],
    /// Columns: normal n, tangents t₁, t₂ (global coordinates).
    pub frame: Matrix3<f64>,
    /// Tributary area (length²) on the lower body's face.
    pub area: f64,
}

/// The element faces of `lower`'s z-max face whose centre `c` has `keep(c)`: the
/// contact face of an interface, counter-clockwise quads as `Body::face_quads` gives.
pub fn contact_quads(
    model: &Model,
    lower: usize,
    keep: &dyn Fn([f64; 3]) -> bool,
) -> Result<Vec<[usize; 4]>, PairError> {
    Ok(model
        .body(lower)?
        .face_quads(Face::ZMax, &model.elements)
        .into_iter()
        .filter(|q| {
            let c =
                std::array::from_fn(|a| q.iter().map(|&n| model.nodes[n][a]).sum::<f64>() / 4.0);
            keep(c)
        })
        .collect())
}

/// Pairs the coincident nodes of `lower`'s z-max face and `upper`'s z-min face.
/// Nodes match when their positions differ by less than `rel_tol` times the smallest
/// in-plane element size; every node of the lower face must find a partner (the upper
/// face may be larger). Sorted by lower node id.
pub fn find_pairs(
    model: &Model,
    lower: usize,
    upper: usize,
    rel_tol: f64,
) -> Result<Vec<ContactPair>, PairError> {
    find_pairs_where(model, lower, upper, rel_tol, &|_| true)
}

/// As [`find_pairs`], on the element faces of the lower body's z-max face whose centre
/// `c` has `keep(c)`: areas and points come from those faces only (a face with a
/// relieved region).
pub fn find_pairs_where(
    model: &Model,
    lower: usize,
    upper: usize,
    rel_tol: f64,
    keep: &dyn Fn([f64; 3]) -> bool,
) -> Result<Vec<ContactPair>, PairError> {
    let lo = *model.body(lower)?;
    let hi = *model.body(upper)?;
    let h = |b: &crate::fe::mesh::Body| b.smallest_edge(0).min(b.smallest_edge(1));
    let tol = rel_tol * h(&lo).min(h(&hi));
    let top = lo.spec.origin[2] + lo.spec.size[2];
    let bottom = hi.spec.origin[2];
    if (top - bottom).abs() > tol {
        return Err(PairError::NotTouching {
            lower,
            upper,
            top,
            bottom,
        });
    }
    // Hash the upper face's nodes on a grid of cell size `tol`; a match lies in one of
    // the 3×3×3 neighbouring cells.
    let cell = |p: [f64; 3]| p.map(|v| (v / tol).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for n in hi.face_nodes(Face::ZMin) {
        grid.entry(cell(model.nodes[n])).or_default().push(n);
    }
    let quads = contact_quads(model, lower, keep)?;
    let areas = nodal_areas(model, &quads);
    let frame = Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0);
    let mut out = Vec::with_capacity(areas.len());
    for (node, area) in areas {
        let p = model.nodes[node];
        let c = cell(p);
        let mut best: Option<(f64, usize)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(cands) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &m in cands {
                        let q = model.nodes[m];
                        let d =
                            ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2))
                                .sqrt();
                        if d < tol && best.is_none_or(|b| d < b.0) {
                            best = Some((d, m));
                        }
                    }
                }
            }
        }
        let (_, partner) = best.ok_or(PairError::Unmatched { node, at: p, tol })?;
        out.push(ContactPair {
            nodes: [node, partner],
            frame,
            area,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::mesh::{BoxSpec, Layer, Material};

    fn three_beams() -> Model {
        let mut m = Model::new(vec![Material::new(210_000.0, 0.3, 7.85e-9).unwrap()]);
        let l = |t, nz| Layer {
            thickness: t,
            nz,
            material: 0,
        };
        m.add_stack(
            [0.0, 0.0, 0.0],
            [60.0, 10.0],
            [12, 3],
            &[l(2.0, 2), l(1.0, 1), l(2.0, 2)],
        )
        .unwrap();
        m
    }

    #[test]
    fn areas_sum_to_interface_area_and_pairs_coincide() {
        let m = three_beams();
        for (lo, hi) in [(0, 1), (1, 2)] {
            let pairs = find_pairs(&m, lo, hi, 1e-6).unwrap();
            assert_eq!(pairs.len(), 13 * 4);
            let total: f64 = pairs.iter().map(|p| p.area).sum();
            approx::assert_relative_eq!(total, 600.0, max_relative = 1e-14);
            for p in &pairs {
                assert_ne!(p.nodes[0], p.nodes[1]);
                assert_eq!(m.nodes[p.nodes[0]], m.nodes[p.nodes[1]]);
                assert!(m.bodies[lo].face_nodes(Face::ZMax).contains(&p.nodes[0]));
                assert!(m.bodies[hi].face_nodes(Face::ZMin).contains(&p.nodes[1]));
                // Orthonormal right-handed frame with n = +z.
                assert!((p.frame.transpose() * p.frame - Matrix3::identity()).norm() < 1e-15);
                approx::assert_relative_eq!(p.frame.determinant(), 1.0);
                assert_eq!(p.frame.column(0).as_slice(), &[0.0, 0.0, 1.0]);
            }
            // Element face 5 × 10/3: corner node a quarter, interior node a full face.
            let h = 5.0 * 10.0 / 3.0;
            let b = m.bodies[lo];
            let area_of = |n: usize| pairs.iter().find(|p| p.nodes[0] == n).unwrap().area;
            approx::assert_relative_eq!(
                area_of(b.node(0, 0, b.spec.divisions[2])),
                h / 4.0,
                max_relative = 1e-14
            );
            approx::assert_relative_eq!(
                area_of(b.node(3, 1, b.spec.divisions[2])),
                h,
                max_relative = 1e-14
            );
        }
    }

    #[test]
    fn mismatched_meshes_and_gaps_are_errors() {
        let mut m = Model::new(vec![Material::new(1.0, 0.3, 1.0).unwrap()]);
        m.add_box(BoxSpec {
            origin: [0.0; 3],
            size: [4.0, 4.0, 1.0],
            divisions: [4, 4, 1],
            material: 0,
        })
        .unwrap();
        // Coarser upper body: lower face nodes at odd grid lines have no partner.
        m.add_box(BoxSpec {
            origin: [0.0, 0.0, 1.0],
            size: [4.0, 4.0, 1.0],
            divisions: [2, 2, 1],
            material: 0,
        })
        .unwrap();
        // Separated body.
        m.add_box(BoxSpec {
            origin: [0.0, 0.0, 2.5],
            size: [4.0, 4.0, 1.0],
            divisions: [4, 4, 1],
            material: 0,
        })
        .unwrap();
        assert!(matches!(
            find_pairs(&m, 0, 1, 1e-6),
            Err(PairError::Unmatched { .. })
        ));
        assert!(matches!(
            find_pairs(&m, 1, 2, 1e-6),
            Err(PairError::NotTouching { .. })
        ));
        assert!(matches!(
            find_pairs(&m, 0, 7, 1e-6),
            Err(PairError::Mesh(MeshError::UnknownBody(7)))
        ));
    }
}
