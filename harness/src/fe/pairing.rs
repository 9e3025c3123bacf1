//! Node-to-surface pairing for non-conforming contact and ties (small sliding): every
//! node of the slave surface is projected onto the closest master face (local
//! coordinates by Newton on the face's shape functions); its relative displacement is
//! the slave node's minus the master face's interpolated displacement
//! Σᵢ Nᵢ(s) u_master,i, its area is its tributary area on the slave surface, its frame
//! follows the master's outward normal (model.md §3, the contact point's normal and
//! tangential directions). Coincident nodes are the exact special case (one weight 1).
//! Candidate faces come from a uniform bucket grid over the master faces' bounding
//! boxes, so pairing costs O(slave nodes × faces per bucket).

use std::collections::HashMap;

use nalgebra::{Matrix2, Vector2, Vector3};

use crate::fe::elements::face::{tributary_areas, MeshFace};

/// One paired slave node.
#[derive(Debug, Clone, PartialEq)]
pub struct PairedNode {
    /// Slave node index (0-based, into the coordinates).
    pub slave: usize,
    /// Index of the master face (into the master face list).
    pub face: usize,
    /// Natural coordinates of the projection on that face.
    pub s: [f64; 2],
    /// (master node index, shape function value Nᵢ(s)); the weights sum to 1.
    pub weights: Vec<(usize, f64)>,
    /// Unit outward normal of the master face at the projection (from master toward
    /// slave for touching surfaces), then two unit tangents: n, t₁, t₂ right-handed.
    pub frame: [[f64; 3]; 3],
    /// Tributary area of the slave node on the slave surface (length²).
    pub area: f64,
    /// Gap (length): (x_slave − x_projection)·n, positive = open, negative = overclosed.
    pub gap: f64,
}

/// The result of pairing a slave surface with a master surface.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Pairing {
    pub nodes: Vec<PairedNode>,
    /// Slave nodes that project onto no master face within the tolerance.
    pub unmatched: Vec<usize>,
}

impl Pairing {
    /// "N slave nodes project onto no master face (first: a, b, …)", or None.
    pub fn unmatched_report(&self, ids: impl Fn(usize) -> u64) -> Option<String> {
        if self.unmatched.is_empty() {
            return None;
        }
        let first: Vec<String> = self
            .unmatched
            .iter()
            .take(8)
            .map(|&n| ids(n).to_string())
            .collect();
        Some(format!(
            "{} slave nodes project onto no master face (first: {})",
            self.unmatched.len(),
            first.join(", ")
        ))
    }
}

/// Largest distance outside a face's natural domain still counted as on the face
/// (natural units): slave nodes on a master face's edge belong to it.
const ON_FACE: f64 = 1e-6;

/// Pairs every node of `slave` faces with the `master` faces (node coordinates
/// `coords`, length). `tolerance` (length) is the largest |gap| accepted; a node is also
/// unmatched if its projection lands outside every candidate face.
pub fn pair(
    coords: &[[f64; 3]],
    slave: &[MeshFace],
    master: &[MeshFace],
    tolerance: f64,
) -> Pairing {
    let grid = Grid::new(coords, master, tolerance);
    let mut out = Pairing::default();
    for (node, area) in tributary_areas(slave, coords) {
        let p = Vector3::from(coords[node]);
        let mut best: Option<(f64, usize, [f64; 2])> = None;
        for &f in grid.candidates(&p) {
            let Some(s) = project(coords, &master[f], &p) else {
                continue;
            };
            if master[f].shape.outside(s) > ON_FACE {
                continue;
            }
            let d = (p - master[f].at(coords, s).x).norm();
            if d <= tolerance && best.is_none_or(|(bd, _, _)| d < bd) {
                best = Some((d, f, s));
            }
        }
        let Some((_, f, s)) = best else {
            out.unmatched.push(node);
            continue;
        };
        let face = &master[f];
        let fp = face.at(coords, s);
        let Some(n) = fp.outward_normal() else {
            out.unmatched.push(node);
            continue;
        };
        let t1 = (fp.t1 - n * n.dot(&fp.t1)).normalize();
        let t2 = n.cross(&t1);
        out.nodes.push(PairedNode {
            slave: node,
            face: f,
            s,
            weights: face
                .nodes
                .iter()
                .enumerate()
                .map(|(i, &m)| (m, fp.n[i]))
                .collect(),
            frame: [n, t1, t2].map(|v| [v[0], v[1], v[2]]),
            area,
            gap: (p - fp.x).dot(&n),
        });
    }
    out
}

/// Natural coordinates of the point of `face` closest to `p`: Newton (Gauss–Newton on
/// |x(s) − p|²) from the face centre, None if it does not converge.
fn project(coords: &[[f64; 3]], face: &MeshFace, p: &Vector3<f64>) -> Option<[f64; 2]> {
    let mut s = face.shape.centre();
    for _ in 0..30 {
        let fp = face.at(coords, s);
        let r = p - fp.x;
        let a = Matrix2::new(
            fp.t1.dot(&fp.t1),
            fp.t1.dot(&fp.t2),
            fp.t2.dot(&fp.t1),
            fp.t2.dot(&fp.t2),
        );
        let ds = a.lu().solve(&Vector2::new(fp.t1.dot(&r), fp.t2.dot(&r)))?;
        s = [s[0] + ds[0], s[1] + ds[1]];
        if !(s[0].is_finite() && s[1].is_finite()) || s[0].abs() > 10.0 || s[1].abs() > 10.0 {
            return None;
        }
        if ds.norm() < 1e-13 {
            return Some(s);
        }
    }
    Some(s)
}

/// Uniform bucket grid over the master faces' bounding boxes (grown by the tolerance).
struct Grid {
    origin: Vector3<f64>,
    cell: f64,
    buckets: HashMap<[i64; 3], Vec<usize>>,
}

impl Grid {
    fn new(coords: &[[f64; 3]], faces: &[MeshFace], tolerance: f64) -> Grid {
        let boxes: Vec<(Vector3<f64>, Vector3<f64>)> = faces
            .iter()
            .map(|f| {
                let mut lo = Vector3::repeat(f64::INFINITY);
                let mut hi = Vector3::repeat(f64::NEG_INFINITY);
                for &n in &f.nodes {
                    let x = Vector3::from(coords[n]);
                    lo = lo.inf(&x);
                    hi = hi.sup(&x);
                }
                (lo.add_scalar(-tolerance), hi.add_scalar(tolerance))
            })
            .collect();
        let mean =
            boxes.iter().map(|(lo, hi)| (hi - lo).max()).sum::<f64>() / boxes.len().max(1) as f64;
        let cell = if mean.is_finite() && mean > 0.0 {
            mean
        } else {
            1.0
        };
        let origin = boxes
            .iter()
            .fold(Vector3::repeat(f64::INFINITY), |o, (lo, _)| o.inf(lo));
        let origin = if origin.iter().all(|v| v.is_finite()) {
            origin
        } else {
            Vector3::zeros()
        };
        let mut grid = Grid {
            origin,
            cell,
            buckets: HashMap::new(),
        };
        for (f, (lo, hi)) in boxes.iter().enumerate() {
            let (a, b) = (grid.key(lo), grid.key(hi));
            for i in a[0]..=b[0] {
                for j in a[1]..=b[1] {
                    for k in a[2]..=b[2] {
                        grid.buckets.entry([i, j, k]).or_default().push(f);
                    }
                }
            }
        }
        grid
    }

    fn key(&self, x: &Vector3<f64>) -> [i64; 3] {
        let k = (x - self.origin) / self.cell;
        [k[0], k[1], k[2]].map(|v| v.floor().clamp(-1e9, 1e9) as i64)
    }

    fn candidates(&self, p: &Vector3<f64>) -> &[usize] {
        self.buckets
            .get(&self.key(p))
            .map(Vec::as_slice)
            .unwrap_or(&[])
    }
}

#[cfg(test)]
mod tests;
