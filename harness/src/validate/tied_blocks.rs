//! A deck of the kind users bring: a C3D10 (tetrahedral) block on a C3D8 (hexahedral)
//! block with its own, non-conforming mesh, joined by `*TIE` (slave: the hex block's
//! top, the finer side, as Abaqus advises), both clamped at x = 0 (N, mm, s, t; steel). The modes comparison with CalculiX and the eigensolver's cost table run
//! it at growing sizes.

use std::fmt::Write as _;

use crate::fe::elements::box_mesh::{box_mesh, SolidMesh};
use crate::fe::elements::ElementKind;

use super::mesh_cards::mesh_cards;
use super::stack_deck::STEEL;

/// Each block's length, width, height (mm); the tet block sits on the hex block's top.
pub const BLOCK: [f64; 3] = [100.0, 20.0, 10.0];

/// The meshes for a refinement level r ≥ 1: hexes 10r × 2r × 2r, tets (6 per cell)
/// 3r × r × r cells, so the tied interface does not conform.
fn meshes(r: usize) -> (SolidMesh, SolidMesh) {
    let hex = box_mesh(ElementKind::C3D8, BLOCK, [10 * r, 2 * r, 2 * r], 0.0, 0);
    let tet = box_mesh(ElementKind::C3D10, BLOCK, [3 * r, r, r], 0.0, 0);
    (hex, tet)
}

/// `*SURFACE, TYPE=ELEMENT` data lines (element id, Sk) of the faces of `m` whose
/// corners all lie at height z (ids offset by `elem_base`).
fn faces_at_height(m: &SolidMesh, z: f64, elem_base: usize) -> String {
    let mut s = String::new();
    for (e, conn) in m.elements.iter().enumerate() {
        for (face, def) in m.kind.element().faces().iter().enumerate() {
            if def.corners().iter().all(|&k| m.nodes[conn[k]][2] == z) {
                let _ = writeln!(s, "{}, S{}", elem_base + e + 1, face + 1);
            }
        }
    }
    s
}

/// The deck at refinement `r` with one `*FREQUENCY` step of `modes` modes, and its
/// number of free DOFs (clamped nodes removed; the tied slave nodes counted, as the
/// model keeps them).
pub fn tied_blocks_deck(r: usize, modes: usize) -> (String, usize) {
    let (hex, tet) = meshes(r.max(1));
    let mut s = String::from(
        "*HEADING\nC3D10 block tied onto a C3D8 block, non-conforming\n** jointlin units: length=mm force=N time=s mass=t\n",
    );
    mesh_cards(&mut s, &hex, "HEX", (0, 0), [0.0; 3]);
    let (nb, eb) = (hex.nodes.len(), hex.elements.len());
    mesh_cards(&mut s, &tet, "TET", (nb, eb), [0.0, 0.0, BLOCK[2]]);
    let _ = write!(
        s,
        "*SURFACE, NAME=HEX-TOP, TYPE=ELEMENT\n{}*SURFACE, NAME=TET-BOT, TYPE=ELEMENT\n{}",
        faces_at_height(&hex, BLOCK[2], 0),
        faces_at_height(&tet, 0.0, eb)
    );
    let clamped: Vec<usize> = (hex.nodes.iter().enumerate())
        .filter(|(_, p)| p[0] == 0.0)
        .map(|(i, _)| i + 1)
        .chain(
            (tet.nodes.iter().enumerate())
                .filter(|(_, p)| p[0] == 0.0)
                .map(|(i, _)| nb + i + 1),
        )
        .collect();
    s.push_str("*NSET, NSET=CLAMP\n");
    for chunk in clamped.chunks(16) {
        let ids: Vec<String> = chunk.iter().map(usize::to_string).collect();
        let _ = writeln!(s, "{}", ids.join(", "));
    }
    let (e, nu, rho) = STEEL;
    let _ = writeln!(
        s,
        "*ELSET, ELSET=ALL\nHEX, TET\n*MATERIAL, NAME=STEEL\n*ELASTIC\n{e:e}, {nu}\n*DENSITY\n{rho:e}\n\
         *SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n*BOUNDARY\nCLAMP, 1, 3\n\
         *TIE, NAME=GLUE\nHEX-TOP, TET-BOT\n*STEP\n*FREQUENCY\n{modes}\n*END STEP"
    );
    let free = 3 * (hex.nodes.len() + tet.nodes.len() - clamped.len());
    (s, free)
}
