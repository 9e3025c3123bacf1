//! A step's loads as nodal forces (force units, global axes, full DOFs): `*CLOAD`
//! forces, `*DLOAD` Pn and `*DSLOAD` P pressures (positive into the face), their real and
//! imaginary (`IMAGINARY`) parts apart.

use crate::fe::elements::face::{add_pressure, MeshFace};
use crate::input::deck::job::DeckJob;
use crate::input::deck::summary::faces;
use crate::input::deck::{DeckError, DeckErrorKind as K, ElementTarget, Step};

/// The nodal forces of step `st` over `n_dofs` full DOFs: (real parts, imaginary parts).
pub type PartLoads = (Vec<f64>, Vec<f64>);

/// [`PartLoads`] of step `st`.
pub fn step_loads(job: &DeckJob, st: &Step, n_dofs: usize) -> Result<PartLoads, DeckError> {
    let d = &job.deck;
    let (mut re, mut im) = (vec![0.0; n_dofs], vec![0.0; n_dofs]);
    let x: Vec<[f64; 3]> = d.nodes.iter().map(|n| n.x).collect();
    let mut in_element = vec![false; d.nodes.len()];
    for e in &d.elements {
        for n in &e.nodes {
            in_element[d.node_index[n]] = true;
        }
    }
    for l in &st.cloads {
        let f = if l.imaginary { &mut im } else { &mut re };
        for id in job.target_nodes(&l.target) {
            if !in_element[d.node_index[&id]] {
                return Err(l.origin.error(
                    K::BadValue,
                    "*CLOAD",
                    format!("node {id} is in no element: the load would act on nothing"),
                ));
            }
            f[3 * d.node_index[&id] + (l.dof as usize - 1)] += l.value;
        }
    }
    for l in &st.dloads {
        let ids = match &l.elements {
            ElementTarget::Element(id) => vec![*id],
            ElementTarget::Set(s) => d.element_sets[s].clone(),
        };
        for id in ids {
            let ei = d.element_index[&id];
            let e = &d.elements[ei];
            let conn: Vec<usize> = e.nodes.iter().map(|n| d.node_index[n]).collect();
            let face = MeshFace::new(e.kind, ei, &conn, l.face).ok_or_else(|| {
                l.origin.error(
                    K::BadValue,
                    "*DLOAD",
                    format!("element {id} ({}) has no face P{}", e.kind, l.face + 1),
                )
            })?;
            let f = if l.imaginary { &mut im } else { &mut re };
            add_pressure(&x, &face, l.pressure, f);
        }
    }
    for l in &st.dsloads {
        for face in faces(d, &l.surface, &l.origin, "*DSLOAD")? {
            let f = if l.imaginary { &mut im } else { &mut re };
            add_pressure(&x, &face, l.pressure, f);
        }
    }
    Ok((re, im))
}
