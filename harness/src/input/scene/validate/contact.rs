//! `[[interfaces]]`, `[[ties]]` and `[[screws]]`: the bodies they join and their constants.

use std::collections::BTreeSet;

use super::{Checker, GROUND, MAX_AREA_SAMPLES};
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;

/// Every contact interface.
pub(super) fn interfaces(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    let mut iface_names = BTreeSet::new();
    for (i, f) in s.interfaces.iter().enumerate() {
        let p = root.key("interfaces").index(i);
        if !iface_names.insert(f.name.as_str()) {
            c.fail(p.key("name"), format!("duplicate interface `{}`", f.name));
        }
        let [lo, hi] = &f.between;
        let hi_kind = c.body(p.key("between").index(1), hi);
        if lo == GROUND {
            if hi_kind.is_some_and(|k| k != BodyKind::Mass) {
                c.fail(
                    p.key("between").index(0),
                    "`ground` can only be the lower side of a mass body",
                );
            }
        } else {
            let k = c.body(p.key("between").index(0), lo);
            if k.is_some() && (k != Some(BodyKind::Box) || hi_kind != Some(BodyKind::Box)) {
                c.fail(
                    p.key("between"),
                    "an interface joins two boxes, or `ground` and a mass body",
                );
            }
        }
        if lo == hi {
            c.fail(p.key("between"), "an interface needs two different bodies");
        }
        let lumped = lo == GROUND;
        c.non_negative(p.key("mu"), f.mu);
        c.positive(p.key("k_t0_per_area"), f.k_t0_per_area);
        if let Some(k) = f.normal_stiffness_per_area {
            c.positive(p.key("normal_stiffness_per_area"), k);
        }
        normal_law(c, &p, f, s);
        if c.finite(p.key("initial_gap"), f.initial_gap) && f.initial_gap < 0.0 {
            c.fail(
                p.key("initial_gap"),
                format!("must be >= 0, got {}", f.initial_gap),
            );
        }
        for (k, r) in f.exclude.iter().enumerate() {
            let rp = p.key("exclude").index(k);
            c.vec3(rp.key("min"), &r.min);
            c.vec3(rp.key("max"), &r.max);
            if (0..3).any(|a| r.max[a] < r.min[a]) {
                c.fail(rp.key("max"), "must be >= min in every component");
            }
        }
        if lumped && !f.exclude.is_empty() {
            c.fail(p.key("exclude"), "only for box interfaces");
        }
        if let Some(n) = f.area_samples {
            if lumped {
                c.fail(p.key("area_samples"), "only for box interfaces");
            } else if !(1..=MAX_AREA_SAMPLES).contains(&n) {
                c.fail(
                    p.key("area_samples"),
                    format!("must be 1 ..= {MAX_AREA_SAMPLES}, got {n}"),
                );
            }
            if s.iteration.mode != Mode::Fast {
                c.fail(
                    p.key("area_samples"),
                    "needs [iteration] mode = \"fast\" (the other modes evaluate each point at its node)",
                );
            }
        }
        if lumped {
            match f.area {
                Some(a) => c.positive(p.key("area"), a),
                None => {
                    c.require(p.key("area"), &f.area, "for a ground-mass interface");
                }
            }
        } else {
            c.forbid(
                p.key("area"),
                &f.area,
                "for box interfaces (tributary areas are used)",
            );
        }
    }
}

/// The normal law's keys of interface `f` at `p`: k_N for linear, r* and E* for Hertz
/// (and k_N when the normal nonlinearity is off).
fn normal_law(c: &mut Checker, p: &KeyPath, f: &InterfaceSpec, s: &SceneFile) {
    match f.normal_law {
        NormalLawName::Linear => {
            c.require(
                p.key("normal_stiffness_per_area"),
                &f.normal_stiffness_per_area,
                "for normal_law = \"linear\"",
            );
            c.forbid(
                p.key("hertz_radius"),
                &f.hertz_radius,
                "for normal_law = \"linear\"",
            );
        }
        NormalLawName::Hertz => {
            if c.require(
                p.key("hertz_radius"),
                &f.hertz_radius,
                "for normal_law = \"hertz\"",
            ) {
                c.positive(p.key("hertz_radius"), f.hertz_radius.unwrap());
            }
            if c.require(
                p.key("hertz_e_star"),
                &f.hertz_e_star,
                "for normal_law = \"hertz\"",
            ) {
                c.positive(p.key("hertz_e_star"), f.hertz_e_star.unwrap());
            }
            if !s.effects.normal_contact_nonlinearity {
                c.require(
                    p.key("normal_stiffness_per_area"),
                    &f.normal_stiffness_per_area,
                    "when effects.normal_contact_nonlinearity = false",
                );
            }
        }
    }
}

/// Every tie: two different boxes.
pub(super) fn ties(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (i, t) in s.ties.iter().enumerate() {
        let p = root.key("ties").index(i);
        let [a, b] = &t.between;
        let ka = c.body(p.key("between").index(0), a);
        let kb = c.body(p.key("between").index(1), b);
        if ka == Some(BodyKind::Mass) || kb == Some(BodyKind::Mass) {
            c.fail(p.key("between"), "a tie joins two boxes");
        }
        if a == b {
            c.fail(p.key("between"), "a tie needs two different bodies");
        }
    }
}

/// Every screw: constants, and the bodies under its head and nut.
pub(super) fn screws(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    let mut screw_names = BTreeSet::new();
    for (i, sc) in s.screws.iter().enumerate() {
        let p = root.key("screws").index(i);
        if !screw_names.insert(sc.name.as_str()) {
            c.fail(p.key("name"), format!("duplicate screw `{}`", sc.name));
        }
        c.non_negative(p.key("torque"), sc.torque);
        c.positive(p.key("pitch"), sc.pitch);
        c.positive(p.key("d2"), sc.d2);
        c.non_negative(p.key("mu_thread"), sc.mu_thread);
        c.non_negative(p.key("mu_head"), sc.mu_head);
        c.non_negative(p.key("d_km"), sc.d_km);
        if c.finite(p.key("share"), sc.share) && !(sc.share > 0.0 && sc.share <= 1.0) {
            c.fail(
                p.key("share"),
                format!("must be in (0, 1], got {}", sc.share),
            );
        }
        for (k, end) in [("head", &sc.head), ("nut", &sc.nut)] {
            screw_end(c, p.key(k), end);
        }
        c.direction(p.key("direction"), &sc.direction);
    }
}

/// One end of a screw: its body, point and how its force is spread.
fn screw_end(c: &mut Checker, p: KeyPath, end: &ScrewEnd) {
    let names = end.body.names();
    let kinds: Vec<_> = names
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let path = match end.body {
                BodyNames::One(_) => p.key("body"),
                BodyNames::Many(_) => p.key("body").index(i),
            };
            c.body(path, n)
        })
        .collect();
    if names.is_empty() {
        c.fail(p.key("body"), "name at least one body");
    }
    let mass = kinds.contains(&Some(BodyKind::Mass));
    if mass && names.len() > 1 {
        c.fail(p.key("body"), "a mass body is one node: name it alone");
    }
    c.vec3(p.key("at"), &end.at);
    let spread = end.bearing.is_some() || end.thread.is_some();
    if end.bearing.is_some() && end.thread.is_some() {
        c.fail(p.clone(), "give `bearing` or `thread`, not both");
    }
    if spread && mass {
        c.fail(
            p.key("body"),
            "a mass body has one node: `bearing` and `thread` need a box",
        );
    }
    if let Some([inner, outer]) = end.bearing {
        let b = p.key("bearing");
        c.non_negative(b.index(0), inner);
        c.positive(b.index(1), outer);
        if inner.is_finite() && outer.is_finite() && inner >= outer {
            c.fail(
                b,
                format!("the inner diameter {inner} must be below the outer {outer}"),
            );
        }
    }
    if let Some(t) = end.thread {
        c.positive(p.key("thread").key("diameter"), t.diameter);
        c.positive(p.key("thread").key("length"), t.length);
    }
}
