//! `[materials]` and `[[bodies]]`: values in range, the keys each body kind needs.

use super::{Checker, GROUND};
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;

/// Largest constrained modulus (force/length²) a material may have: its products with
/// element sizes and integration weights stay finite for sizes within 1e±100.
pub const MAX_MODULUS: f64 = 1e200;

/// Every material's constants.
pub(super) fn materials(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (name, m) in &s.materials {
        let p = root.key("materials").key(name);
        c.positive(p.key("E"), m.e);
        if c.finite(p.key("nu"), m.nu) && !(m.nu > -1.0 && m.nu < 0.5) {
            c.fail(p.key("nu"), format!("must be in (-1, 0.5), got {}", m.nu));
        }
        // The constrained modulus E(1 − ν)/((1 + ν)(1 − 2ν)) enters every stiffness
        // entry times element sizes: beyond MAX_MODULUS the element matrices overflow.
        let modulus = m.e * (1.0 - m.nu) / ((1.0 + m.nu) * (1.0 - 2.0 * m.nu));
        if m.e.is_finite() && m.e > 0.0 && (modulus.is_nan() || modulus > MAX_MODULUS) {
            c.fail(
                p.key("E"),
                format!("E(1 − ν)/((1 + ν)(1 − 2ν)) = {modulus:e} exceeds {MAX_MODULUS:e}: the element stiffness would overflow"),
            );
        }
        c.non_negative(p.key("rho"), m.rho);
        c.non_negative(p.key("rayleigh_alpha"), m.rayleigh_alpha);
        c.non_negative(p.key("rayleigh_beta"), m.rayleigh_beta);
    }
}

/// Every body: a unique name, the keys of its kind; records the kinds for the later tables.
pub(super) fn bodies(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    if s.bodies.is_empty() && s.matrices.is_empty() {
        c.fail(
            root.key("bodies"),
            "at least one body (or [[matrices]] model) is needed",
        );
    }
    for (i, b) in s.bodies.iter().enumerate() {
        let p = root.key("bodies").index(i);
        if b.name.is_empty() || b.name == GROUND {
            c.fail(
                p.key("name"),
                format!("body name must be non-empty and not `{GROUND}`"),
            );
        }
        if c.kinds.insert(b.name.clone(), b.kind).is_some() {
            c.fail(p.key("name"), format!("duplicate body name `{}`", b.name));
        }
        match b.kind {
            BodyKind::Box => {
                let why = "for kind = \"box\"";
                if c.require(p.key("origin"), &b.origin, why) {
                    c.vec3(p.key("origin"), b.origin.as_ref().unwrap());
                }
                if let Some(size) = &b.size {
                    for (a, v) in size.iter().enumerate() {
                        c.positive(p.key("size").index(a), *v);
                    }
                } else {
                    c.require(p.key("size"), &b.size, why);
                }
                if let Some(d) = &b.divisions {
                    for (a, v) in d.iter().enumerate() {
                        if *v == 0 {
                            c.fail(p.key("divisions").index(a), "must be >= 1");
                        }
                    }
                } else {
                    c.require(p.key("divisions"), &b.divisions, why);
                }
                if let Some(g) = &b.grading {
                    for (name, a) in [("x", g.x), ("y", g.y), ("z", g.z)] {
                        if let Some(a) = a {
                            if !(a.ratio.is_finite() && a.ratio >= 1.0) {
                                c.fail(
                                    p.key("grading").key(name).key("ratio"),
                                    "must be finite and >= 1",
                                );
                            }
                        }
                    }
                }
                match &b.material {
                    Some(m) if !s.materials.contains_key(m) => c.fail(
                        p.key("material"),
                        format!("unknown material `{m}` (not in [materials])"),
                    ),
                    None => {
                        c.require(p.key("material"), &b.material, why);
                    }
                    _ => {}
                }
                c.forbid(p.key("position"), &b.position, why);
                c.forbid(p.key("mass"), &b.mass, why);
            }
            BodyKind::Mass => {
                let why = "for kind = \"mass\"";
                if c.require(p.key("position"), &b.position, why) {
                    c.vec3(p.key("position"), b.position.as_ref().unwrap());
                }
                match b.mass {
                    Some(m) => c.positive(p.key("mass"), m),
                    None => {
                        c.require(p.key("mass"), &b.mass, why);
                    }
                }
                c.forbid(p.key("origin"), &b.origin, why);
                c.forbid(p.key("size"), &b.size, why);
                c.forbid(p.key("divisions"), &b.divisions, why);
                c.forbid(p.key("grading"), &b.grading, why);
                c.forbid(p.key("material"), &b.material, why);
            }
        }
    }
}
