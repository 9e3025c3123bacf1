//! Deck → [`Problem`]: the deck's mesh, materials and zero boundary conditions, its ties
//! (a conforming tie's coincident nodes merged, as a scene's ties are; otherwise penalty
//! couplings of each slave node to its interpolated master face), its contact
//! pairs (one contact point per paired slave node, `fe::pairing`), the static step's
//! loads as preload, the steady-state step's loads as the harmonic excitation, and the
//! scene's outputs on the deck's sets. The scene (a deck run's, or one with `model`)
//! gives the effects and the iteration. The contact laws come from the USER property
//! table (`input::deck::props`).
//!
//! A contact point's relative displacement is the slave node's minus the master face's
//! interpolated one, δ = u_s − Σᵢ Nᵢ u_mᵢ, in the frame of the master's outward normal
//! (model.md §3: n from the lower body, here the master, into the upper one, the
//! slave); its area is the slave node's tributary area.

mod held;
mod loads;
mod mesh;

use std::collections::HashMap;

use nalgebra::{Complex, Matrix3};

use super::damping::material_damping;
use super::{BuildError, ContactPoint, Interface, Output, Problem};
use crate::fe::assembly::assemble_couplings;
use crate::fe::pair_blocks::Coupling;
use crate::fe::pairing::{PairedNode, Pairing};
use crate::input::deck::error::DeckWarning;
use crate::input::deck::job::DeckJob;
use crate::input::deck::summary::{self, pair_surfaces, pair_tolerance};
use crate::input::deck::Deck;
use crate::input::deck::DeckErrorKind;
use crate::input::scene::Scene;

/// Tie penalty: each tied slave node is held to its master face by a spring
/// TIE_PENALTY · E · √A per direction (E the stiffest material's modulus, A the node's
/// tributary area): about 1e5 times the stiffness of the elements it joins, so the tie
/// gives way by about 1e-5 of the elements' own deformation.
pub const TIE_PENALTY: f64 = 1e5;

/// The coupling of a paired slave node: δ = u_slave − Σᵢ Nᵢ u_masterᵢ (master nodes
/// of weight zero left out: a node coincident with a master node couples to that node
/// alone, as a scene's coincident pair does).
fn coupling(p: &PairedNode) -> Coupling {
    std::iter::once((p.slave, 1.0))
        .chain(
            p.weights
                .iter()
                .filter(|&&(_, w)| w != 0.0)
                .map(|&(m, w)| (m, -w)),
        )
        .collect()
}

/// Frame columns n, t₁, t₂ (global axes) of a paired node.
fn frame(p: &PairedNode) -> Matrix3<f64> {
    Matrix3::from_fn(|g, c| p.frame[c][g])
}

/// The `[slave, master]` node pairs of a conforming pairing: every slave node paired
/// and lying within `tol` (length) of a node of its master face; None otherwise.
fn coincident(x: &[[f64; 3]], p: &Pairing, tol: f64) -> Option<Vec<[usize; 2]>> {
    if !p.unmatched.is_empty() {
        return None;
    }
    let dist = |a: usize, b: usize| {
        (0..3)
            .map(|c| (x[a][c] - x[b][c]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    p.nodes
        .iter()
        .map(|n| {
            n.weights
                .iter()
                .map(|&(m, _)| m)
                .find(|&m| dist(n.slave, m) <= tol)
                .map(|m| [n.slave, m])
        })
        .collect()
}

/// Unmatched slave nodes, as a warning line.
fn unmatched(deck: &Deck, what: &str, p: &Pairing) -> Option<String> {
    p.unmatched_report(|n| deck.nodes[n].id)
        .map(|r| format!("{what}: {r}; they are left out"))
}

/// Slave nodes off the master surface by more than `round_off` (length), as a warning
/// line naming how many, the largest gap and its node, and what the run makes of it.
fn gaps(
    deck: &Deck,
    at: &str,
    p: &Pairing,
    round_off: f64,
    length: &str,
    taken: &str,
) -> Option<String> {
    let off: Vec<&PairedNode> = p.nodes.iter().filter(|n| n.gap.abs() > round_off).collect();
    let worst = off
        .iter()
        .max_by(|a, b| a.gap.abs().total_cmp(&b.gap.abs()))?;
    Some(format!(
        "{at}: {} slave nodes lie off the master surface, up to {:e} {length} (node {}); {taken}",
        off.len(),
        worst.gap.abs(),
        deck.nodes[worst.slave].id
    ))
}

/// The deck reader's notes and warnings for the run log, and the nodes in no element
/// (dropped) among the warnings.
fn findings(job: &DeckJob, orphans: &[u64]) -> (Vec<String>, Vec<String>) {
    let (notes, warnings): (Vec<_>, Vec<_>) = job.warnings.iter().partition(|w| w.note);
    let text = |v: Vec<&DeckWarning>| -> Vec<String> { v.iter().map(|w| w.to_string()).collect() };
    let mut warnings = text(warnings);
    if !orphans.is_empty() {
        let shown: Vec<String> = orphans.iter().take(10).map(u64::to_string).collect();
        warnings.push(format!(
            "{}: {} nodes in no element ({}{}): dropped, as Abaqus ignores them",
            job.file,
            orphans.len(),
            shown.join(", "),
            if orphans.len() > 10 { ", …" } else { "" }
        ));
    }
    (text(notes), warnings)
}

/// Builds the problem of a deck for `scene` (its effects and outputs).
pub fn build(scene: &Scene, job: &DeckJob) -> Result<Problem, BuildError> {
    let deck = &job.deck;
    let mesh::DeckMesh {
        mut model,
        rayleigh,
        structural,
        orphans,
    } = mesh::mesh(job)?;
    let (notes, mut warnings) = findings(job, &orphans);
    let length = &scene.spec.units.length;
    let e_max = model
        .materials
        .iter()
        .map(|m| m.youngs_modulus)
        .fold(0.0, f64::max);

    // Ties: a conforming tie merges each slave node with its coincident master node
    // (one set of DOFs, exact, as Abaqus eliminates a tie's slave DOFs); any other tie
    // becomes penalty couplings, added to K after assembly.
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

    // Contact pairs: interfaces and their points.
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
    let first_contact = couplings.len();
    couplings.extend(raw.iter().map(|(n, _)| coupling(n)));
    let groups: Vec<Vec<usize>> = (couplings.iter())
        .map(|c| c.iter().map(|&(n, _)| n).collect())
        .collect();
    if let Some(l) = held::loose_parts(&model, &groups).first() {
        let ids: Vec<String> = l
            .nodes
            .iter()
            .take(5)
            .map(|&i| deck.nodes[i].id.to_string())
            .collect();
        return Err(crate::input::deck::DeckError {
            kind: DeckErrorKind::BadValue,
            file: job.file.clone(),
            line: 0,
            keyword: "*BOUNDARY".into(),
            message: format!(
                "the model is not held: {} rigid-body modes in the part of {} nodes ({}{}); hold it with *BOUNDARY (a free model's modes at 0 Hz are not computed)",
                l.modes,
                l.nodes.len(),
                ids.join(", "),
                if l.nodes.len() > 5 { ", …" } else { "" }
            ),
        }
        .into());
    }

    let mut sys = assemble_couplings(&model, &couplings)?;
    for &(k, spring) in &tie_springs {
        sys.pairs.add(
            &mut sys.k.values,
            k,
            &Matrix3::from_diagonal_element(spring),
        );
    }
    let (damping, structural) = if scene.spec.effects.material_damping {
        let hysteretic: Vec<(f64, f64)> = structural.iter().map(|&s| (0.0, s)).collect();
        (
            material_damping(&model, &sys, &rayleigh)?,
            material_damping(&model, &sys, &hysteretic)?,
        )
    } else {
        (None, None)
    };

    let contacts = raw
        .iter()
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
        .collect();

    // Preload (the static step) and excitation (the steady-state step's loads).
    let n = model.n_dofs();
    // (A static step's imaginary loads are refused by the deck job's step check.)
    let (pre, _) = match job.preload {
        Some(i) => loads::step_loads(job, &deck.steps[i], n)?,
        None => (vec![0.0; n], vec![0.0; n]),
    };
    let (exc_re, exc_im) = match job.dynamics {
        Some(i) => loads::step_loads(job, &deck.steps[i], n)?,
        None => (vec![0.0; n], vec![0.0; n]),
    };
    model.loads = pre.clone();
    let preload = sys.dofs.restrict(&pre);
    let excitation = (sys.dofs.restrict(&exc_re).into_iter())
        .zip(sys.dofs.restrict(&exc_im))
        .map(|(re, im)| Complex::new(re, im))
        .collect();

    let outputs = scene
        .spec
        .outputs
        .iter()
        .map(|o| {
            let node = output_node(job, &o.body, o.at).ok_or_else(|| {
                BuildError::Other(format!(
                    "{}: output `{}`: `{}` is neither a node set nor an element set of {}",
                    scene.file, o.name, o.body, job.file
                ))
            })?;
            let len = o.direction.iter().map(|v| v * v).sum::<f64>().sqrt();
            let dofs = (0..3)
                .filter_map(|c| {
                    sys.dofs
                        .free(3 * node + c)
                        .map(|f| (f, o.direction[c] / len))
                })
                .filter(|&(_, w)| w != 0.0)
                .collect();
            Ok(Output {
                name: o.name.clone(),
                node,
                dofs,
            })
        })
        .collect::<Result<Vec<_>, BuildError>>()?;

    Ok(Problem {
        model,
        sys,
        damping,
        structural,
        modal_damping: scene.spec.sweep.modal_damping.clone(),
        interfaces,
        contacts,
        cubic_springs: Vec::new(),
        preload,
        excitation,
        outputs,
        screws: Vec::new(),
        warnings,
        notes,
    })
}

/// The node of set `set` (a node set, else an element set's nodes) nearest `at` (its
/// first node without `at`).
fn output_node(job: &DeckJob, set: &str, at: Option<[f64; 3]>) -> Option<usize> {
    let d = &job.deck;
    let ids: Vec<u64> = match (d.node_sets.get(set), d.element_sets.get(set)) {
        (Some(n), _) => n.clone(),
        (None, Some(e)) => e
            .iter()
            .flat_map(|id| d.elements[d.element_index[id]].nodes.iter().copied())
            .collect(),
        (None, None) => return None,
    };
    let nodes = ids.iter().map(|id| d.node_index[id]);
    match at {
        None => nodes.into_iter().next(),
        Some(p) => nodes.min_by(|&a, &b| {
            let dist = |n: usize| {
                (0..3)
                    .map(|c| (d.nodes[n].x[c] - p[c]).powi(2))
                    .sum::<f64>()
            };
            dist(a).total_cmp(&dist(b))
        }),
    }
}
