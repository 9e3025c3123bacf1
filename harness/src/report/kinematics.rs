//! Large-displacement honesty: a run's output that moves by a sizeable fraction of the
//! thickness of the part it sits on is past what linear (small-displacement) kinematics
//! describe: a plate bent by about its thickness stiffens by membrane action, and
//! sections turn. The part is the output node's piece of mesh (the elements connected to
//! it through shared nodes: a body, or a separately meshed plate of a deck; ties and
//! contact pairs join parts without sharing nodes) and its thickness the smallest extent
//! of its nodes along their principal axes, so a tilted or thin part inside a thick
//! assembly is measured as itself.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

use crate::run::RunResult;
use crate::settings::units::frequency_unit;

/// An output amplitude beyond this fraction of its part's thickness is a large
/// deflection.
pub const LARGE_DEFLECTION: f64 = 0.5;

/// A note when an output's largest amplitude (either sweep direction) exceeds
/// [`LARGE_DEFLECTION`] of its part's thickness (the output with the largest ratio;
/// outputs on nodes in no element, such as a reference node, are not judged).
pub fn note(units: &crate::settings::Units, r: &RunResult) -> Option<String> {
    let model = &r.problem.model;
    let elements: Vec<&[usize]> = model.elements.iter().map(|e| e.nodes.as_slice()).collect();
    let thickness = part_thickness(&model.nodes, &elements);
    let sweeps: Vec<_> = std::iter::once(&r.main).chain(r.down.as_ref()).collect();
    let mut worst: Option<(f64, usize, f64, f64, f64)> = None;
    for (k, out) in r.problem.outputs.iter().enumerate() {
        let Some(t) = thickness.get(out.node).copied().flatten() else {
            continue;
        };
        for sweep in &sweeps {
            for (row, f) in sweep.outputs.iter().zip(&sweep.freqs) {
                let amp = row.get(k).map_or(0.0, |u| u.norm());
                let ratio = amp / t;
                if ratio.is_finite() && worst.is_none_or(|w| ratio > w.0) {
                    worst = Some((ratio, k, amp, *f, t));
                }
            }
        }
    }
    let (ratio, k, amp, f, t) = worst?;
    (ratio > LARGE_DEFLECTION).then(|| {
        let fu = frequency_unit(units);
        format!(
            "output {} moves {amp:.3e} {l} at {:.6e} {}, {ratio:.2} × the thickness of the part it sits on ({t:.3e} {l}, its smallest extent across its principal axes; more than {LARGE_DEFLECTION} ×): a deflection this large stiffens plates held at their edges by membrane action and turns sections; linear kinematics may no longer hold there",
            r.problem.outputs[k].name,
            fu.show(f),
            fu.text,
            l = units.length
        )
    })
}

/// Per node, the thickness of its part (the nodes connected to it through elements):
/// the smallest extent of the part's nodes along the principal axes of their spread.
/// `None` for nodes in no element.
pub fn part_thickness(nodes: &[[f64; 3]], elements: &[&[usize]]) -> Vec<Option<f64>> {
    let mut parent: Vec<usize> = (0..nodes.len()).collect();
    fn root(parent: &mut [usize], mut a: usize) -> usize {
        while parent[a] != a {
            parent[a] = parent[parent[a]];
            a = parent[a];
        }
        a
    }
    let mut used = vec![false; nodes.len()];
    for e in elements {
        for &n in *e {
            used[n] = true;
            let (a, b) = (root(&mut parent, e[0]), root(&mut parent, n));
            parent[a] = b;
        }
    }
    let mut parts: std::collections::HashMap<usize, Vec<usize>> = Default::default();
    for n in (0..nodes.len()).filter(|&n| used[n]) {
        parts.entry(root(&mut parent, n)).or_default().push(n);
    }
    let mut out = vec![None; nodes.len()];
    for members in parts.values() {
        let points = members.iter().map(|&n| Vector3::from(nodes[n]));
        let (t, size) = (thinnest_extent(points.clone()), widest_extent(points));
        // A flat or broken part (coplanar or non-finite nodes) has no thickness to judge.
        let t = (t.is_finite() && t > 1e-9 * size).then_some(t);
        for &n in members {
            out[n] = t;
        }
    }
    out
}

/// The largest extent of `points` along the coordinate axes.
fn widest_extent(points: impl Iterator<Item = Vector3<f64>> + Clone) -> f64 {
    (0..3)
        .map(|k| {
            let (lo, hi) = points
                .clone()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p[k]), hi.max(p[k]))
                });
            hi - lo
        })
        .fold(0.0, f64::max)
}

/// The smallest extent of `points` along the eigenvectors of their covariance.
fn thinnest_extent(points: impl Iterator<Item = Vector3<f64>> + Clone) -> f64 {
    let count = points.clone().count().max(1) as f64;
    let mean = points.clone().fold(Vector3::zeros(), |s, p| s + p) / count;
    let cov = points.clone().fold(Matrix3::zeros(), |s, p| {
        s + (p - mean) * (p - mean).transpose()
    }) / count;
    let axes = SymmetricEigen::new(cov).eigenvectors;
    (0..3)
        .map(|k| {
            let axis = axes.column(k);
            let (lo, hi) =
                points
                    .clone()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                        let s = axis.dot(&p);
                        (lo.min(s), hi.max(s))
                    });
            hi - lo
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corners of a box (lengths `l`) turned by `angle` about y, then shifted by `at`,
    /// as one 8-node element.
    fn tilted_box(
        l: [f64; 3],
        angle: f64,
        at: [f64; 3],
        first: usize,
    ) -> (Vec<[f64; 3]>, Vec<usize>) {
        let (c, s) = (angle.cos(), angle.sin());
        let mut nodes = Vec::new();
        for k in 0..8 {
            let p = [
                l[0] * (k & 1) as f64,
                l[1] * ((k >> 1) & 1) as f64,
                l[2] * ((k >> 2) & 1) as f64,
            ];
            nodes.push([
                at[0] + c * p[0] + s * p[2],
                at[1] + p[1],
                at[2] - s * p[0] + c * p[2],
            ]);
        }
        (nodes, (first..first + 8).collect())
    }

    #[test]
    fn a_tilted_plate_in_a_thick_assembly_has_its_own_thickness() {
        // A 100 × 30 × 4 plate at 35° beside a 50 mm cube; a loose reference node.
        let (mut nodes, plate) = tilted_box([100.0, 30.0, 4.0], 35f64.to_radians(), [0.0; 3], 0);
        let (cube_nodes, cube) = tilted_box([50.0; 3], 0.0, [200.0, 0.0, 0.0], 8);
        nodes.extend(cube_nodes);
        nodes.push([500.0, 500.0, 500.0]);
        let t = part_thickness(&nodes, &[&plate, &cube]);
        for n in 0..8 {
            assert!(
                (t[n].unwrap() - 4.0).abs() < 1e-9,
                "plate node {n}: {:?}",
                t[n]
            );
        }
        for n in 8..16 {
            assert!(
                (t[n].unwrap() - 50.0).abs() < 1e-9,
                "cube node {n}: {:?}",
                t[n]
            );
        }
        assert_eq!(t[16], None);
        // A flat part (coplanar nodes, turned) and one with a NaN coordinate: not judged.
        let (mut flat, element) = tilted_box([10.0, 10.0, 0.0], 0.3, [0.0; 3], 0);
        assert_eq!(part_thickness(&flat, &[&element])[0], None);
        flat[3][1] = f64::NAN;
        assert_eq!(part_thickness(&flat, &[&element])[0], None);
    }
}
