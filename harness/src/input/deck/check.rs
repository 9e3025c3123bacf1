//! Whole-deck checks after reading: element nodes exist, no inverted element, every
//! element has a section with an elastic material, dynamic steps have densities.

use std::collections::HashMap;

use super::error::{DeckError, DeckErrorKind as K};
use super::model::{Deck, Procedure};

/// Checks the deck; the first problem is the error.
pub fn check(deck: &Deck) -> Result<(), DeckError> {
    let mut x = Vec::new();
    for e in &deck.elements {
        x.clear();
        for n in &e.nodes {
            match deck.node(*n) {
                Some(p) => x.push(p),
                None => {
                    return Err(e.origin.error(
                        K::Undefined,
                        "*ELEMENT",
                        format!("element {} uses node {n}, which is not defined", e.id),
                    ))
                }
            }
        }
        if let Err(err) = e.kind.element().volume(&x) {
            return Err(e.origin.error(
                K::BadValue,
                "*ELEMENT",
                format!("element {}: {err}", e.id),
            ));
        }
    }
    let mut material_of: HashMap<u64, &str> = HashMap::new();
    for s in &deck.sections {
        let Some(m) = deck.materials.get(&s.material) else {
            return Err(s.origin.error(
                K::Undefined,
                "*SOLID SECTION",
                format!("material {} is not defined", s.material),
            ));
        };
        if m.elastic.is_none() {
            return Err(m.origin.error(
                K::BadValue,
                "*MATERIAL",
                format!("material {} has no *ELASTIC", m.name),
            ));
        }
        for id in &deck.element_sets[&s.element_set] {
            if material_of.insert(*id, &s.material).is_some() {
                return Err(s.origin.error(
                    K::Duplicate,
                    "*SOLID SECTION",
                    format!("element {id} is in two sections"),
                ));
            }
        }
    }
    if let Some(e) = deck
        .elements
        .iter()
        .find(|e| !material_of.contains_key(&e.id))
    {
        return Err(e.origin.error(
            K::Undefined,
            "*ELEMENT",
            format!("element {} has no *SOLID SECTION", e.id),
        ));
    }
    let dynamic = deck
        .steps
        .iter()
        .find(|s| !matches!(s.procedure, Procedure::Static));
    if let Some(step) = dynamic {
        for s in &deck.sections {
            let m = &deck.materials[&s.material];
            if m.density.is_none() {
                return Err(m.origin.error(
                    K::BadValue,
                    "*MATERIAL",
                    format!(
                        "material {} has no *DENSITY, which step {} (line {}) needs",
                        m.name, step.name, step.origin.line
                    ),
                ));
            }
        }
    }
    for p in &deck.contact_pairs {
        if !deck.interactions.contains_key(&p.interaction) {
            return Err(p.origin.error(
                K::Undefined,
                "*CONTACT PAIR",
                format!("interaction {} is not defined", p.interaction),
            ));
        }
    }
    Ok(())
}
