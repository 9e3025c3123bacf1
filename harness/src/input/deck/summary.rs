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

/// The tolerances of one contact pair or tie, judged on the faces it pairs (never on
/// the whole model, whose far reference nodes would widen them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairTolerance {
    /// A gap at or below this is round-off (length): [`ROUND_OFF`] × the master's typical
    /// face diagonal; larger gaps are reported with their size.
    pub round_off: f64,
    /// The farthest a slave node may lie from the master surface and be paired
    /// (length): a tie's `POSITION TOLERANCE`, else [`DEFAULT_POSITION`] × the master's
    /// typical face diagonal (Abaqus's default for ties).
    pub search: f64,
}

/// Round-off gap relative to the master's typical face diagonal.
pub const ROUND_OFF: f64 = 1e-6;
/// Default position tolerance relative to the master's typical face diagonal.
pub const DEFAULT_POSITION: f64 = 0.05;

/// The tolerances of a pair with master surface `master` (`position`: a tie's
/// `POSITION TOLERANCE`, length).
pub fn pair_tolerance(deck: &Deck, master: &str, position: Option<f64>) -> PairTolerance {
    let h = typical_face_diagonal(deck, master);
    PairTolerance {
        round_off: ROUND_OFF * h,
        search: position.unwrap_or(DEFAULT_POSITION * h),
    }
}

/// The mean diagonal of the bounding boxes of surface `name`'s faces (length; 1 for a
/// surface without faces, which pairing then refuses).
fn typical_face_diagonal(deck: &Deck, name: &str) -> f64 {
    let Some(SurfaceKind::Element(list)) = deck.surfaces.get(name).map(|s| &s.kind) else {
        return 1.0;
    };
    let mut sum = 0.0;
    let mut count = 0usize;
    for &(id, face) in list {
        let e = &deck.elements[deck.element_index[&id]];
        let local = e.kind.face_nodes(face).unwrap_or(&[]);
        let x: Vec<[f64; 3]> = local
            .iter()
            .filter_map(|&i| e.nodes.get(i).and_then(|&n| deck.node(n)))
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in &x {
            for c in 0..3 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        let d = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
        if d.is_finite() {
            sum += d;
            count += 1;
        }
    }
    if count > 0 && sum > 0.0 {
        sum / count as f64
    } else {
        1.0
    }
}

/// `n` and `word`, plural unless n = 1 ("1 material", "3 node sets").
fn count(n: usize, word: &str) -> String {
    if n == 1 {
        format!("1 {word}")
    } else {
        format!("{n} {word}s")
    }
}

/// The model summary printed by `jointlin check`; `frequency` names the unit of the
/// steady-state steps' frequencies (`Hz`, `1/ms`, or `1/time` when the deck states no
/// units).
pub fn summary(deck: &Deck, file: &str, frequency: &str) -> Result<String, DeckError> {
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
        "  {}, {}, {}, {}, {}",
        count(deck.node_sets.len(), "node set"),
        count(deck.element_sets.len(), "element set"),
        count(deck.surfaces.len(), "surface"),
        count(deck.materials.len(), "material"),
        count(deck.sections.len(), "section")
    );
    let ids = |n: usize| deck.nodes[n].id;
    for c in &deck.contact_pairs {
        let tol = pair_tolerance(deck, &c.master, None).search;
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
            pair_tolerance(deck, &t.master, t.position_tolerance).search,
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
                    "steady-state dynamics {lo}…{hi} ({frequency}), {points} points on {} data lines",
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
