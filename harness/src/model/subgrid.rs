//! Sub-grid samples of a contact point's tributary area.
//!
//! A node-based contact point stands for its tributary area Aᵢ = ∫ Nᵢ dA (the quarters
//! of the element faces around the node). Evaluated at the node alone, the point carries
//! one pressure over all of Aᵢ, so the row of points at the edge of a contact patch
//! (where the pressure falls to zero inside an element) carries a low pressure over a
//! whole element width: its slip, and the loss it adds, scale with the element size.
//! Sampling the tributary area on an s × s grid per quarter face, with the overclosure
//! interpolated bilinearly from the face's four nodes, puts the patch edge inside the
//! element and makes the point's law the area average of the law over its samples.

use crate::fe::mesh::Model;

/// One sample of a point's tributary area: the overclosure there is Σ w·h of the face's
/// corner points, and it stands for `fraction` of the point's area.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaSample {
    /// (contact point index, bilinear weight Nⱼ) of the face's four corners.
    pub corners: [(usize, f64); 4],
    /// Share of the point's tributary area (the fractions of a point sum to 1).
    pub fraction: f64,
}

/// Parametric corners of a bilinear quad in `Body::face_quads` order.
const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Samples for the points of one contact face: `quads` its element faces, `point_of`
/// maps a node of the face to its contact point index (`None`: no point there, e.g. a
/// node with every DOF fixed; its samples then use the sampled point's own value),
/// `per_side` the samples per quarter face and direction (s). Returns (point index,
/// sampled area, samples) for every point on the face; fractions come from the true
/// area element |∂x/∂ξ × ∂x/∂η| at each sample (midpoint rule in the quarter, exact
/// for plane faces, where |J| is linear in ξ and η).
pub fn face_samples(
    model: &Model,
    quads: &[[usize; 4]],
    point_of: &dyn Fn(usize) -> Option<usize>,
    per_side: usize,
) -> Vec<(usize, f64, Vec<AreaSample>)> {
    use std::collections::BTreeMap;
    let s = per_side.max(1);
    let mut acc: BTreeMap<usize, Vec<(AreaSample, f64)>> = BTreeMap::new();
    for q in quads {
        let x = q.map(|n| nalgebra::Vector3::from(model.nodes[n]));
        for (ci, corner) in CORNERS.iter().enumerate() {
            let Some(own) = point_of(q[ci]) else {
                continue;
            };
            for a in 0..s {
                for b in 0..s {
                    // Midpoints of an s × s grid on the quarter between the face's
                    // centre (0, 0) and this corner.
                    let xi = corner[0] * (a as f64 + 0.5) / s as f64;
                    let eta = corner[1] * (b as f64 + 0.5) / s as f64;
                    let mut dxdxi = nalgebra::Vector3::zeros();
                    let mut dxdeta = nalgebra::Vector3::zeros();
                    let corners = std::array::from_fn(|j| {
                        let c = CORNERS[j];
                        dxdxi += x[j] * (0.25 * c[0] * (1.0 + c[1] * eta));
                        dxdeta += x[j] * (0.25 * (1.0 + c[0] * xi) * c[1]);
                        let w = 0.25 * (1.0 + c[0] * xi) * (1.0 + c[1] * eta);
                        (point_of(q[j]).unwrap_or(own), w)
                    });
                    // Parametric cell area (1/s)² of the quarter's unit square.
                    let da = dxdxi.cross(&dxdeta).norm() / (s * s) as f64;
                    acc.entry(own).or_default().push((
                        AreaSample {
                            corners,
                            fraction: 0.0,
                        },
                        da,
                    ));
                }
            }
        }
    }
    acc.into_iter()
        .map(|(point, list)| {
            let total: f64 = list.iter().map(|(_, da)| da).sum();
            let samples = list
                .into_iter()
                .map(|(mut smp, da)| {
                    smp.fraction = da / total;
                    smp
                })
                .collect();
            (point, total, samples)
        })
        .collect()
}

/// Node pairs whose matrix entries the coupling of sampled points needs: for point k
/// (nodes `[lower, upper]`, `points[k].0`) and each other point j at a corner of its
/// samples, all four node combinations of k and j (deduplicated).
pub fn coupling_pairs<T>(
    points: &[([usize; 2], T, f64, usize)],
    samples: &[Vec<AreaSample>],
) -> Vec<[usize; 2]> {
    let mut out = std::collections::BTreeSet::new();
    for (k, list) in samples.iter().enumerate() {
        for j in list.iter().flat_map(|s| s.corners.map(|c| c.0)) {
            if j != k {
                for a in points[k].0 {
                    for b in points[j].0 {
                        out.insert([a, b]);
                    }
                }
            }
        }
    }
    out.into_iter().collect()
}

/// The overclosure at a sample from the points' overclosures `h`.
pub fn sample_value(s: &AreaSample, h: &[f64]) -> f64 {
    s.corners.iter().map(|&(j, w)| w * h[j]).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::mesh::{BoxSpec, Face, Material};
    use crate::fe::surface::nodal_areas;
    use std::collections::BTreeMap;

    /// A 3 × 2 box face with uneven element sizes (graded in x), one point per node.
    fn face(warp: bool) -> (Model, Vec<[usize; 4]>) {
        let mut m = Model::new(vec![Material::new(1.0, 0.3, 1.0).unwrap()]);
        m.add_box(BoxSpec {
            origin: [0.0, 0.0, 0.0],
            size: [6.0, 3.0, 1.0],
            divisions: [3, 2, 1],
            material: 0,
        })
        .unwrap();
        let b = m.bodies[0];
        for j in 0..=2 {
            m.nodes[b.node(1, j, 1)][0] = 1.5; // elements 1.5, 2.5 and 2 long
            if warp {
                m.nodes[b.node(2, j, 1)][0] += 0.3 * j as f64; // a trapezoid column
            }
        }
        let q = m.bodies[0].face_quads(Face::ZMax, &m.elements);
        (m, q)
    }

    #[test]
    fn fractions_sum_to_one_and_sample_areas_to_the_tributary_area() {
        for warp in [false, true] {
            let (m, quads) = face(warp);
            let areas: BTreeMap<usize, f64> = nodal_areas(&m, &quads).into_iter().collect();
            let point_of = |n: usize| Some(n);
            for s in [1, 3, 8] {
                let all = face_samples(&m, &quads, &point_of, s);
                // The quarters partition the face: 6 × 3 (the trapezoid column keeps
                // its area: its sides move by 0, 0.3, 0.6 in x, linearly in y).
                let total: f64 = all.iter().map(|x| x.1).sum();
                approx::assert_relative_eq!(total, 18.0, max_relative = 1e-13);
                for (point, area, list) in all {
                    let sum: f64 = list.iter().map(|x| x.fraction).sum();
                    approx::assert_relative_eq!(sum, 1.0, max_relative = 1e-14);
                    assert!(list.iter().all(|x| x.fraction > 0.0));
                    for x in &list {
                        let w: f64 = x.corners.iter().map(|c| c.1).sum();
                        approx::assert_relative_eq!(w, 1.0, max_relative = 1e-14);
                    }
                    // On rectangles the quarters are the tributary areas ∫ Nᵢ dA of
                    // `nodal_areas` (on the trapezoid they differ slightly).
                    if !warp {
                        approx::assert_relative_eq!(area, areas[&point], max_relative = 1e-13);
                    }
                }
            }
        }
    }

    /// On rectangles the samples integrate a bilinear overclosure exactly: the
    /// average over a point's area equals ∫ h dA / Aᵢ over its tributary cell (half an
    /// element to each side), in closed form.
    #[test]
    fn samples_average_a_bilinear_field_exactly_over_the_tributary_area() {
        let (m, quads) = face(false);
        let h = |x: [f64; 3]| 0.3 - 0.2 * x[0] + 0.7 * x[1] + 0.05 * x[0] * x[1];
        let values: Vec<f64> = (0..m.nodes.len()).map(|n| h(m.nodes[n])).collect();
        let point_of = |n: usize| Some(n);
        // Closed form: ∫∫ h over [x0, x1] × [y0, y1].
        let integral = |x0: f64, x1: f64, y0: f64, y1: f64| {
            let (dx, dy) = (x1 - x0, y1 - y0);
            let (mx, my) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
            (0.3 - 0.2 * mx + 0.7 * my + 0.05 * mx * my) * dx * dy
        };
        let xs = [0.0, 1.5, 4.0, 6.0];
        let ys = [0.0, 1.5, 3.0];
        // A node's tributary cell: half an element to each side.
        let cell = |v: f64, grid: &[f64]| {
            let i = grid.iter().position(|&g| (g - v).abs() < 1e-12).unwrap();
            let lo = if i == 0 { v } else { 0.5 * (grid[i - 1] + v) };
            let hi = if i + 1 == grid.len() {
                v
            } else {
                0.5 * (grid[i + 1] + v)
            };
            (lo, hi)
        };
        for s in [1, 2, 5] {
            for (point, _, list) in face_samples(&m, &quads, &point_of, s) {
                let x = m.nodes[point];
                let ((x0, x1), (y0, y1)) = (cell(x[0], &xs), cell(x[1], &ys));
                let exact = integral(x0, x1, y0, y1) / ((x1 - x0) * (y1 - y0));
                let avg: f64 = list
                    .iter()
                    .map(|smp| smp.fraction * sample_value(smp, &values))
                    .sum();
                approx::assert_relative_eq!(avg, exact, max_relative = 1e-13);
            }
        }
    }

    #[test]
    fn coupling_pairs_join_each_point_to_its_sample_corners() {
        let (m, quads) = face(false);
        let row: Vec<usize> = (0..4).map(|i| m.bodies[0].node(i, 0, 1)).collect();
        let point_of = |n: usize| row.iter().position(|&r| r == n);
        let mut samples = vec![Vec::new(); 4];
        for (k, _, list) in face_samples(&m, &quads, &point_of, 2) {
            samples[k] = list;
        }
        let points: Vec<([usize; 2], (), f64, usize)> =
            (0..4).map(|k| ([k, 100 + k], (), 1.0, 0)).collect();
        let pairs = coupling_pairs(&points, &samples);
        // Nodes 0..3 are the first row of the face: neighbours 0–1, 1–2, 2–3 (the
        // second row has no points, so its corners fall back to the sampled point).
        for (k, j) in [(0, 1), (1, 0), (1, 2), (2, 1), (2, 3), (3, 2)] {
            for pair in [[k, j], [k, 100 + j], [100 + k, j], [100 + k, 100 + j]] {
                assert!(pairs.contains(&pair), "{pair:?}");
            }
        }
        assert!(!pairs.contains(&[0, 2]) && !pairs.contains(&[0, 0]));
        assert_eq!(pairs.len(), 6 * 4);
    }
}
