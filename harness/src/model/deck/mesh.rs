//! The deck's nodes, elements, sections and materials as a [`Model`] (node i = the
//! deck's i-th node, element j = its j-th element), and its zero boundary conditions.

use std::collections::HashMap;

use crate::fe::mesh::{Element, Material, Model};
use crate::input::deck::job::DeckJob;
use crate::input::deck::{DeckError, DeckErrorKind as K};

/// The model of a deck and each material's Rayleigh coefficients (α 1/time, β time).
pub struct DeckMesh {
    pub model: Model,
    pub rayleigh: Vec<(f64, f64)>,
    /// Each material's structural damping factor s (0: none).
    pub structural: Vec<f64>,
    /// Ids of the nodes in no element (Gmsh and Abaqus/CAE write them; Abaqus ignores
    /// them): their DOFs are held, so that they carry no stiffness-free unknowns.
    pub orphans: Vec<u64>,
}

/// Nodes, elements with their section's material, and the boundary conditions (DOFs
/// 1–3 held at zero; DOFs 4–6 are rotations, which solid nodes do not have).
pub fn mesh(job: &DeckJob) -> Result<DeckMesh, DeckError> {
    let d = &job.deck;
    let mut index: HashMap<&str, usize> = HashMap::new();
    let mut materials = Vec::new();
    let mut rayleigh = Vec::new();
    let mut structural = Vec::new();
    let mut material_of: HashMap<u64, usize> = HashMap::new();
    for s in &d.sections {
        let m = &d.materials[&s.material];
        let next = materials.len();
        let i = *index.entry(m.name.as_str()).or_insert(next);
        if i == next {
            let (e, nu) = m.elastic.expect("checked by the reader");
            let rho = m.density.expect("checked by DeckJob");
            let mat = Material::new(e, nu, rho)
                .map_err(|x| m.origin.error(K::BadValue, "*MATERIAL", x.to_string()))?;
            materials.push(mat);
            rayleigh.push(m.damping.unwrap_or((0.0, 0.0)));
            structural.push(m.structural.unwrap_or(0.0));
        }
        for id in &d.element_sets[&s.element_set] {
            material_of.insert(*id, i);
        }
    }
    let mut model = Model::new(materials);
    model.nodes = d.nodes.iter().map(|n| n.x).collect();
    model.elements = d
        .elements
        .iter()
        .map(|e| Element {
            kind: e.kind,
            nodes: e.nodes.iter().map(|n| d.node_index[n]).collect(),
            material: material_of[&e.id],
        })
        .collect();
    model.fixed = vec![false; model.n_dofs()];
    model.loads = vec![0.0; model.n_dofs()];
    let mut used = vec![false; model.nodes.len()];
    for e in &model.elements {
        for &n in &e.nodes {
            used[n] = true;
        }
    }
    let orphans: Vec<u64> = (0..used.len())
        .filter(|&i| !used[i])
        .map(|i| d.nodes[i].id)
        .collect();
    for (i, u) in used.iter().enumerate() {
        if !u {
            model.fixed[3 * i..3 * i + 3].fill(true);
        }
    }
    for b in d
        .boundaries
        .iter()
        .chain(d.steps.iter().flat_map(|s| &s.boundaries))
    {
        let comps: [bool; 3] = std::array::from_fn(|c| (b.first..=b.last).contains(&(c as u8 + 1)));
        let nodes: Vec<usize> = job
            .target_nodes(&b.target)
            .iter()
            .map(|id| d.node_index[id])
            .collect();
        model
            .fix(&nodes, comps)
            .map_err(|x| b.origin.error(K::BadValue, "*BOUNDARY", x.to_string()))?;
    }
    Ok(DeckMesh {
        model,
        rayleigh,
        structural,
        orphans,
    })
}
