//! `jointlin check DECK.inp`: the model summary (nodes,
//! elements by type, DOFs, sets, contact points of each contact pair and tie after
//! pairing, steps). A contact pair or tie whose slave surface pairs with no master face
//! is an error.

use std::fmt::Write as _;

use crate::fe::elements::face::MeshFace;
use crate::fe::pairing::{pair, Pairing};

use super::error::{DeckError, DeckErrorKind as K, Origin};
use super::model::{Deck, Procedure, SurfaceKind};

/// Node coordinates in deck order (index = position in `deck.nodes`).
pub fn coords(deck: &Deck) -> Vec<[f64; 3]> {
    deck.nodes.iter().map(|n| n.x).collect()
}

/// The element faces of surface `name` as mesh faces over deck node indices.
pub fn faces(
    deck: &Deck,
    name: &str,
    origin: &Origin,
    keyword: &str,
) -> Result<Vec<MeshFace>, DeckError> {
    let s = &deck.surfaces[name];
    let SurfaceKind::Element(list) = &s.kind else {
        return Err(origin.error(
            K::Unsupported,
            keyword,
            format!("surface {name} is a node surface; contact needs element faces"),
        ));
    };
    Ok(list
        .iter()
        .filter_map(|&(id, face)| {
            let ei = deck.element_index[&id];
            let e = &deck.elements[ei];
            let conn: Vec<usize> = e.nodes.iter().map(|n| deck.node_index[n]).collect();
            MeshFace::new(e.kind, ei, &conn, face)
        })
        .collect())
}

/// Pairs the slave and master surfaces of a contact pair or tie; no paired node at all
/// is an error ("no overlap").
pub fn pair_surfaces(
    deck: &Deck,
    slave: &str,
    master: &str,
    tol: f64,
    origin: &Origin,
    keyword: &str,
) -> Result<Pairing, DeckError> {
    let x = coords(deck);
    let p = pair(
        &x,
        &faces(deck, slave, origin, keyword)?,
        &faces(deck, master, origin, keyword)?,
        tol,
    );
    if p.nodes.is_empty() {
        return Err(origin.error(K::BadValue, keyword, format!("slave {slave} and master {master} do not overlap (no slave node within {tol:e} of a master face)")));
    }
    Ok(p)
}

/// Position tolerance of contact pairs and untoleranced ties: 1e-6 × the model's size.
pub fn default_tolerance(deck: &Deck) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for n in &deck.nodes {
        for c in 0..3 {
            lo[c] = lo[c].min(n.x[c]);
            hi[c] = hi[c].max(n.x[c]);
        }
    }
    let size = (0..3).map(|c| hi[c] - lo[c]).fold(0.0, f64::max);
    1e-6 * if size.is_finite() && size > 0.0 {
        size
    } else {
        1.0
    }
}

/// The model summary printed by `jointlin check`.
pub fn summary(deck: &Deck, file: &str) -> Result<String, DeckError> {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{file}: ok — {}",
        deck.heading.lines().next().unwrap_or("").trim()
    );
    let by_type: Vec<String> = deck
        .element_counts()
        .iter()
        .map(|(k, n)| format!("{n} {k}"))
        .collect();
    let _ = writeln!(
        s,
        "  {} nodes ({} DOFs), {} elements ({})",
        deck.nodes.len(),
        3 * deck.nodes.len(),
        deck.elements.len(),
        by_type.join(", ")
    );
    let _ = writeln!(
        s,
        "  {} node sets, {} element sets, {} surfaces, {} materials, {} sections",
        deck.node_sets.len(),
        deck.element_sets.len(),
        deck.surfaces.len(),
        deck.materials.len(),
        deck.sections.len()
    );
    let tol = default_tolerance(deck);
    let ids = |n: usize| deck.nodes[n].id;
    for c in &deck.contact_pairs {
        let p = pair_surfaces(deck, &c.slave, &c.master, tol, &c.origin, "*CONTACT PAIR")?;
        let _ = writeln!(
            s,
            "  contact pair {} / {} ({}): {} contact points",
            c.slave,
            c.master,
            c.interaction,
            p.nodes.len()
        );
        if let Some(r) = p.unmatched_report(ids) {
            let _ = writeln!(s, "    warning: {r}");
        }
    }
    for t in &deck.ties {
        let p = pair_surfaces(
            deck,
            &t.slave,
            &t.master,
            t.position_tolerance.unwrap_or(tol),
            &t.origin,
            "*TIE",
        )?;
        let _ = writeln!(
            s,
            "  tie {} ({} / {}): {} tied nodes",
            t.name,
            t.slave,
            t.master,
            p.nodes.len()
        );
        if let Some(r) = p.unmatched_report(ids) {
            let _ = writeln!(s, "    warning: {r}");
        }
    }
    for st in &deck.steps {
        let what = match &st.procedure {
            Procedure::Static => "static".to_string(),
            Procedure::Frequency { modes } => format!("frequency, {modes} modes"),
            Procedure::SteadyState { ranges, .. } => {
                let lo = ranges.iter().map(|r| r.f_low).fold(f64::INFINITY, f64::min);
                let hi = ranges.iter().map(|r| r.f_high).fold(0.0, f64::max);
                let points: usize = ranges.iter().map(|r| r.points).sum();
                format!(
                    "steady-state dynamics {lo}…{hi} (1/time), {points} points on {} data lines",
                    ranges.len()
                )
            }
        };
        let _ = writeln!(
            s,
            "  step {}{}: {what}",
            st.name,
            if st.perturbation {
                " (perturbation)"
            } else {
                ""
            }
        );
    }
    Ok(s)
}
