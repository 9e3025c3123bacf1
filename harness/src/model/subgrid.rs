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
//! For the friction law, after the static step, samples whose cell the patch edge
//! crosses (or where the overclosure varies steeply) are split further
//! ([`refine_at_patch_edge`]).

use crate::fe::mesh::Model;

/// One sample of a point's tributary area: the overclosure there is Σ w·h of the face's
/// corner points, and it stands for `fraction` of the point's area.
#[derive(Debug, Clone, PartialEq)]
pub struct AreaSample {
    /// (contact point index, bilinear weight Nⱼ) of the face's four corners.
    pub corners: [(usize, f64); 4],
    /// Share of the point's tributary area (the fractions of a point sum to 1).
    pub fraction: f64,
    /// The sample's cell on its face: centre (ξ, η) and half-width in ξ and η.
    pub at: [f64; 2],
    pub half: f64,
    /// Area element of the face, |∂x/∂ξ × ∂x/∂η| ≈ j₀ + j₁ξ + j₂η (exact on plane faces).
    pub jac: [f64; 3],
}

/// Area element |∂x/∂ξ × ∂x/∂η| of the bilinear face through `x` at (ξ, η).
fn area_element(x: &[nalgebra::Vector3<f64>; 4], xi: f64, eta: f64) -> f64 {
    let mut dxdxi = nalgebra::Vector3::zeros();
    let mut dxdeta = nalgebra::Vector3::zeros();
    for (j, c) in CORNERS.iter().enumerate() {
        dxdxi += x[j] * (0.25 * c[0] * (1.0 + c[1] * eta));
        dxdeta += x[j] * (0.25 * (1.0 + c[0] * xi) * c[1]);
    }
    dxdxi.cross(&dxdeta).norm()
}

/// Bilinear weights Nⱼ(ξ, η) of the face's corners.
fn weights(xi: f64, eta: f64) -> [f64; 4] {
    CORNERS.map(|c| 0.25 * (1.0 + c[0] * xi) * (1.0 + c[1] * eta))
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
            let j0 = area_element(&x, 0.0, 0.0);
            let jac = [
                j0,
                area_element(&x, 1.0, 0.0) - j0,
                area_element(&x, 0.0, 1.0) - j0,
            ];
            let half = 0.5 / s as f64;
            for a in 0..s {
                for b in 0..s {
                    // Midpoints of an s × s grid on the quarter between the face's
                    // centre (0, 0) and this corner.
                    let xi = corner[0] * (a as f64 + 0.5) / s as f64;
                    let eta = corner[1] * (b as f64 + 0.5) / s as f64;
                    let w = weights(xi, eta);
                    let corners = std::array::from_fn(|j| (point_of(q[j]).unwrap_or(own), w[j]));
                    // Parametric cell area (1/s)² of the quarter's unit square.
                    let da = area_element(&x, xi, eta) / (s * s) as f64;
                    acc.entry(own).or_default().push((
                        AreaSample {
                            corners,
                            fraction: 0.0,
                            at: [xi, eta],
                            half,
                            jac,
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

/// Splits of [`refine_at_patch_edge`] per sample: cells down to 2⁻⁵ of a sample's.
pub const EDGE_DEPTH: u32 = 5;

/// Splits every sample, up to `depth` times, into its four quarter cells (midpoint rule
/// on each) where the overclosure interpolated from `h` varies steeply over the cell:
/// where the cell's corners straddle zero (the edge of the contact patch) or its
/// smallest positive value is below half its spread. There the friction law's energy
/// density varies fastest: it grows like 1/p in microslip as the pressure p → 0 and
/// falls again in sliding below the pressure where δ* = A (2.46), a band much narrower
/// than an element. Fractions keep summing to one (exactly on plane faces).
pub fn refine_at_patch_edge(list: &[AreaSample], h: &[f64], depth: u32) -> Vec<AreaSample> {
    let mut out = Vec::with_capacity(list.len());
    for s in list {
        split(s, h, depth, &mut out);
    }
    out
}

fn split(s: &AreaSample, h: &[f64], depth: u32, out: &mut Vec<AreaSample>) {
    let value = |xi: f64, eta: f64| -> f64 {
        let w = weights(xi, eta);
        (0..4).map(|j| w[j] * h[s.corners[j].0]).sum()
    };
    let r = s.half;
    let v = [(-r, -r), (r, -r), (r, r), (-r, r)].map(|(a, b)| value(s.at[0] + a, s.at[1] + b));
    let (lo, hi) = v
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), &x| {
            (l.min(x), u.max(x))
        });
    let steep = hi > 0.0 && (lo <= 0.0 || lo < 0.5 * (hi - lo));
    if depth == 0 || !steep {
        out.push(s.clone());
        return;
    }
    let da =
        |at: [f64; 2], half: f64| (s.jac[0] + s.jac[1] * at[0] + s.jac[2] * at[1]) * half * half;
    let parent = da(s.at, r);
    for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let at = [s.at[0] + 0.5 * r * a, s.at[1] + 0.5 * r * b];
        let w = weights(at[0], at[1]);
        let child = AreaSample {
            corners: std::array::from_fn(|j| (s.corners[j].0, w[j])),
            fraction: s.fraction * da(at, 0.5 * r) / parent,
            at,
            half: 0.5 * r,
            jac: s.jac,
        };
        split(&child, h, depth - 1, out);
    }
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

    /// Refined at the patch edge, the samples integrate max(h, 0) of a linear field
    /// that crosses zero inside an element to the finest cell's size: the average
    /// over each point's tributary cell [x₀, x₁] against the closed form
    /// ((x₁ − c)² − (max(x₀, c) − c)²) / 2 / (x₁ − x₀) for h = x − c; unrefined, the
    /// midpoint rule errs by the whole sample size. Fields without a zero crossing or
    /// steep part are not split.
    #[test]
    fn refining_at_the_patch_edge_integrates_the_closed_part_exactly() {
        let (m, quads) = face(false);
        let c = 2.3;
        let values: Vec<f64> = (0..m.nodes.len()).map(|n| m.nodes[n][0] - c).collect();
        let xs = [0.0, 1.5, 4.0, 6.0];
        let cell = |v: f64| {
            let i = xs.iter().position(|&g| (g - v).abs() < 1e-12).unwrap();
            let lo = if i == 0 { v } else { 0.5 * (xs[i - 1] + v) };
            let hi = if i == 3 { v } else { 0.5 * (xs[i + 1] + v) };
            (lo, hi)
        };
        let average = |list: &[AreaSample]| -> f64 {
            list.iter()
                .map(|s| s.fraction * sample_value(s, &values).max(0.0))
                .sum()
        };
        let point_of = |n: usize| Some(n);
        let (mut worst_plain, mut worst_refined) = (0.0_f64, 0.0_f64);
        for (point, _, list) in face_samples(&m, &quads, &point_of, 2) {
            let (x0, x1) = cell(m.nodes[point][0]);
            let exact = if x1 > c {
                ((x1 - c).powi(2) - (x0.max(c) - c).powi(2)) / 2.0 / (x1 - x0)
            } else {
                0.0
            };
            let refined = refine_at_patch_edge(&list, &values, EDGE_DEPTH);
            let sum: f64 = refined.iter().map(|s| s.fraction).sum();
            approx::assert_relative_eq!(sum, 1.0, max_relative = 1e-13);
            worst_plain = worst_plain.max((average(&list) - exact).abs());
            worst_refined = worst_refined.max((average(&refined) - exact).abs());
        }
        println!("largest error of the average: unrefined {worst_plain:.2e}, refined {worst_refined:.2e}");
        // Finest cells: 2 per quarter, 2⁻⁵ of that, ≤ 2.5/4/32 = 0.02 wide; the midpoint
        // error of a cell the kink crosses is below (width)²/8 per unit width.
        assert!(worst_refined < 1e-4, "{worst_refined}");
        assert!(
            worst_plain > 100.0 * worst_refined,
            "{worst_plain} {worst_refined}"
        );
        // A field closed everywhere and varying by less than its level: no splits.
        let flat: Vec<f64> = (0..m.nodes.len()).map(|n| 10.0 + m.nodes[n][0]).collect();
        for (_, _, list) in face_samples(&m, &quads, &point_of, 2) {
            assert_eq!(
                refine_at_patch_edge(&list, &flat, EDGE_DEPTH).len(),
                list.len()
            );
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
