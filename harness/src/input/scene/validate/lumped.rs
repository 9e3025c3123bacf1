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
        axis(c, p.key("direction"), &j.direction);
        c.positive(p.key("mu"), j.mu);
        c.positive(p.key("k_t0"), j.k_t0);
        if let Some(f) = j.normal_force {
            c.positive(p.key("normal_force"), f);
        }
        let Some(n) = &j.normal else {
            let why = "without `normal` (a joint of one tangential direction)";
            c.require(p.key("normal_force"), &j.normal_force, why);
            c.forbid(p.key("normal_stiffness"), &j.normal_stiffness, why);
            continue;
        };
        axis(c, p.key("normal"), n);
        if n.iter().zip(&j.direction).any(|(a, b)| a * b != 0.0) {
            c.fail(
                p.key("direction"),
                "must be perpendicular to `normal` (the first tangential axis)",
            );
        }
        if c.require(
            p.key("normal_stiffness"),
            &j.normal_stiffness,
            "with `normal` (k_N, force/length)",
        ) {
            c.positive(p.key("normal_stiffness"), j.normal_stiffness.unwrap());
        }
        let e = &s.effects;
        if (e.normal_load_variation || e.coupled_slip) && j.rule != RuleName::Masing {
            c.fail(
                p.key("rule"),
                "must be \"masing\" with [effects] normal_load_variation or coupled_slip (the three-direction point unloads by Masing's rule)",
            );
        }
    }
}

/// A coordinate axis, e.g. [1, 0, 0] or [0, 0, -1].
fn axis(c: &mut Checker, path: KeyPath, v: &[f64; 3]) {
    c.direction(path.clone(), v);
    if v.iter().filter(|x| **x != 0.0).count() > 1 {
        c.fail(path, "must be a coordinate axis, e.g. [1, 0, 0]");
    }
}

/// The `[effects]` a lumped system switches: `material_damping` (the springs' dashpots
/// and the matrices' D) and, on joints with `normal` in the harmonic balance,
/// `normal_load_variation` and `coupled_slip`; the others belong to FE interfaces and
/// are refused when changed.
pub(super) fn effects(c: &mut Checker, s: &SceneFile) {
    if !s.is_lumped() {
        return;
    }
    let p = KeyPath::root().key("effects");
    let e = &s.effects;
    let fe_only = [
        (
            "normal_contact_nonlinearity",
            e.normal_contact_nonlinearity,
            true,
        ),
        ("tangential_microslip", e.tangential_microslip, true),
        ("macroslip", e.macroslip, true),
        ("contact_damping", e.contact_damping, true),
        ("point_energy_output", e.point_energy_output, false),
        ("stick_slip_map", e.stick_slip_map, false),
    ];
    for (key, value, default) in fe_only {
        if value != default {
            c.fail(
                p.key(key),
                format!("a lumped system does not switch this effect (it belongs to FE interfaces): leave it at {default}"),
            );
        }
    }
    for (key, on) in [
        ("normal_load_variation", e.normal_load_variation),
        ("coupled_slip", e.coupled_slip),
    ] {
        if !on {
            continue;
        }
        if !s.joints.iter().any(|j| j.normal.is_some()) {
            c.fail(
                p.key(key),
                "acts on joints with `normal` (three-direction points): no joint has one",
            );
        }
        if s.iteration.mode != Mode::HarmonicBalance {
            c.fail(
                p.key(key),
                "a lumped system computes it by the harmonic balance: set [iteration] mode = \"harmonic_balance\"",
            );
        }
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

/// Lumped elements (`[[joints]]`, springs `between` two bodies) make the scene a lumped
/// system, which has no FE parts: refused beside `model`, box bodies or `[[interfaces]]`
/// at the first of them (a `[[matrices]]` model says so itself).
pub(super) fn no_fe_parts(c: &mut Checker, s: &SceneFile) {
    let fe_parts = s.model.is_some()
        || !s.interfaces.is_empty()
        || s.bodies.iter().any(|b| b.kind == BodyKind::Box);
    if !fe_parts || !s.matrices.is_empty() {
        return;
    }
    let root = KeyPath::root();
    let first = if s.joints.is_empty() {
        let Some(i) = s.springs.iter().position(|sp| sp.between.is_some()) else {
            return;
        };
        root.key("springs").index(i).key("between")
    } else {
        root.key("joints").index(0)
    };
    c.fail(
        first,
        "[[joints]] and springs `between` two bodies make a lumped system, joined by mass bodies, [[springs]] and [[matrices]]: no `model`, box bodies or [[interfaces]]",
    );
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
