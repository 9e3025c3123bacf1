//! The mesh cards of the decks the CalculiX comparisons write: a structured box mesh
//! ([`crate::fe::elements::box_mesh::box_mesh`]) as `*NODE` and `*ELEMENT` cards.

use std::fmt::Write as _;

use crate::fe::elements::box_mesh::SolidMesh;

/// Node ids per data line of an `*ELEMENT` card: Abaqus (and CalculiX) continue an
/// element with more nodes (C3D20) on the next line.
const IDS_PER_LINE: usize = 16;

/// Appends `*NODE` (node i of `m` as id `node_base + i + 1`, moved by `offset`, length)
/// and `*ELEMENT, TYPE=<kind>, ELSET=<elset>` (element e as id `elem_base + e + 1`) to
/// `s`.
pub fn mesh_cards(
    s: &mut String,
    m: &SolidMesh,
    elset: &str,
    (node_base, elem_base): (usize, usize),
    offset: [f64; 3],
) {
    s.push_str("*NODE\n");
    for (i, p) in m.nodes.iter().enumerate() {
        let _ = writeln!(
            s,
            "{}, {}, {}, {}",
            node_base + i + 1,
            p[0] + offset[0],
            p[1] + offset[1],
            p[2] + offset[2]
        );
    }
    let _ = writeln!(s, "*ELEMENT, TYPE={}, ELSET={elset}", m.kind.name());
    for (e, conn) in m.elements.iter().enumerate() {
        let _ = write!(s, "{}", elem_base + e + 1);
        for (k, n) in conn.iter().enumerate() {
            s.push_str(if k % IDS_PER_LINE == IDS_PER_LINE - 1 {
                ",\n"
            } else {
                ", "
            });
            let _ = write!(s, "{}", node_base + n + 1);
        }
        s.push('\n');
    }
}
