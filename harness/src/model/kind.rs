//! What an input builds into, decided here and nowhere else: an FE problem
//! ([`Problem`]) or a lumped system ([`Lumped`]); [`kind`] tells it before building,
//! [`model`] builds it.

use super::lumped::{self, Lumped};
use super::{BuildError, Problem};
use crate::input::scene::schema::BodyKind;
use crate::input::scene::Scene;

/// Which model an input makes, read off the input without building it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `[[matrices]]`, `[[joints]]` or springs `between` two bodies: a lumped system
    /// (the lumped sweep, modes, time domain and tradeoff, `jointlin backbone`);
    /// validation refuses them beside FE parts, and where both are, these decide.
    Lumped,
    /// A deck, box bodies or `[[interfaces]]` (and no lumped element): an FE problem.
    Fe,
    /// Mass bodies with grounded springs and nothing else: both builds take it. It runs
    /// as the FE problem ([`model`]); `jointlin backbone` reads it as the lumped system.
    MassesOnly,
}

/// The kind of `scene`'s model (a deck, or a scene with `model`, is FE).
pub fn kind(scene: &Scene) -> Kind {
    let s = &scene.spec;
    if s.is_lumped() {
        Kind::Lumped
    } else if scene.deck.is_some()
        || !s.interfaces.is_empty()
        || s.bodies.iter().any(|b| b.kind != BodyKind::Mass)
    {
        Kind::Fe
    } else {
        Kind::MassesOnly
    }
}

/// An input built: the FE problem of a deck or an FE scene, or the lumped system of a
/// lumped scene.
#[derive(Debug, Clone)]
pub enum Built {
    Fe(Box<Problem>),
    Lumped(Box<Lumped>),
}

/// Builds `scene` by its [`kind`]: [`Kind::Lumped`] through [`lumped::build`] (its
/// error as [`BuildError::Lumped`]), the others through [`super::build()`].
pub fn model(scene: &Scene) -> Result<Built, BuildError> {
    match kind(scene) {
        Kind::Lumped => lumped::build(scene)
            .map(|l| Built::Lumped(Box::new(l)))
            .map_err(BuildError::Lumped),
        Kind::Fe | Kind::MassesOnly => super::build(scene).map(|p| Built::Fe(Box::new(p))),
    }
}
