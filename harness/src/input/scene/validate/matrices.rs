//! `[[matrices]]`: models given by their matrices. Their files are read by the model
//! build (`input::matrices`), which names file:line; here the names and what a matrix
//! model can be joined with (mass bodies, springs, joints: a lumped system).

use super::{Checker, GROUND};
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;

/// Every `[[matrices]]` entry; records the names (their points are `<name>.<point>`).
pub(super) fn matrices(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    for (i, m) in s.matrices.iter().enumerate() {
        let p = root.key("matrices").index(i);
        let ok = !m.name.is_empty()
            && m.name
                .chars()
                .all(|ch| ch.is_ascii_alphanumeric() || ch == '_' || ch == '-');
        if !ok {
            c.fail(p.key("name"), "names use only A-Z a-z 0-9 _ -");
        } else if m.name == GROUND || c.kinds.contains_key(&m.name) {
            c.fail(
                p.key("name"),
                format!("`{}` is already a body's name or \"ground\"", m.name),
            );
        } else if !c.matrices.insert(m.name.clone()) {
            c.fail(p.key("name"), format!("duplicate matrices `{}`", m.name));
        }
        for (key, v) in [("mass", &m.mass), ("stiffness", &m.stiffness)] {
            if v.trim().is_empty() {
                c.fail(p.key(key), "a Matrix Market file name is needed");
            }
        }
        if i == 0
            && (s.model.is_some()
                || !s.interfaces.is_empty()
                || s.bodies.iter().any(|b| b.kind == BodyKind::Box))
        {
            c.fail(
                p,
                "a [[matrices]] model is joined by mass bodies, [[springs]] and [[joints]]: no `model`, box bodies or [[interfaces]]",
            );
        }
    }
}
