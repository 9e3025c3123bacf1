//! A deck's contact pairs: one interface per pair, one contact point per paired slave
//! node that is not held in every direction (`fe::pairing`).

use std::collections::HashMap;

use super::{coupling, frame, gaps, unmatched};
use crate::fe::assembly::System;
use crate::fe::mesh::Model;
use crate::fe::pairing::PairedNode;
use crate::input::deck::job::DeckJob;
use crate::input::deck::summary::{pair_surfaces, pair_tolerance};
use crate::input::deck::DeckErrorKind;
use crate::model::{BuildError, ContactPoint, Interface};

/// A paired slave node and the index of its interface.
pub(super) type PairedPoint = (PairedNode, usize);

/// The interfaces of `job`'s contact pairs and their paired slave nodes (with the
/// interface of each); warnings on unmatched or gapped slave nodes added to `warnings`
/// (`length`: the unit). A slave node in two pairs is refused.
pub(super) fn contact_pairs(
    job: &DeckJob,
    model: &Model,
    length: &str,
    warnings: &mut Vec<String>,
) -> Result<(Vec<Interface>, Vec<PairedPoint>), BuildError> {
    let deck = &job.deck;
    let mut interfaces = Vec::new();
    let mut raw = Vec::new(); // (paired node, interface)
    let mut slave_of: HashMap<usize, usize> = HashMap::new(); // slave node → contact pair
    for (ci, (c, l)) in deck.contact_pairs.iter().zip(&job.laws).enumerate() {
        interfaces.push(Interface {
            name: format!("{}/{}", c.slave, c.master),
            contact: *l,
            initial_gap: 0.0,
        });
        let tol = pair_tolerance(deck, &c.master, None);
        let p = pair_surfaces(
            deck,
            &c.slave,
            &c.master,
            tol.search,
            &c.origin,
            "*CONTACT PAIR",
        )?;
        let at = format!(
            "{}:{}: *CONTACT PAIR {}/{}",
            c.origin.file, c.origin.line, c.slave, c.master
        );
        for n in &p.nodes {
            if let Some(&other) = slave_of.get(&n.slave) {
                let o = &deck.contact_pairs[other];
                return Err(c.origin.error(
                    DeckErrorKind::Duplicate,
                    "*CONTACT PAIR",
                    format!(
                        "slave node {} is in {}/{} and in {}/{} (line {}): it would get two contact points",
                        deck.nodes[n.slave].id, c.slave, c.master, o.slave, o.master, o.origin.line
                    ),
                )
                .into());
            }
        }
        slave_of.extend(p.nodes.iter().map(|n| (n.slave, ci)));
        if let Some(w) = unmatched(deck, &at, &p) {
            warnings.push(w);
        }
        if let Some(w) = gaps(
            deck,
            &at,
            &p,
            tol.round_off,
            length,
            "the run takes the surfaces as touching (gap 0)",
        ) {
            warnings.push(w);
        }
        let all_fixed = |n: &PairedNode| {
            coupling(n)
                .iter()
                .all(|&(node, _)| (0..3).all(|g| model.fixed[3 * node + g]))
        };
        raw.extend(
            p.nodes
                .into_iter()
                .filter(|n| !all_fixed(n))
                .map(|n| (n, interfaces.len() - 1)),
        );
    }
    Ok((interfaces, raw))
}

/// The contact points of the paired slave nodes `raw`: their relative-displacement rows
/// (free DOFs of `sys`) in the master's frame; point k is coupling `first_contact + k`.
pub(super) fn contact_points(
    raw: &[PairedPoint],
    sys: &System,
    model: &Model,
    first_contact: usize,
) -> Vec<ContactPoint> {
    raw.iter()
        .enumerate()
        .map(|(k, (n, interface))| {
            let q = frame(n);
            let cpl = coupling(n);
            let rows = std::array::from_fn(|c| {
                let mut r = Vec::new();
                for &(node, w) in &cpl {
                    for g in 0..3 {
                        let v = w * q[(g, c)];
                        if let Some(f) = sys.dofs.free(3 * node + g) {
                            if v != 0.0 {
                                r.push((f, v));
                            }
                        }
                    }
                }
                r
            });
            let master = n
                .weights
                .iter()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .map_or(n.slave, |w| w.0);
            ContactPoint {
                pair: first_contact + k,
                nodes: [master, n.slave],
                frame: q,
                area: n.area,
                interface: *interface,
                position: model.nodes[n.slave],
                rows,
                samples: Vec::new(),
            }
        })
        .collect()
}
