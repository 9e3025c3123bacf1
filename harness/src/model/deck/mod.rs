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
mod pairs;
mod ties;

use nalgebra::{Complex, Matrix3};

use super::damping::material_damping;
use super::{BuildError, Output, Problem};
use crate::fe::assembly::{assemble_couplings, System};
use crate::fe::pair_blocks::Coupling;
use crate::fe::pairing::{PairedNode, Pairing};
use crate::input::deck::error::DeckWarning;
use crate::input::deck::job::DeckJob;
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
    let (mut couplings, tie_springs) = ties::ties(job, &mut model, length, &mut warnings)?;

    let (interfaces, raw) = pairs::contact_pairs(job, &model, length, &mut warnings)?;
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

    let contacts = pairs::contact_points(&raw, &sys, &model, first_contact);

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

    let outputs = outputs(scene, job, &sys)?;

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

/// The scene's outputs on `job`'s sets: the node of each (the nearest its `at`) and its
/// direction's weights on the free DOFs of `sys`.
fn outputs(scene: &Scene, job: &DeckJob, sys: &System) -> Result<Vec<Output>, BuildError> {
    scene
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
        .collect()
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
