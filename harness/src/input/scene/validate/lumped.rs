//! `[[joints]]` and `[[springs]]`: lumped elements between mass bodies and ground.

use std::collections::BTreeSet;

use super::{Checker, GROUND};
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;

/// Every lumped friction joint.
pub(super) fn joints(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    let mut joint_names = BTreeSet::new();
    for (i, j) in s.joints.iter().enumerate() {
        let p = root.key("joints").index(i);
        if !joint_names.insert(j.name.as_str()) {
            c.fail(p.key("name"), format!("duplicate joint `{}`", j.name));
        }
        lumped_ends(c, p.key("between"), &j.between);
        c.direction(p.key("direction"), &j.direction);
        if j.direction.iter().filter(|v| **v != 0.0).count() > 1 {
            c.fail(
                p.key("direction"),
                "must be a coordinate axis, e.g. [1, 0, 0]",
            );
        }
        c.positive(p.key("mu"), j.mu);
        c.positive(p.key("normal_force"), j.normal_force);
        c.positive(p.key("k_t0"), j.k_t0);
    }
}

/// Every spring (linear, cubic, damped).
pub(super) fn springs(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (i, sp) in s.springs.iter().enumerate() {
        let p = root.key("springs").index(i);
        if let Some(ends) = &sp.between {
            if !sp.body.is_empty() {
                c.fail(p.key("body"), "not allowed with `between`");
            }
            lumped_ends(c, p.key("between"), ends);
        } else if c.body(p.key("body"), &sp.body) == Some(BodyKind::Box) {
            c.fail(p.key("body"), "springs attach to mass bodies");
        }
        c.direction(p.key("direction"), &sp.direction);
        c.non_negative(p.key("stiffness"), sp.stiffness);
        c.finite(p.key("cubic"), sp.cubic);
        c.non_negative(p.key("damping"), sp.damping);
        // The first-order balance linearizes the cubic term about x = 0: a static
        // preload would move the operating point, which the static step (linear springs)
        // does not follow.
        if sp.cubic != 0.0 && s.iteration.mode == Mode::HarmonicBalance {
            c.fail(
                p.key("cubic"),
                "cubic springs are linearized to first order: use mode \"fast\" or \"thesis\"",
            );
        }
        // A preload across the spring (e.g. the normal load of a friction contact under
        // the mass) leaves its elongation at zero; one with a component along it would not.
        let along = |l: &PreloadSpec| {
            l.force
                .is_none_or(|f| f.iter().zip(&sp.direction).any(|(a, b)| a * b != 0.0))
        };
        if sp.cubic != 0.0 && s.preload.iter().any(|l| l.body == sp.body && along(l)) {
            c.fail(
                p.key("cubic"),
                format!(
                    "a cubic spring is linearized about zero static elongation: body `{}` must carry no preload along the spring",
                    sp.body
                ),
            );
        }
    }
}

/// The two ends of a lumped element: mass bodies or `"ground"`, not the same twice.
fn lumped_ends(c: &mut Checker, path: KeyPath, ends: &[String; 2]) {
    for (k, e) in ends.iter().enumerate() {
        if e == GROUND {
            continue;
        }
        match c.kind(e) {
            Some(BodyKind::Mass) => {}
            Some(BodyKind::Box) => c.fail(path.index(k), "must be a mass body or \"ground\""),
            None => c.fail(path.index(k), format!("unknown body `{e}`")),
        }
    }
    if ends[0] == ends[1] {
        c.fail(path, "the two ends must differ");
    }
}
