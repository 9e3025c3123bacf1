//! A deck's ties: a conforming tie merges each slave node with its coincident master
//! node (one set of DOFs, exact, as Abaqus eliminates a tie's slave DOFs); any other
//! tie becomes penalty couplings, added to K after assembly.

use super::{coincident, coupling, gaps, unmatched, TIE_PENALTY};
use crate::fe::mesh::Model;
use crate::fe::pair_blocks::Coupling;
use crate::input::deck::job::DeckJob;
use crate::input::deck::summary::{self, pair_surfaces, pair_tolerance};
use crate::input::deck::DeckErrorKind;
use crate::model::BuildError;

/// A penalty tie's spring: its coupling's index and stiffness (force/length).
pub(super) type TieSpring = (usize, f64);

/// The ties of `job`: conforming ones merged into `model.ties`; the others' penalty
/// couplings and their springs (coupling index, stiffness in force/length), warnings
/// on unmatched or gapped slave nodes added to `warnings` (`length`: the unit).
pub(super) fn ties(
    job: &DeckJob,
    model: &mut Model,
    length: &str,
    warnings: &mut Vec<String>,
) -> Result<(Vec<Coupling>, Vec<TieSpring>), BuildError> {
    let deck = &job.deck;
    let e_max = model
        .materials
        .iter()
        .map(|m| m.youngs_modulus)
        .fold(0.0, f64::max);

    let mut couplings: Vec<Coupling> = Vec::new();
    let mut tie_springs = Vec::new();
    for t in &deck.ties {
        let tol = pair_tolerance(deck, &t.master, t.position_tolerance);
        let at = format!("{}:{}: *TIE {}", t.origin.file, t.origin.line, t.name);
        // Paired within the face size, so that a node beyond the position tolerance is
        // named rather than left out.
        let wide = tol.search.max(tol.round_off / summary::ROUND_OFF);
        let p = pair_surfaces(deck, &t.slave, &t.master, wide, &t.origin, "*TIE")?;
        if let Some(n) = p.nodes.iter().find(|n| n.gap.abs() > tol.search) {
            return Err(t.origin.error(
                DeckErrorKind::BadValue,
                "*TIE",
                format!(
                    "slave node {} lies {:e} {length} from master {}, beyond the position tolerance {:e} {length} ({}): Abaqus would leave it untied",
                    deck.nodes[n.slave].id,
                    n.gap.abs(),
                    t.master,
                    tol.search,
                    if t.position_tolerance.is_some() { "POSITION TOLERANCE=" } else { "the default, 5 % of the master's typical face diagonal" },
                ),
            )
            .into());
        }
        if let Some(merged) = coincident(&model.nodes, &p, tol.round_off) {
            model.ties.extend(merged);
            continue;
        }
        if t.surface_to_surface {
            return Err(t.origin.error(
                DeckErrorKind::Unsupported,
                "*TIE, TYPE=",
                format!("TYPE=SURFACE TO SURFACE on the non-conforming tie {}: this reader ties node to surface (TYPE=NODE TO SURFACE); the two agree only where the meshes conform", t.name),
            )
            .into());
        }
        if let Some(w) = unmatched(deck, &at, &p) {
            warnings.push(w);
        }
        if let Some(w) = gaps(deck, &at, &p, tol.round_off, length, "tied across the gap") {
            warnings.push(w);
        }
        for n in &p.nodes {
            tie_springs.push((couplings.len(), TIE_PENALTY * e_max * n.area.sqrt()));
            couplings.push(coupling(n));
        }
    }

    Ok((couplings, tie_springs))
}
