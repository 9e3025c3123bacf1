//! `[[preload]]`, `[[clamp]]` and `[[excitation]]`: the body each acts on and the keys
//! of its kind.

use super::Checker;
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;

/// Every static preload.
pub(super) fn preload(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (i, l) in s.preload.iter().enumerate() {
        let p = root.key("preload").index(i);
        let kind = c.body(p.key("body"), &l.body);
        match l.kind {
            PreloadKind::Pressure => {
                let why = "for kind = \"pressure\"";
                if kind == Some(BodyKind::Mass) {
                    c.fail(p.key("kind"), "a pressure needs a box body");
                }
                c.require(p.key("face"), &l.face, why);
                if c.require(p.key("pressure"), &l.pressure, why) {
                    c.finite(p.key("pressure"), l.pressure.unwrap());
                }
                c.forbid(p.key("force"), &l.force, why);
                c.forbid(p.key("at"), &l.at, why);
            }
            PreloadKind::Force => {
                let why = "for kind = \"force\"";
                if kind == Some(BodyKind::Box) && c.require(p.key("at"), &l.at, why) {
                    c.vec3(p.key("at"), l.at.as_ref().unwrap());
                }
                if kind == Some(BodyKind::Mass) {
                    c.forbid(p.key("at"), &l.at, "on a mass body (it acts at the body)");
                }
                if c.require(p.key("force"), &l.force, why) {
                    c.vec3(p.key("force"), l.force.as_ref().unwrap());
                }
                c.forbid(p.key("face"), &l.face, why);
                c.forbid(p.key("pressure"), &l.pressure, why);
            }
        }
    }
}

/// Every clamp: a box face, or a mass body.
pub(super) fn clamp(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (i, cl) in s.clamp.iter().enumerate() {
        let p = root.key("clamp").index(i);
        match c.body(p.key("body"), &cl.body) {
            Some(BodyKind::Box) => {
                c.require(p.key("face"), &cl.face, "for a box body");
            }
            Some(BodyKind::Mass) => c.forbid(p.key("face"), &cl.face, "for a mass body"),
            None => {}
        }
    }
}

/// At least one excitation, each on a known body.
pub(super) fn excitation(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    if s.excitation.is_empty() {
        c.fail(root.key("excitation"), "at least one excitation is needed");
    }
    for (i, e) in s.excitation.iter().enumerate() {
        let p = root.key("excitation").index(i);
        let kind = c.body(p.key("body"), &e.body);
        match e.kind {
            ExcitationKind::Point => {
                if kind == Some(BodyKind::Box)
                    && c.require(p.key("at"), &e.at, "for a point force on a box")
                {
                    c.vec3(p.key("at"), e.at.as_ref().unwrap());
                }
                c.forbid(p.key("face"), &e.face, "for kind = \"point\"");
            }
            ExcitationKind::Face => {
                if kind == Some(BodyKind::Mass) {
                    c.fail(p.key("kind"), "a face excitation needs a box body");
                }
                c.require(p.key("face"), &e.face, "for kind = \"face\"");
                c.forbid(p.key("at"), &e.at, "for kind = \"face\"");
            }
        }
        c.direction(p.key("direction"), &e.direction);
        c.finite(p.key("amplitude"), e.amplitude);
        c.finite(p.key("phase_deg"), e.phase_deg);
    }
}
