//! Gmsh's Abaqus export (`gmsh -3 -format inp`, with `Mesh.SaveGroupsOfNodes = 1`) made
//! into a mesh file that a deck can `*INCLUDE`.
//!
//! Gmsh (4.8) writes the elements of every physical group: a physical surface comes out
//! as plane-stress facets (`CPS3`, `CPS6`; `CPS4`, `CPS8` on hexahedral meshes) under an
//! `*ELSET` of the physical name, and a physical curve as `T3D2`/`T3D3` lines. A 3D deck
//! cannot hold these: they would be structural elements. Here each facet becomes the
//! face of the one solid element it bounds, so a physical surface becomes
//! `*SURFACE, TYPE=ELEMENT, NAME=<physical name>` with face labels S1…S6 (as Abaqus and
//! CalculiX read them); lines and their sets are dropped; nodes, solid elements, the
//! element sets of solid elements and every node set are kept.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::Path;

use crate::fe::elements::ElementKind;

use super::error::{DeckError, DeckErrorKind as K};
use super::lexer::{self, parse_id, parse_number, truncate, Card};

/// Facet types Gmsh writes for surface elements (corners first).
const FACETS: &[(&str, usize)] = &[
    ("CPS3", 3),
    ("CPS6", 6),
    ("CPS4", 4),
    ("CPS8", 8),
    ("S3", 3),
    ("S6", 6),
    ("S4", 4),
    ("S8", 8),
];

/// Line types Gmsh writes for curve elements (dropped).
const LINES: &[(&str, usize)] = &[("T3D2", 2), ("T3D3", 3)];

/// The deck mesh text of the Gmsh export `path` (see the module doc).
pub fn deck_mesh_from_gmsh(path: &Path) -> Result<String, DeckError> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    convert(&lexer::read_file(path)?.0, &name)
}

/// What an element id of the export is.
enum Member {
    Solid,
    /// A facet: its corner node ids, sorted.
    Facet(Vec<u64>),
    Line,
}

/// Ids of a card's data lines (empty fields skipped), each checked to be an id, with
/// its line and whether it is the line's last.
fn ids(card: &Card) -> Result<Vec<(u64, usize, bool)>, DeckError> {
    let mut out = Vec::new();
    for l in &card.data {
        let fields: Vec<&String> = l.fields.iter().filter(|f| !f.is_empty()).collect();
        for (k, f) in fields.iter().enumerate() {
            let id = parse_id(f).ok_or_else(|| {
                card.error_at(
                    l.line,
                    K::Syntax,
                    format!("{:?} is not a positive integer", truncate(f)),
                )
            })?;
            out.push((id, l.line, k + 1 == fields.len()));
        }
    }
    Ok(out)
}

/// Writes `ids` 10 to a line.
fn write_ids(s: &mut String, ids: &[u64]) {
    for chunk in ids.chunks(10) {
        let line: Vec<String> = chunk.iter().map(u64::to_string).collect();
        let _ = writeln!(s, "{}", line.join(", "));
    }
}

/// Converts the cards of a Gmsh export named `name` (for the header comment).
pub fn convert(cards: &[Card], name: &str) -> Result<String, DeckError> {
    let mut out = format!(
        "** Mesh from the Gmsh export {name}: physical surfaces as element-face surfaces\n\
         ** (`jointlin deck from-gmsh`).\n"
    );
    let mut members: HashMap<u64, Member> = HashMap::new();
    // Sorted face corners → (element id, face index) of every solid element face.
    let mut faces: HashMap<Vec<u64>, Vec<(u64, usize)>> = HashMap::new();
    let mut sets = String::new();
    let mut surfaces: BTreeMap<String, Vec<(u64, usize)>> = BTreeMap::new();
    for card in cards {
        match card.keyword.as_str() {
            "HEADING" => {}
            "NODE" => {
                out.push_str("*NODE\n");
                for l in card.data.iter().filter(|l| !l.fields.is_empty()) {
                    let id = parse_id(&l.fields[0]);
                    let x: Vec<Option<f64>> = (1..4)
                        .map(|c| l.fields.get(c).and_then(|f| parse_number(f)))
                        .collect();
                    match (id, x.as_slice()) {
                        (Some(id), [Some(a), Some(b), Some(c)]) => {
                            let _ = writeln!(out, "{id}, {a}, {b}, {c}");
                        }
                        _ => {
                            return Err(card.error_at(
                                l.line,
                                K::Syntax,
                                "expected node id, x, y, z",
                            ))
                        }
                    }
                }
            }
            "ELEMENT" => element(card, &mut out, &mut members, &mut faces)?,
            "ELSET" => {
                let set = card.required("ELSET")?.trim().to_ascii_uppercase();
                let list = ids(card)?;
                let (mut solid, mut facet) = (Vec::new(), Vec::new());
                for &(id, line, _) in &list {
                    match members.get(&id) {
                        Some(Member::Solid) => solid.push(id),
                        Some(Member::Facet(c)) => facet.push((id, c, line)),
                        Some(Member::Line) => {}
                        None => {
                            return Err(card.error_at(
                                line,
                                K::Undefined,
                                format!("element {id} is not defined"),
                            ))
                        }
                    }
                }
                if !solid.is_empty() && !facet.is_empty() {
                    return Err(card.error(
                        K::Unsupported,
                        format!("set {set} mixes solid elements and surface facets"),
                    ));
                }
                if !solid.is_empty() {
                    let _ = writeln!(sets, "*ELSET, ELSET={set}");
                    write_ids(&mut sets, &solid);
                }
                for (id, corners, line) in facet {
                    let found = faces.get(corners).map(Vec::as_slice).unwrap_or(&[]);
                    let face = match found {
                        [one] => *one,
                        [] => {
                            return Err(card.error_at(
                                line,
                                K::BadValue,
                                format!(
                                    "facet {id} of surface {set} is no face of a solid element"
                                ),
                            ))
                        }
                        [a, b, ..] => {
                            return Err(card.error_at(
                                line,
                                K::BadValue,
                                format!(
                                    "facet {id} of surface {set} lies between elements {} and {} \
                                     (an inner face; a surface must bound the mesh)",
                                    a.0, b.0
                                ),
                            ))
                        }
                    };
                    surfaces.entry(set.clone()).or_default().push(face);
                }
            }
            "NSET" => {
                let set = card.required("NSET")?.trim().to_ascii_uppercase();
                let list: Vec<u64> = ids(card)?.into_iter().map(|(id, _, _)| id).collect();
                let _ = writeln!(sets, "*NSET, NSET={set}");
                write_ids(&mut sets, &list);
            }
            _ => {
                return Err(card.error(
                    K::Unsupported,
                    "not a keyword of Gmsh's export (*NODE, *ELEMENT, *ELSET, *NSET)",
                ))
            }
        }
    }
    out.push_str(&sets);
    for (set, list) in &surfaces {
        let _ = writeln!(out, "*SURFACE, TYPE=ELEMENT, NAME={set}");
        for (id, face) in list {
            let _ = writeln!(out, "{id}, S{}", face + 1);
        }
    }
    Ok(out)
}

/// One `*ELEMENT` card: solid elements are written to `out` and their faces indexed,
/// facets and lines are recorded in `members`. An element's ids may continue over
/// several data lines.
fn element(
    card: &Card,
    out: &mut String,
    members: &mut HashMap<u64, Member>,
    faces: &mut HashMap<Vec<u64>, Vec<(u64, usize)>>,
) -> Result<(), DeckError> {
    let ty = card.required("TYPE")?.trim().to_ascii_uppercase();
    let solid = ElementKind::from_name(&ty);
    let facet = FACETS.iter().find(|(n, _)| *n == ty).map(|&(_, k)| k);
    let line = LINES.iter().find(|(n, _)| *n == ty).map(|&(_, k)| k);
    let Some(need) = solid.map(ElementKind::node_count).or(facet).or(line) else {
        return Err(card.error(
            K::Unsupported,
            format!(
                "element type {ty}: solids C3D4, C3D10, C3D6, C3D15, C3D8, C3D20, facets \
                 CPS3/6, CPS4/8, lines T3D2/3"
            ),
        ));
    };
    if let Some(kind) = solid {
        let set = card
            .param("ELSET")
            .map(|s| format!(", ELSET={}", s.trim()))
            .unwrap_or_default();
        let _ = writeln!(out, "*ELEMENT, TYPE={kind}{set}");
    }
    let mut v: Vec<u64> = Vec::with_capacity(need + 1);
    for (id, line, last_on_line) in ids(card)? {
        v.push(id);
        if v.len() < need + 1 {
            continue;
        }
        if !last_on_line {
            // Gmsh writes its 18-node prism as C3D6: read on, it would be misread.
            return Err(card.error_at(
                line,
                K::Syntax,
                format!(
                    "element {} lists more than the {need} nodes of a {ty} (a second-order \
                     Gmsh mesh: export with Mesh.SecondOrderIncomplete = 1)",
                    v[0]
                ),
            ));
        }
        let (id, nodes) = (v[0], &v[1..]);
        if members.contains_key(&id) {
            return Err(card.error_at(line, K::Duplicate, format!("element {id} defined twice")));
        }
        let member = match (solid, facet) {
            (Some(kind), _) => {
                for (s, face) in kind.element().faces().iter().enumerate() {
                    let mut key: Vec<u64> = face.corners().iter().map(|&i| nodes[i]).collect();
                    key.sort_unstable();
                    faces.entry(key).or_default().push((id, s));
                }
                // At most 16 entries per data line (Abaqus): continue longer ones.
                for (k, n) in v.iter().enumerate() {
                    let sep = match k {
                        0 => "",
                        16 => ",\n",
                        _ => ", ",
                    };
                    let _ = write!(out, "{sep}{n}");
                }
                out.push('\n');
                Member::Solid
            }
            (None, Some(k)) => {
                let mut key = nodes[..if k == 3 || k == 6 { 3 } else { 4 }].to_vec();
                key.sort_unstable();
                Member::Facet(key)
            }
            _ => Member::Line,
        };
        members.insert(id, member);
        v.clear();
    }
    if !v.is_empty() {
        return Err(card.error(
            K::Syntax,
            format!("the last {ty} has {} of its {need} nodes", v.len() - 1),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::input::deck::{read_str, SurfaceKind};

    /// Two C3D4 tetrahedra on either side of the face 1-2-3 (element 1 above, 2 below),
    /// as Gmsh writes them: a physical surface of facets, a physical curve, sets.
    const EXPORT: &str = "\
*Heading
 t.inp
*NODE
1, 0, 0, 0
2, 1, 0, 0
3, 0, 1, 0
4, 0, 0, 1
5, 0, 0, -1
******* E L E M E N T S *************
*ELEMENT, type=T3D2, ELSET=Line1
30, 1, 4
*ELEMENT, type=CPS3, ELSET=Surface1
10, 1, 2, 4
12, 4, 3, 2
*ELEMENT, type=C3D4, ELSET=Volume1
1, 1, 2, 3, 4
*ELEMENT, type=C3D4, ELSET=Volume2
2, 1, 3, 2, 5
*ELSET,ELSET=EDGE
30, 
*ELSET,ELSET=SIDE
10, 12, 
*ELSET,ELSET=TOP
1, 
*NSET,NSET=SIDE
1, 2, 3, 4, 
";

    fn convert_text(text: &str) -> Result<String, DeckError> {
        convert(&lexer::read_str(text, "t.inp", Path::new("."))?, "t.inp")
    }

    #[test]
    fn facets_become_the_faces_they_cover() {
        let mesh = convert_text(EXPORT).unwrap();
        let deck = format!(
            "{mesh}*MATERIAL, NAME=M\n*ELASTIC\n1., 0.3\n\
             *SOLID SECTION, ELSET=Volume1, MATERIAL=M\n\
             *SOLID SECTION, ELSET=Volume2, MATERIAL=M\n"
        );
        let (d, warnings) = read_str(&deck, "d.inp", Path::new(".")).unwrap();
        assert!(warnings.is_empty());
        assert_eq!(d.elements.len(), 2);
        // Facet 1-2-4 is S2 (1-4-2) of element 1, facet 4-3-2 its S3 (2-4-3).
        assert_eq!(
            d.surfaces["SIDE"].kind,
            SurfaceKind::Element(vec![(1, 1), (1, 2)])
        );
        assert_eq!(d.node_sets["SIDE"], vec![1, 2, 3, 4]);
        assert_eq!(d.element_sets["TOP"], vec![1]);
        assert!(!d.element_sets.contains_key("EDGE"));
        assert!(!d.element_sets.contains_key("SURFACE1"));
    }

    #[test]
    fn long_connectivities_are_continued_and_reread() {
        // One C3D20 brick: 21 ids, split after 16 on the way out.
        let mut text = String::from("*NODE\n");
        let corners = [
            [0., 0., 0.],
            [1., 0., 0.],
            [1., 1., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
            [1., 0., 1.],
            [1., 1., 1.],
            [0., 1., 1.],
        ];
        let mut x: Vec<[f64; 3]> = corners.to_vec();
        for (a, b) in crate::fe::elements::hex::EDGES {
            x.push([0, 1, 2].map(|c| (corners[a][c] + corners[b][c]) / 2.0));
        }
        for (i, p) in x.iter().enumerate() {
            text.push_str(&format!("{}, {}, {}, {}\n", i + 1, p[0], p[1], p[2]));
        }
        text.push_str("*ELEMENT, type=C3D20, ELSET=Volume1\n7, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10,\n");
        text.push_str("11, 12, 13, 14, 15, 16, 17, 18, 19, 20\n");
        let mesh = convert_text(&text).unwrap();
        assert!(mesh.contains("7, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,\n16,"));
        let deck = format!(
            "{mesh}*MATERIAL, NAME=M\n*ELASTIC\n1., 0.3\n\
             *SOLID SECTION, ELSET=Volume1, MATERIAL=M\n"
        );
        let (d, _) = read_str(&deck, "d.inp", Path::new(".")).unwrap();
        assert_eq!(d.elements[0].nodes, (1..=20).collect::<Vec<u64>>());
    }

    #[test]
    fn what_cannot_be_a_surface_is_a_named_error() {
        let cases = [
            (
                "10, 1, 2, 4",
                "10, 1, 2, 3",
                "lies between elements 1 and 2",
            ),
            (
                "10, 1, 2, 4",
                "10, 1, 4, 5",
                "is no face of a solid element",
            ),
            (
                "*ELSET,ELSET=SIDE\n10, 12,",
                "*ELSET,ELSET=SIDE\n10, 1,",
                "mixes solid elements",
            ),
            ("type=CPS3", "type=M3D3", "element type M3D3"),
            (
                "*ELSET,ELSET=TOP",
                "*MATERIAL, NAME=M\n*ELSET,ELSET=TOP",
                "not a keyword",
            ),
            (
                "12, 4, 3, 2\n",
                "12, 4, 3\n",
                "the last CPS3 has 2 of its 3 nodes",
            ),
            (
                "*ELSET,ELSET=TOP\n1,",
                "*ELSET,ELSET=TOP\n9,",
                "element 9 is not defined",
            ),
        ];
        for (from, to, what) in cases {
            assert!(EXPORT.contains(from), "{from}");
            let e = convert_text(&EXPORT.replacen(from, to, 1)).unwrap_err();
            assert!(e.to_string().contains(what), "{to}: {e}");
            assert!(e.to_string().starts_with("t.inp:"), "{e}");
        }
    }
}
