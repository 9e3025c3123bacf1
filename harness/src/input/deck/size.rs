//! The memory a deck's run needs, estimated from the deck before anything is built
//! (DOFs and the sparse factor from its nodes, contact points from its slave surfaces,
//! results from its frequencies and outputs), against the memory the machine has (or
//! `JOINTLIN_MAX_MEMORY`): a deck beyond it is refused at the card that makes it so big,
//! as a scene is (`input::scene::validate::size`).

use super::error::{DeckError, DeckErrorKind as K, Origin};
use super::model::{Deck, Procedure, SurfaceKind};
use crate::util::memory::{
    self, format_bytes, BASE_BYTES, BYTES_PER_FREQUENCY, FACTOR_BYTES_PER_ENTRY,
    MATRIX_BYTES_PER_DOF, MAX_MEMORY_VAR, OUTPUT_BYTES_PER_FREQUENCY, POINT_BYTES_PER_FREQUENCY,
};

/// Most frequencies one steady-state step may list (all its data lines together).
pub const MAX_FREQUENCIES: usize = 10_000_000;

/// One part of the estimate: where it comes from, its size (bytes) and what it is.
struct Part {
    origin: Origin,
    keyword: &'static str,
    bytes: f64,
    what: String,
}

/// The deck's estimate by part. The factor of an unstructured mesh of n nodes is taken
/// as that of a cube of as many: 9 n^{4/3} entries (nested dissection).
fn parts(deck: &Deck) -> Vec<Part> {
    let nodes = deck.nodes.len() as f64;
    let dofs = 3.0 * nodes;
    let factor = 9.0 * nodes.powf(4.0 / 3.0);
    let mesh_at = deck
        .elements
        .first()
        .map(|e| e.origin.clone())
        .unwrap_or_default();
    let mut out = vec![Part {
        origin: mesh_at,
        keyword: "*ELEMENT",
        bytes: MATRIX_BYTES_PER_DOF * dofs + FACTOR_BYTES_PER_ENTRY * factor,
        what: format!(
            "{nodes:.0} nodes: {dofs:.0} DOFs, a sparse factor of about {factor:.3e} entries"
        ),
    }];
    let points: f64 = deck
        .contact_pairs
        .iter()
        .map(|c| match &deck.surfaces[&c.slave].kind {
            // At most 9 nodes per face (C3D20's 8, C3D10's 6).
            SurfaceKind::Element(f) => 8.0 * f.len() as f64,
            SurfaceKind::Node(n) => n.len() as f64,
        })
        .sum();
    let outputs: f64 = deck
        .steps
        .iter()
        .flat_map(|s| &s.outputs)
        .map(|o| 3.0 * deck.node_sets[&o.node_set].len() as f64)
        .sum();
    for st in &deck.steps {
        if let Procedure::Frequency { modes } = &st.procedure {
            // Kept as the mode-based steady state's basis: full vectors of doubles (never
            // more modes than DOFs).
            let modes = (*modes as f64).min(dofs);
            out.push(Part {
                origin: st.origin.clone(),
                keyword: "*FREQUENCY",
                bytes: 8.0 * modes * dofs,
                what: format!("{modes:.0} mode shapes of {dofs:.0} DOFs"),
            });
        }
        if let Procedure::SteadyState { ranges, .. } = &st.procedure {
            let count: f64 = ranges.iter().map(|r| r.points as f64).sum();
            out.push(Part {
                origin: st.origin.clone(),
                keyword: "*STEADY STATE DYNAMICS",
                bytes: count
                    * (BYTES_PER_FREQUENCY
                        + OUTPUT_BYTES_PER_FREQUENCY * outputs
                        + POINT_BYTES_PER_FREQUENCY * points),
                what: format!("{count:.0} frequencies × about {points:.0} contact points and {outputs:.0} outputs"),
            });
        }
    }
    out
}

/// The estimate of deck `file` against the memory limit ([`memory::limit`]): an error
/// at the card of the largest part if beyond it.
pub fn check(file: &str, deck: &Deck) -> Result<(), DeckError> {
    let limit = memory::limit().map_err(|m| DeckError {
        kind: K::BadValue,
        file: file.to_string(),
        line: 0,
        keyword: MAX_MEMORY_VAR.into(),
        message: m,
    })?;
    let Some((limit, source)) = limit else {
        return Ok(());
    };
    let parts = parts(deck);
    let total = BASE_BYTES + parts.iter().map(|p| p.bytes).sum::<f64>();
    if total <= limit {
        return Ok(());
    }
    let Some(p) = parts.iter().max_by(|a, b| a.bytes.total_cmp(&b.bytes)) else {
        return Ok(());
    };
    Err(p.origin.error(
        K::BadValue,
        p.keyword,
        format!(
            "the run needs about {} of memory ({}: {}), more than the {} {}; make the model smaller, or set {MAX_MEMORY_VAR}=<bytes> (e.g. 64G) to run it anyway",
            format_bytes(total),
            p.what,
            format_bytes(p.bytes),
            format_bytes(limit),
            source.describe(),
        ),
    ))
}
