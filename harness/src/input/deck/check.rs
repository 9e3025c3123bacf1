//! Whole-deck checks after reading: element nodes exist, no inverted element, every
//! element has a section with an elastic material, dynamic steps have densities.

use std::collections::HashMap;

use super::error::{DeckError, DeckErrorKind as K};
use super::model::{Deck, Procedure};

/// Largest stiffness E·L (force/length, L the model's size), nodal force or pressure
/// force p·L² a deck may give: the solve forms products of two such numbers, which stay
/// finite below (1e150)².
pub const MAX_MAGNITUDE: f64 = 1e150;

/// Checks the deck; the first problem is the error.
pub fn check(deck: &Deck) -> Result<(), DeckError> {
    magnitudes(deck)?;
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

/// Materials and loads whose stiffness or force would overflow the solve's products
/// ([`MAX_MAGNITUDE`]), named at their card.
fn magnitudes(deck: &Deck) -> Result<(), DeckError> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for n in &deck.nodes {
        for c in 0..3 {
            lo[c] = lo[c].min(n.x[c]);
            hi[c] = hi[c].max(n.x[c]);
        }
    }
    let size = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
    // (Finite: the reader bounds every coordinate by MAX_MAGNITUDE.)
    let too_big = |v: f64| v.is_nan() || v.abs() > MAX_MAGNITUDE;
    for m in deck.materials.values() {
        if let Some((e, _)) = m.elastic {
            if too_big(e * size) {
                return Err(m.origin.error(
                    K::BadValue,
                    "*MATERIAL",
                    format!("material {}: E = {e:e} over the model's size {size:e} is a stiffness of {:e}, beyond {MAX_MAGNITUDE:e}: the solve would overflow", m.name, e * size),
                ));
            }
        }
    }
    for st in &deck.steps {
        for l in &st.cloads {
            if too_big(l.value) {
                return Err(l.origin.error(
                    K::BadValue,
                    "*CLOAD",
                    format!(
                        "force {:e} beyond {MAX_MAGNITUDE:e}: the solve would overflow",
                        l.value
                    ),
                ));
            }
        }
        let pressures = (st.dloads.iter().map(|l| (l.pressure, &l.origin, "*DLOAD"))).chain(
            st.dsloads
                .iter()
                .map(|l| (l.pressure, &l.origin, "*DSLOAD")),
        );
        for (p, origin, keyword) in pressures {
            if too_big(p * size * size) {
                return Err(origin.error(
                    K::BadValue,
                    keyword,
                    format!("pressure {p:e} over the model's size {size:e} is a force of {:e}, beyond {MAX_MAGNITUDE:e}: the solve would overflow", p * size * size),
                ));
            }
        }
    }
    Ok(())
}
