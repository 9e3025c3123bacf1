//! A contact pair's USER interaction → its contact law: the PROPS table of
//! fortran-shim/README.md read by the library's own check (`capi::props::decode`), exactly
//! as the Fortran shim reads it, so the same deck runs in Abaqus with the shim's UINTER.

use super::{ContactPair, DeckError, DeckErrorKind as K, Interaction};
use crate::capi::props::{decode, MIN_PROPS};
use crate::names::ContactLaw;

/// The contact law (stress form: per unit area) of contact pair `pair` with interaction
/// `inter` (PROPS 1…12).
pub fn user_law(pair: &ContactPair, inter: &Interaction) -> Result<ContactLaw, DeckError> {
    let err = |m: String| pair.origin.error(K::Unsupported, "*CONTACT PAIR", m);
    if !inter.user || inter.properties.len() < MIN_PROPS {
        return Err(err(format!(
            "interaction {} (line {}) needs USER, PROPERTIES >= {MIN_PROPS} and the property table of fortran-shim/README.md (law, rule, mu, k_T0 per area, normal law, k_N or E*, r*)",
            inter.name, inter.origin.line
        )));
    }
    decode(&inter.properties).map_err(|e| err(format!("interaction {}: {e}", inter.name)))
}
