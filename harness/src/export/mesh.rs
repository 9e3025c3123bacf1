//! The deck's model data: heading and units, nodes, elements, materials and sections,
//! clamps, ties, and the contact interfaces with the shim's property table.

use std::collections::BTreeSet;
use std::fmt::Write;

use super::names::{face as face_label, Names};
use super::{num, ExportError};
use crate::capi::{props::encode, NPROPS};
use crate::fe::mesh::{Body, Face, Model};
use crate::fe::ties::find_ties;
use crate::input::deck::job::UNITS_COMMENT;
use crate::input::scene::Scene;
use crate::model::mesh_face;
use crate::model::{Problem, PAIR_TOL};

/// State variables per contact point the shim's UINTER needs (fortran-shim/README.md).
pub const DEPVAR: usize = 57;

/// Entries per data line of a set (Abaqus reads at most 16).
const PER_LINE: usize = 16;

/// The Abaqus label of a box face on a C3D8 element (the node order of
/// `Model::add_graded_box`): S1 z-min, S2 z-max, S3 y-min, S4 x-max, S5 y-max, S6 x-min.
pub fn s_label(f: Face) -> &'static str {
    match f {
        Face::ZMin => "S1",
        Face::ZMax => "S2",
        Face::YMin => "S3",
        Face::XMax => "S4",
        Face::YMax => "S5",
        Face::XMin => "S6",
    }
}

/// The elements of `body` on box face `f` (0-based ids), in the order of
/// `Body::face_quads`, with their corner nodes.
pub fn face_elements(model: &Model, body: &Body, f: Face) -> Vec<(usize, [usize; 4])> {
    let [nx, ny, nz] = body.spec.divisions;
    let axis = f.axis();
    let layer = if f.outward_normal()[axis] > 0.0 {
        body.spec.divisions[axis] - 1
    } else {
        0
    };
    let corners = f.element_corners();
    let mut out = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                if [i, j, k][axis] == layer {
                    let e = body.element(i, j, k);
                    out.push((e, corners.map(|c| model.elements[e].nodes[c])));
                }
            }
        }
    }
    out
}

/// Data lines of ids (1-based), [`PER_LINE`] per line.
pub fn id_lines(out: &mut String, ids: impl IntoIterator<Item = usize>) {
    let ids: Vec<String> = ids.into_iter().map(|i| (i + 1).to_string()).collect();
    for chunk in ids.chunks(PER_LINE) {
        let _ = writeln!(out, "{}", chunk.join(", "));
    }
}

/// An element-face surface `name` of (element, face) pairs.
fn surface(out: &mut String, name: &str, faces: &[(usize, Face)]) {
    let _ = writeln!(out, "*SURFACE, NAME={name}, TYPE=ELEMENT");
    for (e, f) in faces {
        let _ = writeln!(out, "{}, {}", e + 1, s_label(*f));
    }
}

/// Writes the model data of `scene` (its built `p`) to `out`.
pub fn write(
    out: &mut String,
    scene: &Scene,
    p: &Problem,
    names: &Names,
) -> Result<(), ExportError> {
    let s = &scene.spec;
    let m = &p.model;
    let u = &s.units;
    for (what, v) in [
        ("length", &u.length),
        ("force", &u.force),
        ("time", &u.time),
        ("mass", &u.mass),
    ] {
        if v.is_empty() || v.contains(char::is_whitespace) {
            return Err(ExportError::Unsupported {
                file: scene.file.clone(),
                key: format!("units.{what}"),
                message: format!("`{v}`: the deck's units comment takes one word per unit"),
            });
        }
    }
    let title = if s.title.is_empty() {
        &scene.file
    } else {
        &s.title
    };
    let _ = writeln!(out, "*HEADING\n{}", title.replace(['\n', '*'], " "));
    let _ = writeln!(
        out,
        "** Written by `jointlin export {}`: the scene's model, node for node.",
        scene.file
    );
    let _ = writeln!(
        out,
        "** {UNITS_COMMENT} length={} force={} time={} mass={}",
        u.length, u.force, u.time, u.mass
    );
    let _ = writeln!(out, "*NODE");
    for (i, x) in m.nodes.iter().enumerate() {
        let _ = writeln!(
            out,
            "{}, {}, {}, {}",
            i + 1,
            num(x[0]),
            num(x[1]),
            num(x[2])
        );
    }
    for (b, body) in m.bodies.iter().enumerate() {
        let _ = writeln!(out, "*ELEMENT, TYPE=C3D8I, ELSET={}", names.bodies[b]);
        for e in body.first_element..body.first_element + body.n_elements() {
            let nodes: Vec<String> = m.elements[e]
                .nodes
                .iter()
                .map(|n| (n + 1).to_string())
                .collect();
            let _ = writeln!(out, "{}, {}", e + 1, nodes.join(", "));
        }
    }
    let used: BTreeSet<&str> = s
        .bodies
        .iter()
        .filter_map(|b| b.material.as_deref())
        .collect();
    for (key, mat) in s
        .materials
        .iter()
        .filter(|(k, _)| used.contains(k.as_str()))
    {
        let _ = writeln!(out, "*MATERIAL, NAME={}", names.materials[key]);
        let _ = writeln!(out, "*ELASTIC\n{}, {}", num(mat.e), num(mat.nu));
        let _ = writeln!(out, "*DENSITY\n{}", num(mat.rho));
        if mat.rayleigh_alpha != 0.0 || mat.rayleigh_beta != 0.0 {
            let _ = writeln!(
                out,
                "*DAMPING, ALPHA={}, BETA={}",
                num(mat.rayleigh_alpha),
                num(mat.rayleigh_beta)
            );
        }
    }
    for (b, body) in s.bodies.iter().enumerate() {
        let mat = body
            .material
            .as_deref()
            .expect("validated: boxes have a material");
        let _ = writeln!(
            out,
            "*SOLID SECTION, ELSET={}, MATERIAL={}",
            names.bodies[b], names.materials[mat]
        );
    }
    // Clamps: zero displacement of a face's nodes in the clamped components.
    for c in &s.clamp {
        let b = body_index(scene, &c.body);
        let f = c.face.expect("validated: box clamps name a face");
        let set = format!("CLAMP_{}_{}", names.bodies[b], face_label(f));
        let _ = writeln!(out, "*NSET, NSET={set}");
        id_lines(out, m.bodies[b].face_nodes(mesh_face(f)));
        let _ = writeln!(out, "*BOUNDARY");
        if c.components == [true; 3] {
            let _ = writeln!(out, "{set}, 1, 3");
        } else {
            for (k, _) in c.components.iter().enumerate().filter(|(_, on)| **on) {
                let _ = writeln!(out, "{set}, {0}, {0}", k + 1);
            }
        }
    }
    ties(out, scene, m, names)?;
    interfaces(out, scene, m, names);
    Ok(())
}

/// Index of body `name` (every body is a box: `check`).
pub fn body_index(scene: &Scene, name: &str) -> usize {
    scene
        .spec
        .bodies
        .iter()
        .position(|b| b.name == name)
        .expect("validated: the body exists")
}

/// Each tie as a `*TIE` between the element faces of the two boxes whose corners are
/// all tied nodes (slave: the second box); every tied node must lie on such a face.
fn ties(out: &mut String, scene: &Scene, m: &Model, names: &Names) -> Result<(), ExportError> {
    for (i, t) in scene.spec.ties.iter().enumerate() {
        let [a, b] = [0, 1].map(|k| body_index(scene, &t.between[k]));
        let pairs =
            find_ties(m, a, b, PAIR_TOL).map_err(|source| crate::model::BuildError::Tie {
                a: t.between[0].clone(),
                b: t.between[1].clone(),
                source,
            })?;
        let mut sides = Vec::new();
        for (side, body) in [(0, a), (1, b)] {
            let tied: BTreeSet<usize> = pairs.iter().map(|p| p[side]).collect();
            let mut faces = Vec::new();
            let mut covered = BTreeSet::new();
            for f in Face::ALL {
                for (e, corners) in face_elements(m, &m.bodies[body], f) {
                    if corners.iter().all(|n| tied.contains(n)) {
                        faces.push((e, f));
                        covered.extend(corners);
                    }
                }
            }
            if covered != tied {
                return Err(ExportError::Unsupported {
                    file: scene.file.clone(),
                    key: format!("ties[{i}]"),
                    message: format!(
                        "{} and {} touch along an edge or a point as well as (or instead of) faces: a *TIE ties surfaces",
                        t.between[0], t.between[1]
                    ),
                });
            }
            sides.push(faces);
        }
        let name = format!("TIE_{}_{}", names.bodies[a], names.bodies[b]);
        surface(out, &format!("{name}_MASTER"), &sides[0]);
        surface(out, &format!("{name}_SLAVE"), &sides[1]);
        let _ = writeln!(
            out,
            "*TIE, NAME={name}, ADJUST=NO\n{name}_SLAVE, {name}_MASTER"
        );
    }
    Ok(())
}

/// Each interface: its surfaces (slave: the lower body's z-max element faces that carry
/// contact, as `fe::contact_pairs` takes them; master: the upper body's z-min faces),
/// its USER interaction with the shim's property table, its contact pair.
fn interfaces(out: &mut String, scene: &Scene, m: &Model, names: &Names) {
    for (i, f) in scene.spec.interfaces.iter().enumerate() {
        let [lo, hi] = [0, 1].map(|k| body_index(scene, &f.between[k]));
        let keep = |q: &[usize; 4]| {
            let c: [f64; 3] =
                std::array::from_fn(|a| q.iter().map(|&n| m.nodes[n][a]).sum::<f64>() / 4.0);
            !f.exclude.iter().any(|r| r.contains(c))
        };
        let slave: Vec<(usize, Face)> = face_elements(m, &m.bodies[lo], Face::ZMax)
            .into_iter()
            .filter(|(_, q)| keep(q))
            .map(|(e, _)| (e, Face::ZMax))
            .collect();
        let master: Vec<(usize, Face)> = face_elements(m, &m.bodies[hi], Face::ZMin)
            .into_iter()
            .map(|(e, _)| (e, Face::ZMin))
            .collect();
        let name = &names.interfaces[i];
        surface(out, &format!("{name}_SLAVE"), &slave);
        surface(out, &format!("{name}_MASTER"), &master);
        // The shim's PROPS (fortran-shim/README.md, src/ffi/props.rs).
        let p = encode(&f.contact_law()).map(num);
        let _ = writeln!(
            out,
            "*SURFACE INTERACTION, NAME={name}, USER, DEPVAR={DEPVAR}, PROPERTIES={NPROPS}\n1.,\n\
             ** law (0 Mindlin, 1 Jenkins), rule (0 thesis, 1 Masing), mu, k_T0 per area,\n\
             ** normal law (0 linear, 1 Hertz), k_N per area or E*, r*, k_T0 source (0: PROPS 4)\n\
             {}\n\
             ** G*, damping (0 DVISCOUS), quadrature (0 graded), points (0 default)\n\
             {}",
            p[..8].join(", "),
            p[8..].join(", ")
        );
        let _ = writeln!(
            out,
            "*CONTACT PAIR, INTERACTION={name}, TYPE=NODE TO SURFACE, SMALL SLIDING\n{name}_SLAVE, {name}_MASTER"
        );
    }
}
