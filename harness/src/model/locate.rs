//! A model build's error as a scene error: the key of the table it comes from
//! (interface, tie, screw by name; bodies otherwise), so that `jointlin check` and
//! `jointlin run` name `file:line:col` for what only the build can find (e.g. contact
//! faces whose nodes do not match, a tie between non-conforming meshes).

use super::BuildError;
use crate::input::scene::error::{at_path, KeyPath};
use crate::input::scene::{Scene, SceneError};

/// The scene location of `e`, with its message.
pub fn locate(scene: &Scene, e: &BuildError) -> SceneError {
    let s = &scene.spec;
    let root = KeyPath::root();
    let path = match e {
        BuildError::Pairs { name, .. } => s
            .interfaces
            .iter()
            .position(|f| &f.name == name)
            .map(|i| root.key("interfaces").index(i).key("between")),
        BuildError::Tie { a, b, .. } => s
            .ties
            .iter()
            .position(|t| (&t.between[0], &t.between[1]) == (a, b))
            .map(|i| root.key("ties").index(i).key("between")),
        BuildError::Screw { name, .. } => s
            .screws
            .iter()
            .position(|x| &x.name == name)
            .map(|i| root.key("screws").index(i)),
        BuildError::Deck(_) => s.model.as_ref().map(|_| root.key("model")),
        BuildError::Mesh(_)
        | BuildError::Assembly(_)
        | BuildError::Lumped(_)
        | BuildError::Other(_) => None,
    };
    let path = path.unwrap_or_else(|| root.key("bodies"));
    at_path(
        &scene.file,
        &scene.text,
        &path,
        format!("building the model: {e}"),
    )
}
