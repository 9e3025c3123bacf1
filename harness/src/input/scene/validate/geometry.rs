//! Where the boxes are: the two boxes of an interface must touch, the first one's
//! z_max face on the second one's z_min face, with overlapping footprints (what the
//! model build's pairing needs, `fe::contact_pairs`); the two boxes of a tie must touch.
//! Found here with the key, rather than by the run's model build.

use super::Checker;
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;

/// Origin and size of a box body named `name`, if it is one with finite values.
fn placed<'a>(s: &'a SceneFile, name: &str) -> Option<(&'a [f64; 3], &'a [f64; 3], f64)> {
    let b = s
        .bodies
        .iter()
        .find(|b| b.name == name && b.kind == BodyKind::Box)?;
    let (o, z, d) = (b.origin.as_ref()?, b.size.as_ref()?, b.divisions?);
    let finite = o.iter().chain(z.iter()).all(|v| v.is_finite()) && z.iter().all(|v| *v > 0.0);
    // Contact nodes match within 1e-6 of an in-plane element edge (fe::contact_pairs).
    let edge = (z[0] / d[0] as f64).min(z[1] / d[1] as f64);
    finite.then_some((o, z, 1e-6 * edge))
}

/// Extent of a box along `axis`: [low, high].
fn span(o: &[f64; 3], z: &[f64; 3], axis: usize) -> [f64; 2] {
    [o[axis], o[axis] + z[axis]]
}

/// Every box interface: touching, in order, footprints overlapping.
pub(super) fn interfaces(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (i, f) in s.interfaces.iter().enumerate() {
        let p = root.key("interfaces").index(i).key("between");
        let [lo, hi] = &f.between;
        let (Some((o1, z1, t1)), Some((o2, z2, t2))) = (placed(s, lo), placed(s, hi)) else {
            continue;
        };
        let tol = t1.min(t2);
        let (top, bottom) = (o1[2] + z1[2], o2[2]);
        if (top - bottom).abs() > tol {
            let msg = if (o2[2] + z2[2] - o1[2]).abs() <= tol {
                format!("reversed: `{hi}` lies below `{lo}`; list the lower body first: [\"{hi}\", \"{lo}\"]")
            } else if bottom > top {
                format!("`{lo}` and `{hi}` do not touch: a gap of {} between `{lo}`'s top z = {top} and `{hi}`'s bottom z = {bottom}", bottom - top)
            } else {
                format!("`{lo}` and `{hi}` overlap by {} (`{lo}`'s top z = {top}, `{hi}`'s bottom z = {bottom}); the second body must start where the first ends", top - bottom)
            };
            c.fail(p, msg);
            continue;
        }
        for (axis, name) in [(0, "x"), (1, "y")] {
            let (a, b) = (span(o1, z1, axis), span(o2, z2, axis));
            if a[1].min(b[1]) - a[0].max(b[0]) <= tol {
                c.fail(
                    p.clone(),
                    format!("`{lo}` ({name} {} … {}) and `{hi}` ({name} {} … {}) do not overlap in {name}: no contact face", a[0], a[1], b[0], b[1]),
                );
                break;
            }
        }
    }
}

/// Every tie between boxes: the boxes touch (a shared face plane, overlapping across it).
pub(super) fn ties(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (i, t) in s.ties.iter().enumerate() {
        let [a, b] = &t.between;
        let (Some((o1, z1, t1)), Some((o2, z2, t2))) = (placed(s, a), placed(s, b)) else {
            continue;
        };
        let tol = t1.min(t2);
        let spans: Vec<([f64; 2], [f64; 2])> =
            (0..3).map(|k| (span(o1, z1, k), span(o2, z2, k))).collect();
        let touching = (0..3).any(|k| {
            let (p, q) = spans[k];
            let face = (p[1] - q[0]).abs() <= tol || (q[1] - p[0]).abs() <= tol;
            let across = (0..3)
                .filter(|&j| j != k)
                .all(|j| spans[j].0[1].min(spans[j].1[1]) - spans[j].0[0].max(spans[j].1[0]) > tol);
            face && across
        });
        if !touching {
            c.fail(
                root.key("ties").index(i).key("between"),
                format!("`{a}` and `{b}` do not touch: a tie needs a face of one on a face of the other"),
            );
        }
    }
}
