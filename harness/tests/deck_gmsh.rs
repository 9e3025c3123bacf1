//! The bolted lap joint from Gmsh (examples/deck/): bolted-lap.inp includes
//! bolted-lap-mesh.inp, the mesh of bolted-lap.geo with its physical surfaces made
//! element-face surfaces (input::deck::gmsh). The deck reads; its plate-plate contact pair
//! pairs every node of the slave face (their number counted on the mesh, and equal to
//! Gmsh's node set of that physical surface); the head and nut ties pair every ring node;
//! the preload pressure on the bearing ring is the library's M8 preload at 20 N·m. A mesh
//! Gmsh writes now from the .geo converts (`jointlin deck from-gmsh`) and pairs the same way; a
//! facet that bounds no solid is refused with file:line. CalculiX's *FREQUENCY
//! on the tied variant (every interface *TIE; ccx has no USER interaction) gives the
//! README's first mode, 142.9 Hz, inside the deck's sweep, and `jointlin modes`
//! on the same deck gives CalculiX's six modes to 5e-6. The Gmsh and CalculiX parts fail on CI where the program is missing
//! and are skipped elsewhere (tests/tools/mod.rs).

mod common;
#[path = "../../tests/tools/mod.rs"]
mod tools;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use jointlin_harness::capi::screw_preload;
use jointlin_harness::fe::elements::face::MeshFace;
use jointlin_harness::fe::elements::ElementKind;
use jointlin_harness::input;
use jointlin_harness::input::deck::gmsh::deck_mesh_from_gmsh;
use jointlin_harness::input::deck::summary::summary;
use jointlin_harness::input::deck::{self, Deck, NodeTarget, Procedure, SurfaceKind};
use jointlin_harness::solve::modal_stuck::{stuck_modes, ModeCount};
use jointlin_harness::validate::ccx::{ccx_missing, run_frequencies};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/deck")
        .join(name)
}

fn temp_dir(what: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("jointlin-{what}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The faces of element surface `name`.
fn faces(d: &Deck, name: &str) -> Vec<MeshFace> {
    let SurfaceKind::Element(list) = &d.surfaces[name].kind else {
        panic!("{name} is not an element surface");
    };
    list.iter()
        .map(|&(id, s)| {
            let ei = d.element_index[&id];
            let e = &d.elements[ei];
            let conn: Vec<usize> = e.nodes.iter().map(|n| d.node_index[n]).collect();
            MeshFace::new(e.kind, ei, &conn, s).unwrap()
        })
        .collect()
}

/// The distinct nodes of element surface `name`.
fn surface_nodes(d: &Deck, name: &str) -> BTreeSet<usize> {
    faces(d, name).into_iter().flat_map(|f| f.nodes).collect()
}

/// Area of element surface `name` (mm²).
fn surface_area(d: &Deck, name: &str) -> f64 {
    let x: Vec<[f64; 3]> = d.nodes.iter().map(|n| n.x).collect();
    faces(d, name).iter().map(|f| f.area(&x)).sum()
}

/// The number in the summary line that starts with `head` and ends with `tail`.
fn count(summary: &str, head: &str, tail: &str) -> usize {
    let line = summary
        .lines()
        .find(|l| l.trim_start().starts_with(head))
        .unwrap_or_else(|| panic!("no line {head:?} in\n{summary}"));
    line.rsplit_once(": ")
        .and_then(|(_, n)| n.strip_suffix(tail))
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{line:?}"))
}

/// The mesh and the pairing `jointlin check` prints: every slave node of the contact
/// pair and of both ties is paired, none left over.
fn check_lap(d: &Deck, file: &str) {
    assert_eq!(
        d.element_counts().keys().copied().collect::<Vec<_>>(),
        vec![ElementKind::C3D10]
    );
    let parts: usize = ["LOWER", "UPPER", "BOLT"]
        .iter()
        .map(|s| d.element_sets[*s].len())
        .sum();
    assert_eq!(parts, d.elements.len());
    assert_eq!(d.sections.len(), 3);
    let s = summary(d, file, "1/time").unwrap();
    eprintln!("{s}");
    assert!(!s.contains("warning"), "{s}");
    let slave = surface_nodes(d, "LAP_UPPER").len();
    assert_eq!(slave, d.node_sets["LAP_UPPER"].len());
    assert!(slave > 100, "{slave}");
    let points = count(
        &s,
        "contact pair LAP_UPPER / LAP_LOWER (LAP)",
        " contact points",
    );
    assert_eq!(points, slave);
    for (tie, ring) in [("HEAD", "RING_UPPER"), ("NUT", "RING_LOWER")] {
        let tied = count(&s, &format!("tie {tie} "), " tied nodes");
        assert_eq!(tied, surface_nodes(d, ring).len(), "{tie}");
        assert_eq!(tied, d.node_sets[ring].len(), "{tie}");
    }
}

#[test]
fn shipped_deck_pairs_every_slave_node() {
    let (d, warnings) = deck::read(&example("bolted-lap.inp")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    check_lap(&d, "bolted-lap.inp");
    let lap = &d.interactions["LAP"];
    assert!(lap.user);
    assert_eq!(lap.properties.len(), 12);
    // Mindlin, thesis rule, mu = 0.15, linear normal law (fortran-shim/README.md).
    assert_eq!(lap.properties[..3], [0.0, 0.0, 0.15]);
    assert_eq!(lap.properties[4], 0.0);
    let steps: Vec<(bool, &str)> = d
        .steps
        .iter()
        .map(|s| {
            let what = match s.procedure {
                Procedure::Static => "static",
                Procedure::Frequency { .. } => "frequency",
                Procedure::SteadyState { .. } => "steady state",
            };
            (s.perturbation, what)
        })
        .collect();
    assert_eq!(
        steps,
        [
            (false, "static"),
            (true, "frequency"),
            (true, "steady state")
        ]
    );
    let sweep = &d.steps[2];
    assert_eq!(sweep.cloads.len(), 1);
    assert_eq!(sweep.cloads[0].target, NodeTarget::Set("TIP".into()));
    assert_eq!(sweep.outputs[0].node_set, "TIP");
    // TIP is one node on the free end face (the largest x of the model).
    let tip = &d.node_sets["TIP"];
    assert_eq!(tip.len(), 1);
    let x_max = d.nodes.iter().map(|n| n.x[0]).fold(f64::MIN, f64::max);
    assert_eq!(d.node(tip[0]).unwrap()[0], x_max);
}

#[test]
fn preload_pressure_is_the_m8_preload_at_20_newton_metres() {
    let (d, _) = deck::read(&example("bolted-lap.inp")).unwrap();
    // M8: P = 1.25 mm, d2 = 7.188 mm, mu_G = mu_K = 0.12, D_Km = (11.6 + 9)/2 mm.
    let f = screw_preload(20_000.0, 1.25, 7.188, 0.12, 0.12, 10.3).unwrap();
    let loads = &d.steps[0].dsloads;
    assert_eq!(loads.len(), 2);
    for l in loads {
        let force = l.pressure * surface_area(&d, &l.surface);
        // The pressure is set for the rings' faceted area (16-gon edges): to its 5 digits.
        assert!(
            (force / f - 1.0).abs() < 1e-4,
            "{}: {force} N vs {f} N",
            l.surface
        );
    }
}

#[test]
fn fresh_gmsh_mesh_converts_and_pairs() {
    let dir = temp_dir("gmsh");
    let export = dir.join("bolted-lap-gmsh.inp");
    let run = Command::new("gmsh")
        .args(["-3", "-format", "inp", "-o"])
        .arg(&export)
        .arg(example("bolted-lap.geo"))
        .output();
    match run {
        Err(e) => {
            tools::missing("deck_gmsh", "gmsh", &e.to_string());
            return;
        }
        Ok(o) => assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr)),
    }
    // The command a user runs (the .geo's header): `jointlin deck from-gmsh`.
    let mesh = dir.join("bolted-lap-mesh.inp");
    let log = common::run_ok(&[
        "deck".as_ref(),
        "from-gmsh".as_ref(),
        export.as_os_str(),
        "--out".as_ref(),
        mesh.as_os_str(),
    ]);
    assert!(log.contains("surfaces)"), "{log}");
    assert_eq!(
        std::fs::read_to_string(&mesh).unwrap(),
        deck_mesh_from_gmsh(&export).unwrap()
    );
    std::fs::copy(example("bolted-lap.inp"), dir.join("bolted-lap.inp")).unwrap();
    let (d, warnings) = deck::read(&dir.join("bolted-lap.inp")).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    check_lap(&d, "fresh bolted-lap.inp");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A facet of a physical surface that is no face of a solid element: `jointlin deck
/// from-gmsh` names the export's file and line, exits 2 and writes nothing.
#[test]
fn from_gmsh_refuses_a_facet_that_bounds_no_solid() {
    let dir = temp_dir("gmsh-bad");
    let export = dir.join("bad-gmsh.inp");
    std::fs::write(
        &export,
        "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 1, 1, 1\n\
         *ELEMENT, type=C3D4, ELSET=Volume1\n1, 1, 2, 3, 4\n\
         *ELEMENT, type=CPS3, ELSET=Surface1\n2, 2, 3, 5\n\
         *ELSET, ELSET=TOP\n2\n",
    )
    .unwrap();
    let out = dir.join("mesh.inp");
    let run = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["deck", "from-gmsh"])
        .arg(&export)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{log}");
    assert!(log.contains("bad-gmsh.inp:"), "{log}");
    assert!(!out.exists(), "nothing written");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The deck with every interface tied, for CalculiX: the USER interaction dropped, the
/// contact pair a *TIE, the steps replaced by one *FREQUENCY step of `modes` modes.
fn tied_variant(deck: &str, modes: usize) -> String {
    let mut out = String::new();
    let mut interaction = false;
    for line in deck.lines() {
        let upper = line.trim_start().to_ascii_uppercase();
        if upper.starts_with('*') && !upper.starts_with("**") {
            if upper.starts_with("*STEP") {
                break;
            }
            interaction = upper.starts_with("*SURFACE INTERACTION");
        }
        if interaction {
            continue;
        }
        if upper.starts_with("*CONTACT PAIR") {
            out.push_str("*TIE, NAME=LAP\n");
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    out.push_str(&format!("*STEP\n*FREQUENCY\n{modes}\n*END STEP\n"));
    out
}

#[test]
fn calculix_modes_of_the_tied_variant_are_the_readmes_and_the_sweep_covers_the_first() {
    if let Some(why) = ccx_missing() {
        tools::missing("deck_gmsh_ccx", "ccx", &why);
        return;
    }
    let text = std::fs::read_to_string(example("bolted-lap.inp")).unwrap();
    let dir = temp_dir("lap-ccx");
    std::fs::copy(
        example("bolted-lap-mesh.inp"),
        dir.join("bolted-lap-mesh.inp"),
    )
    .unwrap();
    let variant = tied_variant(&text, 6);
    // Our reader takes the variant too: the contact pair became the third tie.
    std::fs::write(dir.join("check.inp"), &variant).unwrap();
    let (d, _) = deck::read(&dir.join("check.inp")).unwrap();
    assert_eq!((d.ties.len(), d.contact_pairs.len()), (3, 0));
    let f = run_frequencies(&variant, &dir, "tied").unwrap();
    eprintln!("tied bolted lap, ccx modes (Hz): {f:.1?}");
    assert_eq!(f.len(), 6);
    assert!(f.iter().all(|v| v.is_finite() && *v > 0.0), "{f:?}");
    assert!(f.windows(2).all(|w| w[0] <= w[1]), "{f:?}");
    // The README's number, at its printed precision.
    assert!(
        (f[0] - 142.9).abs() < 0.05,
        "first mode {} Hz, README 142.9",
        f[0]
    );
    // jointlin's shift-invert Lanczos on the same deck (penalty ties against ccx's
    // MPCs): every mode to 5e-6 (measured 2.2e-6 at the fifth, 7e-7 at the first).
    let scene = input::load(&dir.join("check.inp")).unwrap().into_scene();
    let ours = stuck_modes(&scene, ModeCount::Exactly(6))
        .unwrap()
        .band
        .modes
        .frequencies_hz();
    eprintln!("jointlin modes (Hz): {ours:.4?}");
    for (a, b) in ours.iter().zip(&f) {
        assert!(((a - b) / b).abs() < 5e-6, "jointlin {ours:?} vs ccx {f:?}");
    }
    let (shipped, _) = deck::read(&example("bolted-lap.inp")).unwrap();
    let Procedure::SteadyState { ranges, .. } = &shipped.steps[2].procedure else {
        panic!("step 3 is not the sweep");
    };
    let (f_low, f_high) = (ranges[0].f_low, ranges[0].f_high);
    assert!(
        f_low < f[0] && f[0] < f_high,
        "{f_low}…{f_high} vs {}",
        f[0]
    );
    assert!(f[1] > f_high, "{f:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A rectangle 10 × 4 mm triangulated by Gmsh and extruded 3 mm in 3 layers: wedges, with
/// the bottom and top (triangles) and the front y = 0 (quadrilaterals) as physical
/// surfaces.
const WEDGE_GEO: &str = "\
Point(1) = {0, 0, 0, 2.5};
Point(2) = {10, 0, 0, 2.5};
Point(3) = {10, 4, 0, 2.5};
Point(4) = {0, 4, 0, 2.5};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 3} { Surface{1}; Layers{3}; Recombine; };
Physical Surface(\"BOTTOM\") = {1};
Physical Surface(\"TOP\") = {out[0]};
Physical Surface(\"FRONT\") = {out[2]};
Physical Volume(\"SOLID\") = {out[1]};
";

/// Gmsh's wedge meshes (C3D6, and C3D15 with Mesh.SecondOrderIncomplete) convert; each
/// surface keeps its faces' shapes (triangles on the ends, quadrilaterals on the sides):
/// areas and volume are the geometry's. Gmsh's 18-node prism (written as C3D6) is
/// refused at its line instead of being read as several elements.
#[test]
fn gmsh_wedges_convert_with_triangle_and_quadrilateral_faces() {
    let dir = temp_dir("gmsh-wedge");
    let geo = dir.join("wedge.geo");
    std::fs::write(&geo, WEDGE_GEO).unwrap();
    // Without its physical surfaces (their 9-node quadrilaterals are refused first).
    let solid_only: String = WEDGE_GEO
        .lines()
        .filter(|l| !l.starts_with("Physical Surface"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.join("solid.geo"), solid_only).unwrap();
    let export = |name: &str, args: &[&str], geo: &Path| {
        let path = dir.join(name);
        let run = Command::new("gmsh")
            .args(["-3", "-format", "inp", "-o"])
            .arg(&path)
            .args(args)
            .arg(geo)
            .output();
        match run {
            Err(e) => {
                tools::missing("deck_gmsh_wedges", "gmsh", &e.to_string());
                None
            }
            Ok(o) => {
                assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
                Some(path)
            }
        }
    };
    let cases = [
        ("linear.inp", vec![], "C3D6"),
        (
            "quadratic.inp",
            vec![
                "-order",
                "2",
                "-setnumber",
                "Mesh.SecondOrderIncomplete",
                "1",
            ],
            "C3D15",
        ),
    ];
    for (name, args, kind) in cases {
        let Some(path) = export(name, &args, &geo) else {
            return;
        };
        let mesh = format!("mesh-{name}");
        std::fs::write(dir.join(&mesh), deck_mesh_from_gmsh(&path).unwrap()).unwrap();
        let main = dir.join(format!("main-{name}"));
        std::fs::write(
            &main,
            format!(
                "*INCLUDE, INPUT={mesh}\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n\
                 *DENSITY\n7.85e-9\n*SOLID SECTION, ELSET=Volume1, MATERIAL=STEEL\n"
            ),
        )
        .unwrap();
        let (d, _) = deck::read(&main).unwrap();
        assert!(d.elements.iter().all(|e| e.kind.name() == kind), "{name}");
        let x: Vec<[f64; 3]> = d.nodes.iter().map(|n| n.x).collect();
        let volume: f64 = d
            .elements
            .iter()
            .map(|e| {
                let ex: Vec<[f64; 3]> = e.nodes.iter().map(|n| x[d.node_index[n]]).collect();
                e.kind.element().volume(&ex).unwrap()
            })
            .sum();
        approx::assert_relative_eq!(volume, 120.0, max_relative = 1e-12);
        for (surface, area) in [("BOTTOM", 40.0), ("TOP", 40.0), ("FRONT", 30.0)] {
            let got = surface_area(&d, surface);
            approx::assert_relative_eq!(got, area, max_relative = 1e-12);
        }
    }
    // The full second order: 18-node prisms, written with TYPE=C3D6.
    let Some(path) = export("full.inp", &["-order", "2"], &dir.join("solid.geo")) else {
        return;
    };
    let err = deck_mesh_from_gmsh(&path).unwrap_err().to_string();
    assert!(
        err.contains("full.inp:") && err.contains("more than the 6 nodes"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
