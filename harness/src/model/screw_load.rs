//! Where a screw's axial force enters a box body: at one node, as a uniform pressure on
//! a bearing ring (a head or nut on its bearing face), or as a uniform force per volume
//! in the cylinder of the engaged thread. The last two are integrated over the body's
//! hexahedra with their own shape functions (the consistent nodal loads of the uniform
//! distribution, by midpoint sampling of each element face or element), and the nodal
//! weights are scaled to sum to one, so the resultant is exactly the screw force
//! wherever the mesh cuts the ring or the cylinder. The part of a region outside the
//! body (a ring cut by a symmetry plane) carries nothing: the screw's `share` says
//! which fraction of the force the model holds.

use std::collections::BTreeMap;

use nalgebra::{Matrix3, Vector3};

use crate::fe::hex8::{shape, CORNERS};
use crate::fe::mesh::{Body, Model};

/// Midpoint samples per direction of an element face (ring) or element (thread).
const FACE_SAMPLES: usize = 24;
const VOLUME_SAMPLES: usize = 12;

/// How one end of a screw loads its body. Lengths in the scene's unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spread {
    /// At the body's node nearest the end's point.
    Node,
    /// Uniform pressure on the element faces in the plane through the point normal to
    /// the axis, for inner radius ≤ r ≤ outer radius from the axis.
    Ring { inner: f64, outer: f64 },
    /// Uniform force per volume for r ≤ `radius`, from the point over `length`
    /// towards the screw's other end.
    Thread { radius: f64, length: f64 },
}

/// Nodal weights (summing to 1) of a unit axial force at `at` on the axis `axis`
/// (unit vector from this end towards the other end) spread by `spread` over the
/// elements of `bodies`. `Err` names what is wrong when the region misses them.
pub fn weights(
    model: &Model,
    bodies: &[Body],
    at: [f64; 3],
    axis: [f64; 3],
    spread: Spread,
) -> Result<Vec<(usize, f64)>, String> {
    let at = Vector3::from(at);
    let axis = Vector3::from(axis).normalize();
    let elements = || {
        bodies
            .iter()
            .flat_map(|b| b.first_element..b.first_element + b.n_elements())
    };
    let mut acc = BTreeMap::new();
    match spread {
        Spread::Node => return Ok(vec![(nearest_node(model, bodies, at), 1.0)]),
        Spread::Ring { inner, outer } => {
            let tol = 1e-6
                * bodies
                    .iter()
                    .map(Body::smallest_element_edge)
                    .fold(f64::INFINITY, f64::min);
            for e in elements() {
                ring_element(model, e, at, axis, (inner, outer, tol), &mut acc);
            }
            if acc.is_empty() {
                return Err(format!(
                    "no sample of the element faces in the plane through {:?} normal to the axis falls within the ring (diameters {}…{}): no face lies there, or the ring is narrower than the sampling (1/{FACE_SAMPLES} of an element)",
                    at.as_slice(),
                    2.0 * inner,
                    2.0 * outer
                ));
            }
        }
        Spread::Thread { radius, length } => {
            for e in elements() {
                thread_element(model, e, at, axis, (radius, length), &mut acc);
            }
            if acc.is_empty() {
                return Err(format!(
                    "the thread (diameter {}, length {length} from {:?}) lies outside the body",
                    2.0 * radius,
                    at.as_slice()
                ));
            }
        }
    }
    let total: f64 = acc.values().sum();
    Ok(acc.into_iter().map(|(n, w)| (n, w / total)).collect())
}

/// The bodies' node nearest `p`.
fn nearest_node(model: &Model, bodies: &[Body], p: Vector3<f64>) -> usize {
    bodies
        .iter()
        .flat_map(|b| b.first_node..b.first_node + b.n_nodes())
        .min_by(|&a, &b| {
            let d = |n: usize| (Vector3::from(model.nodes[n]) - p).norm_squared();
            d(a).total_cmp(&d(b))
        })
        .expect("a box has nodes")
}

/// ∂x/∂ξ_q at a natural point with shape-function derivatives `dn`.
fn tangent(dn: &[[f64; 3]; 8], x: &[Vector3<f64>], q: usize) -> Vector3<f64> {
    (0..8).map(|i| dn[i][q] * x[i]).sum()
}

/// Distance of `x` from the axis and its position along it, from `at`.
fn cylindrical(x: Vector3<f64>, at: Vector3<f64>, axis: Vector3<f64>) -> (f64, f64) {
    let d = x - at;
    let s = d.dot(&axis);
    ((d - s * axis).norm(), s)
}

/// Adds the ring pressure's share of element `e`'s faces that lie in the plane.
fn ring_element(
    model: &Model,
    e: usize,
    at: Vector3<f64>,
    axis: Vector3<f64>,
    (inner, outer, tol): (f64, f64, f64),
    acc: &mut BTreeMap<usize, f64>,
) {
    let el = &model.elements[e];
    let x: Vec<Vector3<f64>> = el.nodes.iter().map(|&n| model.nodes[n].into()).collect();
    let h = 2.0 / FACE_SAMPLES as f64;
    for k in 0..3 {
        for side in [-1.0, 1.0] {
            let in_plane = (0..8)
                .filter(|&i| CORNERS[i][k] == side)
                .all(|i| (x[i] - at).dot(&axis).abs() <= tol);
            if !in_plane {
                continue;
            }
            let (u, v) = ((k + 1) % 3, (k + 2) % 3);
            for a in 0..FACE_SAMPLES {
                for b in 0..FACE_SAMPLES {
                    let mut p = [0.0; 3];
                    p[k] = side;
                    p[u] = -1.0 + h * (a as f64 + 0.5);
                    p[v] = -1.0 + h * (b as f64 + 0.5);
                    let (n, dn) = shape(p);
                    let pos: Vector3<f64> = (0..8).map(|i| n[i] * x[i]).sum();
                    let r = cylindrical(pos, at, axis).0;
                    if r < inner || r > outer {
                        continue;
                    }
                    let da = tangent(&dn, &x, u).cross(&tangent(&dn, &x, v)).norm() * h * h;
                    // The other face's nodes have Nᵢ = 0 here.
                    for i in (0..8).filter(|&i| n[i] > 0.0) {
                        *acc.entry(el.nodes[i]).or_default() += n[i] * da;
                    }
                }
            }
        }
    }
}

/// Adds the thread's force per volume inside element `e`.
fn thread_element(
    model: &Model,
    e: usize,
    at: Vector3<f64>,
    axis: Vector3<f64>,
    (radius, length): (f64, f64),
    acc: &mut BTreeMap<usize, f64>,
) {
    let el = &model.elements[e];
    let x: Vec<Vector3<f64>> = el.nodes.iter().map(|&n| model.nodes[n].into()).collect();
    // Quick reject by the element's bounding box against the cylinder's.
    let lo = x
        .iter()
        .fold(Vector3::repeat(f64::INFINITY), |m, c| m.inf(c));
    let hi = x
        .iter()
        .fold(Vector3::repeat(f64::NEG_INFINITY), |m, c| m.sup(c));
    let end = at + length * axis;
    let pad = Vector3::repeat(radius);
    if (0..3).any(|c| hi[c] < at[c].min(end[c]) - pad[c] || lo[c] > at[c].max(end[c]) + pad[c]) {
        return;
    }
    let h = 2.0 / VOLUME_SAMPLES as f64;
    let mid = |a: usize| -1.0 + h * (a as f64 + 0.5);
    for a in 0..VOLUME_SAMPLES {
        for b in 0..VOLUME_SAMPLES {
            for c in 0..VOLUME_SAMPLES {
                let p = [mid(a), mid(b), mid(c)];
                let (n, dn) = shape(p);
                let pos: Vector3<f64> = (0..8).map(|i| n[i] * x[i]).sum();
                let (r, s) = cylindrical(pos, at, axis);
                if r > radius || s < 0.0 || s > length {
                    continue;
                }
                let j = Matrix3::from_columns(&[0, 1, 2].map(|q| tangent(&dn, &x, q)));
                let dv = j.determinant().abs() * h * h * h;
                for i in 0..8 {
                    *acc.entry(el.nodes[i]).or_default() += n[i] * dv;
                }
            }
        }
    }
}

#[cfg(test)]
#[path = "screw_load_tests.rs"]
mod tests;
