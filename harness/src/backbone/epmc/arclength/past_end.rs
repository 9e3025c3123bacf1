//! Where the arclength path cannot step on (the parent module's docs): the corner
//! switch along the kernel of G_y just past a corner that turns back, and the jump over
//! a short range of q where the sampled balance has no solution to the tolerance.

use nalgebra::DVector;

use super::{crossings, crossings_or_missed, Advanced, Node, Path, MAX_OMEGA_CHANGE};

/// Ln q steps of [`jump`].
const JUMPS: [f64; 6] = [1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.3];

/// Past a gap: the balance of sampled forces may have no solution to the tolerance over
/// a short range of q (Newton's residual stalls above it: a sample's stick–slip state
/// switches across the range, the forces jump). From `node`, where neither a step nor
/// the corner switch goes on, Newton at fixed q a little further in the direction of
/// travel (predicted along the tangent), the nearest that converges, close in ω and not
/// back on the path; its tangent keeps the orientation.
pub(super) fn jump(
    p: &mut Path,
    node: &Node,
    t: &DVector<f64>,
    behind: &[DVector<f64>],
    targets: &[f64],
) -> Option<Advanced> {
    let dim = p.dim;
    let dir = t[dim + 2].signum();
    let ts = t[dim + 2].abs();
    for dl in JUMPS {
        let l = p.lnq(&node.y) + dir * dl;
        // Along the tangent where it rises in q, else from the point itself.
        let guess = if ts > 1e-3 {
            &node.y + (dl / ts) * t
        } else {
            node.y.clone()
        };
        let Some((y, dissipated)) = p.at_amplitude(&guess, l) else {
            continue;
        };
        let omega_change = (y[dim] / node.y[dim] - 1.0).abs();
        let d = (&y - &node.y).norm();
        if omega_change > MAX_OMEGA_CHANGE || distance_to_path(&y, behind, &node.y) < d / 3.0 {
            continue;
        }
        let new = Node { y, dissipated };
        let Some(ev) = p.eval(&new.y) else { continue };
        let Some(tn) = p.tangent(&ev, t) else {
            continue;
        };
        let (crossings, skipped) = crossings_or_missed(p, node, &new, targets);
        return Some(Advanced {
            node: new,
            t: tn,
            crossings,
            corrector_steps: 0,
            switched: false,
            jumped: true,
            skipped,
        });
    }
    None
}

/// Distance of `y` from the polyline through `pts` and `last`.
fn distance_to_path(y: &DVector<f64>, pts: &[DVector<f64>], last: &DVector<f64>) -> f64 {
    let mut best = (y - last).norm();
    for (i, a) in pts.iter().enumerate() {
        let b = pts.get(i + 1).unwrap_or(last);
        let ab = b - a;
        let l2 = ab.norm_squared();
        let s = if l2 > 0.0 {
            ((y - a).dot(&ab) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        best = best.min((y - a - s * ab).norm());
    }
    best
}

/// Past a corner that turns back: from `node` (where even the shortest step failed)
/// along the kernel of G_y just beyond it, in the orientation that does not run back
/// along the old branch: a candidate within a third of its distance from `node` of the
/// points passed (`behind`, oldest first) or behind the old tangent is refused.
pub(super) fn corner(
    p: &mut Path,
    node: &Node,
    t: &DVector<f64>,
    behind: &[DVector<f64>],
    targets: &[f64],
) -> Option<Advanced> {
    for beyond in [1e-5, 1e-4, 1e-3] {
        let yb = &node.y + beyond * t;
        let Some(ev) = p.eval(&yb) else { continue };
        // Border row: a generic vector (t itself may be orthogonal to the new kernel).
        let mut b = t.clone();
        b[p.dim + 2] += 1.0;
        let Some(k) = p.tangent(&ev, &b) else {
            continue;
        };
        for sign in [1.0, -1.0] {
            let dir = sign * &k;
            for len in [1e-4, 1e-3, 1e-2] {
                let yp = &node.y + len * &dir;
                let Some((new, ev, steps)) = p.correct(&yp, &dir) else {
                    continue;
                };
                let d = &new.y - &node.y;
                let dn = d.norm();
                let back =
                    -d.dot(t) / dn > 0.98 || distance_to_path(&new.y, behind, &node.y) < dn / 3.0;
                if dn < 0.3 * len || back {
                    continue;
                }
                let Some(tn) = p.tangent(&ev, &(&d / dn)) else {
                    continue;
                };
                let Some(crossings) = crossings(p, node, &new, targets) else {
                    continue;
                };
                return Some(Advanced {
                    node: new,
                    t: tn,
                    crossings,
                    corrector_steps: steps,
                    switched: true,
                    jumped: false,
                    skipped: Vec::new(),
                });
            }
        }
    }
    None
}
