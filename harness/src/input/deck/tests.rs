//! Reader tests: every keyword of a flat and of a part/instance deck, the number and
//! line syntax, named errors with file:line, and random corruption (never a panic).

use std::path::Path;

use super::*;
use crate::fe::elements::ElementKind;
use crate::util::rng::Rng;

/// A flat deck using every supported keyword, in mixed case, with comments, a
/// continued keyword line and Abaqus number forms.
pub(super) const FLAT: &str = "\
*Heading
 two bricks
** a comment
*node, nset=ALLN
1, 0., 0., 0.
2, 1.E1, 0, 0
3, 10, 1.0e1, 0
4, 0, 10, 0
5, 0, 0, 2.d1
6, 10, 0, 20
7, 10, 10, 20
8, 0, 10, 20
*Element, type=C3D8, elset=BRICK
1, 1, 2, 3, 4, 5, 6, 7, 8
*Nset, nset=BOTTOM
1, 2, 3, 4
*Nset, nset=TOPN, generate
5, 8, 1
*Elset, elset=ALL
BRICK
*Surface, type=ELEMENT, name=TOP
BRICK, S2
*Surface, name=BASE
1, S1
*Material, name=Steel
*Elastic
2.1d5, 0.3
*Density
7.85E-9
*Damping, alpha=0.5, beta=1.e-6
*Solid Section, elset=ALL,
 material=STEEL
,
*Surface Interaction, name=JOINT, user, properties=8,
 depvar=57
1.,
0, 0, 0.6, 1.e4, 0, 1.e5, 0, 0
*Contact Pair, interaction=JOINT, small sliding
TOP, BASE
*Tie, name=GLUE, position tolerance=0.1
TOP, BASE
*Boundary
BOTTOM, ENCASTRE
1, 1, 3
*Step, name=preload
*Static
*Dsload
TOP, P, 2.5
*End Step
*Step, name=modes, perturbation
*Frequency
6
*End Step
*Step, name=sweep, perturbation
*Steady State Dynamics, direct, frequency scale=linear
100., 2.e3, 41, 1.
*Cload
TOPN, 3, 1.5
*Dload
1, P2, 3.
*Output, field
*Node Output, nset=TOPN
U
*Element Output
S
*End Step
";

fn read_text(text: &str) -> Result<(Deck, Vec<DeckWarning>), DeckError> {
    read_str(text, "test.inp", Path::new("."))
}

#[test]
fn flat_deck_reads_every_keyword() {
    let (d, warnings) = read_text(FLAT).unwrap();
    assert_eq!(d.heading.trim(), "two bricks");
    assert_eq!(d.nodes.len(), 8);
    assert_eq!(d.node(2), Some([10.0, 0.0, 0.0]));
    assert_eq!(d.node(5), Some([0.0, 0.0, 20.0]));
    assert_eq!(d.elements[0].kind, ElementKind::C3D8);
    assert_eq!(d.node_sets["TOPN"], vec![5, 6, 7, 8]);
    assert_eq!(d.node_sets["ALLN"].len(), 8);
    assert_eq!(d.element_sets["ALL"], vec![1]);
    assert_eq!(d.surfaces["TOP"].kind, SurfaceKind::Element(vec![(1, 1)]));
    let m = &d.materials["STEEL"];
    assert_eq!(m.elastic, Some((2.1e5, 0.3)));
    assert_eq!(m.density, Some(7.85e-9));
    assert_eq!(m.damping, Some((0.5, 1e-6)));
    assert_eq!(d.sections[0].material, "STEEL");
    let it = &d.interactions["JOINT"];
    assert!(it.user);
    assert_eq!(it.depvar, 57);
    assert_eq!(it.thickness, Some(1.0));
    assert_eq!(it.properties, vec![0.0, 0.0, 0.6, 1e4, 0.0, 1e5, 0.0, 0.0]);
    assert_eq!(d.contact_pairs[0].slave, "TOP");
    assert!(d.contact_pairs[0].small_sliding);
    assert_eq!(d.ties[0].position_tolerance, Some(0.1));
    // ENCASTRE → DOFs 1…6, then node 1 DOFs 1…3.
    assert_eq!(d.boundaries.len(), 2);
    assert_eq!((d.boundaries[0].first, d.boundaries[0].last), (1, 6));
    assert_eq!(d.boundaries[1].target, NodeTarget::Node(1));
    assert_eq!(d.steps.len(), 3);
    assert_eq!(d.steps[0].procedure, Procedure::Static);
    assert_eq!(d.steps[0].dsloads[0].pressure, 2.5);
    assert_eq!(d.steps[1].procedure, Procedure::Frequency { modes: 6 });
    assert!(d.steps[1].perturbation);
    let sweep = &d.steps[2];
    assert_eq!(
        sweep.procedure,
        Procedure::SteadyState {
            ranges: vec![FrequencyRange {
                f_low: 100.0,
                f_high: 2000.0,
                points: 41,
                bias: 1.0,
            }],
            scale: FrequencyScale::Linear,
            direct: true,
            eigen_intervals: false,
        }
    );
    assert_eq!(sweep.cloads[0].target, NodeTarget::Set("TOPN".into()));
    assert_eq!(sweep.dloads[0].face, 1);
    assert_eq!(sweep.outputs[0].node_set, "TOPN");
    // *ELEMENT OUTPUT is ignored with a warning naming its line.
    assert_eq!(warnings.len(), 1);
    let line = FLAT.lines().position(|l| l == "*Element Output").unwrap() + 1;
    assert!(
        warnings[0]
            .to_string()
            .starts_with(&format!("test.inp:{line}: *ELEMENT OUTPUT:")),
        "{}",
        warnings[0]
    );
}

#[test]
fn part_instances_are_translated_prefixed_and_offset() {
    let deck = "\
*Part, name=Plate
*Node
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
*Element, type=C3D8I, elset=ALL
1, 1, 2, 3, 4, 5, 6, 7, 8
*Surface, name=UP
ALL, S2
*Surface, name=DOWN
ALL, S1
*Solid Section, elset=ALL, material=M
*End Part
*Assembly, name=A
*Instance, name=Lower, part=Plate
*End Instance
*Instance, name=Upper, part=Plate
0., 0., 1.
*End Instance
*Nset, nset=PICK
Upper.5, Lower.1
*Nset, nset=LOCAL, instance=Upper
8
*End Assembly
*Material, name=M
*Elastic
1000., 0.25
*Tie, name=T
Upper.DOWN, Lower.UP
";
    let (d, _) = read_text(deck).unwrap();
    assert_eq!(d.nodes.len(), 16);
    assert_eq!(d.elements.len(), 2);
    // Upper's ids are offset past Lower's (8 → 10) and its nodes moved up by 1.
    assert_eq!(d.node(15), Some([0.0, 0.0, 2.0]));
    assert_eq!(d.node_sets["PICK"], vec![15, 1]);
    assert_eq!(d.node_sets["LOCAL"], vec![18]);
    assert_eq!(d.element_sets["UPPER.ALL"], vec![11]);
    assert_eq!(d.sections.len(), 2);
    assert_eq!(d.ties[0].slave, "UPPER.DOWN");
    // The upper instance's bottom lies on the lower's top: 4 tied nodes.
    let s = summary::summary(&d, "test.inp", "1/time").unwrap();
    assert!(
        s.contains("tie T (UPPER.DOWN / LOWER.UP): 4 tied nodes"),
        "{s}"
    );
    assert!(
        s.contains("16 nodes (48 DOFs), 2 elements (2 C3D8I)"),
        "{s}"
    );
}

#[test]
fn contact_surfaces_that_do_not_overlap_are_an_error() {
    // FLAT pairs the brick's top with its own bottom, 20 length units apart.
    let (d, _) = read_text(FLAT).unwrap();
    let e = summary::summary(&d, "test.inp", "1/time").unwrap_err();
    assert_eq!(e.kind, DeckErrorKind::BadValue);
    assert!(
        e.to_string()
            .starts_with("test.inp:39: *CONTACT PAIR: slave TOP and master BASE do not overlap"),
        "{e}"
    );
}

#[test]
fn includes_are_followed_relative_to_the_including_file() {
    let dir = std::env::temp_dir().join(format!("jointlin-deck-include-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("mesh")).unwrap();
    let (head, tail) = FLAT.split_at(FLAT.find("*Element").unwrap());
    std::fs::write(dir.join("mesh/elements.inp"), tail).unwrap();
    std::fs::write(
        dir.join("main.inp"),
        format!("{head}*INCLUDE, INPUT=mesh/elements.inp\n"),
    )
    .unwrap();
    let (d, _) = read(&dir.join("main.inp")).unwrap();
    assert_eq!(d.steps.len(), 3);
    // A file including itself ends with a named error, not a hang.
    std::fs::write(dir.join("loop.inp"), "*include, input=loop.inp\n").unwrap();
    let e = read(&dir.join("loop.inp")).unwrap_err();
    assert_eq!(e.kind, DeckErrorKind::BadValue);
    let e = read(&dir.join("missing.inp")).unwrap_err();
    assert_eq!(e.kind, DeckErrorKind::Io);
    let _ = std::fs::remove_dir_all(&dir);
}

/// (replace, by, expected kind, expected "file:line: *KEYWORD" start of the message); the
/// line is the data line at fault, or the keyword line for a parameter or missing data.
const BAD: &[(&str, &str, DeckErrorKind, &str)] = &[
    (
        "*Static\n",
        "*Statik\n",
        DeckErrorKind::UnknownKeyword,
        "test.inp:46: *STATIK",
    ),
    (
        "type=C3D8,",
        "type=C3D8R,",
        DeckErrorKind::Unsupported,
        "test.inp:13: *ELEMENT",
    ),
    (
        "4, 0, 10, 0\n",
        "3, 0, 10, 0\n",
        DeckErrorKind::Duplicate,
        "test.inp:8: *NODE",
    ),
    (
        "BRICK, S2",
        "BRICK, S7",
        DeckErrorKind::BadValue,
        "test.inp:22: *SURFACE",
    ),
    (
        "1, S1\n",
        "2, S1\n",
        DeckErrorKind::Undefined,
        "test.inp:24: *SURFACE",
    ),
    (
        "material=STEEL",
        "material=IRON",
        DeckErrorKind::Undefined,
        "test.inp:31: *SOLID SECTION",
    ),
    (
        "2.1d5, 0.3",
        "2.1d5, 0.5",
        DeckErrorKind::BadValue,
        "test.inp:27: *ELASTIC",
    ),
    (
        "7.85E-9",
        "7.85F-9",
        DeckErrorKind::Syntax,
        "test.inp:29: *DENSITY",
    ),
    (
        "TOP, BASE\n*Tie",
        "TOP, BOTTOM\n*Tie",
        DeckErrorKind::Undefined,
        "test.inp:39: *CONTACT PAIR",
    ),
    (
        "interaction=JOINT",
        "interaction=OTHER",
        DeckErrorKind::Undefined,
        // Each pair is at its data line (the slave, master line).
        "test.inp:39: *CONTACT PAIR",
    ),
    (
        "BOTTOM, ENCASTRE",
        "BOTTOM, 7",
        DeckErrorKind::BadValue,
        "test.inp:43: *BOUNDARY",
    ),
    (
        "1, 2, 3, 4, 5, 6, 7, 8\n",
        "1, 2, 3, 4, 5, 6, 7, 9\n",
        DeckErrorKind::Undefined,
        "test.inp:14: *ELEMENT",
    ),
    (
        "1, 2, 3, 4, 5, 6, 7, 8\n",
        "1, 2, 3, 4, 5, 6, 7\n",
        DeckErrorKind::Syntax,
        "test.inp:14: *ELEMENT",
    ),
    (
        "1, 2, 3, 4, 5, 6, 7, 8\n",
        "1, 2, 3, 4, 5, 6, 7, 8, 8\n",
        DeckErrorKind::Syntax,
        "test.inp:14: *ELEMENT",
    ),
    (
        "1, 2, 3, 4, 5, 6, 7, 8\n",
        "5, 6, 7, 8, 1, 2, 3, 4\n",
        DeckErrorKind::BadValue,
        "test.inp:14: *ELEMENT",
    ),
    (
        "0, 0, 0.6, 1.e4, 0, 1.e5, 0, 0",
        "0, 0, 0.6, 1.e4, 0, 1.e5, 0",
        DeckErrorKind::BadValue,
        "test.inp:34: *SURFACE INTERACTION",
    ),
    (
        "*Frequency\n6",
        "*Frequency\n-6",
        DeckErrorKind::BadValue,
        "test.inp:52: *FREQUENCY",
    ),
    (
        "100., 2.e3, 41, 1.",
        "100., 2.e1, 41, 1.",
        DeckErrorKind::BadValue,
        "test.inp:56: *STEADY STATE DYNAMICS",
    ),
    (
        "*End Step\n*Step, name=modes",
        "*Step, name=modes",
        DeckErrorKind::Syntax,
        "test.inp:49: *STEP",
    ),
    (
        "TOPN, 3, 1.5",
        "TOPX, 3, 1.5",
        DeckErrorKind::Undefined,
        "test.inp:58: *CLOAD",
    ),
    (
        "1, P2, 3.",
        "1, P9, 3.",
        DeckErrorKind::Unsupported,
        "test.inp:60: *DLOAD",
    ),
    (
        "5, 8, 1\n",
        "5, 9, 1\n",
        DeckErrorKind::Undefined,
        "test.inp:18: *NSET",
    ),
    (
        "*Density\n7.85E-9\n",
        "",
        DeckErrorKind::BadValue,
        "test.inp:25: *MATERIAL",
    ),
];

#[test]
fn bad_decks_give_named_errors_at_their_line() {
    for (from, to, kind, start) in BAD {
        assert!(FLAT.contains(from), "{from}");
        let text = FLAT.replacen(from, to, 1);
        let e = read_text(&text).expect_err(from);
        assert_eq!(e.kind, *kind, "{from} → {to}: {e}");
        assert!(
            e.to_string().starts_with(start),
            "{from} → {to}: got {e}, want {start}"
        );
    }
}

#[test]
fn random_corruption_gives_errors_not_panics() {
    // Random byte edits (replace, delete, insert, duplicate a line, truncate) of the
    // flat deck: each read ends in Ok or a DeckError, never a panic.
    let mut rng = Rng::new(2026);
    let alphabet = b"*,.=-+0123456789eEdDSPCsx \n\t\r";
    let (mut ok, mut err) = (0, 0);
    for _ in 0..3000 {
        let mut b = FLAT.as_bytes().to_vec();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(b.len());
            match rng.below(5) {
                0 => b[at] = alphabet[rng.below(alphabet.len())],
                1 => {
                    b.remove(at);
                }
                2 => b.insert(at, alphabet[rng.below(alphabet.len())]),
                3 => {
                    let end = at + rng.below(40).min(b.len() - at);
                    let copy = b[at..end].to_vec();
                    b.splice(at..at, copy);
                }
                _ => b.truncate(at),
            }
        }
        let text = String::from_utf8_lossy(&b);
        match read_text(&text) {
            Ok(_) => ok += 1,
            Err(e) => {
                assert!(e.to_string().starts_with("test.inp:"), "{e}");
                err += 1;
            }
        }
    }
    eprintln!("corrupted decks: {ok} read, {err} named errors");
    assert!(err > 100 && ok > 100);
}

#[test]
fn decks_written_for_ccx_read_back_for_every_element_type() {
    // C3D20 connectivities continue on a second line (16 entries per line at most).
    use crate::fe::elements::box_mesh::box_mesh;
    use crate::fe::mesh::Material;
    let mat = Material::new(210_000.0, 0.3, 7.85e-9).unwrap();
    for kind in ElementKind::ALL {
        let mesh = box_mesh(kind, [4.0, 1.0, 1.0], [2, 1, 1], 0.0, 1);
        let text = crate::validate::ccx::frequency_deck(&mesh, &mat, &[0, 1], 4);
        let (d, _) = read_text(&text).unwrap();
        assert_eq!(d.elements.len(), mesh.elements.len(), "{kind}");
        for (e, conn) in d.elements.iter().zip(&mesh.elements) {
            assert_eq!(e.kind, kind);
            let ids: Vec<u64> = conn.iter().map(|&n| n as u64 + 1).collect();
            assert_eq!(e.nodes, ids);
        }
        for (n, p) in d.nodes.iter().zip(&mesh.nodes) {
            assert_eq!(n.x, *p);
        }
        assert_eq!(d.steps[0].procedure, Procedure::Frequency { modes: 4 });
        assert_eq!(d.node_sets["FIXED"], vec![1, 2]);
    }
}

/// `*STEADY STATE DYNAMICS` data lines as Abaqus reads them (an upper limit of zero or
/// blank: one frequency; fewer than 2 points: 20), here from an `*INCLUDE`d file of
/// data lines that continues the step's card; a contact pair of another TYPE than node
/// to surface is refused.
#[test]
fn frequency_lines_single_frequencies_and_included_data_lines() {
    let dir = std::env::temp_dir().join(format!("jointlin-deck-frq-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("sweep.frq"), "150.,\n175., 0.\n200., 300., 1\n").unwrap();
    let main = FLAT.replace(
        "100., 2.e3, 41, 1.\n",
        "100., 2.e3, 41, 1.\n*INCLUDE, INPUT=sweep.frq\n",
    );
    assert_ne!(main, FLAT);
    std::fs::write(dir.join("main.inp"), &main).unwrap();
    let (d, _) = read(&dir.join("main.inp")).unwrap();
    let Procedure::SteadyState { ranges, .. } = &d.steps[2].procedure else {
        panic!("step 3 is the sweep");
    };
    let got: Vec<(f64, f64, usize)> = ranges
        .iter()
        .map(|r| (r.f_low, r.f_high, r.points))
        .collect();
    assert_eq!(
        got,
        [
            (100.0, 2000.0, 41),
            (150.0, 150.0, 1),
            (175.0, 175.0, 1),
            (200.0, 300.0, 20)
        ]
    );
    // The step's loads after the include still belong to it.
    assert_eq!(d.steps[2].cloads.len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
    let e = read_text(&FLAT.replace(
        "*Contact Pair, interaction=JOINT, small sliding",
        "*Contact Pair, interaction=JOINT, type=surface to surface",
    ))
    .unwrap_err();
    assert_eq!(e.kind, DeckErrorKind::Unsupported);
    assert!(e.message.starts_with("TYPE=surface to surface"), "{e}");
}
