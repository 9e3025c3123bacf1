//! The deck's history data: step 1 `*STATIC` with the preload (pressures as `*DSLOAD`
//! on the face, point forces and screws as `*CLOAD`), step 2
//! `*STEADY STATE DYNAMICS, DIRECT` with the frequency list and the harmonic loads as
//! `*CLOAD` (face tractions as the consistent nodal forces the scene applies; a phase φ
//! as the real part F cos φ and a `*CLOAD, IMAGINARY` part F sin φ, so that the load acts
//! as F cos(ωt + φ)), node output of every `[[outputs]]` node (U: real and imaginary
//! parts per frequency).

use std::fmt::Write;

use nalgebra::{Complex, Vector3};

use super::mesh::{body_index, id_lines};
use super::names::{face as face_label, Names};
use super::{num, FREQUENCY_FILE};
use crate::fe::mesh::Model;
use crate::fe::surface::nodal_areas;
use crate::input::scene::{ExcitationKind, PreloadKind, Scene};
use crate::model::mesh_face;
use crate::model::Problem;

/// The frequency list: one data line per frequency (1/time), the upper limit left
/// blank (Abaqus: a single frequency).
pub fn frequency_lines(scene: &Scene) -> String {
    scene
        .frequencies()
        .iter()
        .map(|f| format!("{},\n", num(*f)))
        .collect()
}

/// The node of body `b` nearest `at` (as `model::build` takes it).
fn nearest(m: &Model, b: usize, at: [f64; 3]) -> usize {
    let body = m.bodies[b];
    (body.first_node..body.first_node + body.n_nodes())
        .min_by(|&x, &y| {
            let d = |n: usize| (0..3).map(|c| (m.nodes[n][c] - at[c]).powi(2)).sum::<f64>();
            d(x).total_cmp(&d(y))
        })
        .expect("a box has nodes")
}

/// `*CLOAD` lines of force `f` (global components) at node `n`; zero components left out.
fn cload(out: &mut String, n: usize, f: [f64; 3]) {
    for (c, v) in f.iter().enumerate().filter(|(_, v)| **v != 0.0) {
        let _ = writeln!(out, "{}, {}, {}", n + 1, c + 1, num(*v));
    }
}

fn unit(v: [f64; 3]) -> Vector3<f64> {
    Vector3::from(v).normalize()
}

/// Writes both steps of `scene` (its built `p`) to `out`.
pub fn write(out: &mut String, scene: &Scene, p: &Problem, names: &Names) {
    let s = &scene.spec;
    let m = &p.model;
    let _ = writeln!(out, "**\n** Step 1: the preload (UINTER with LINPER = 0).");
    let _ = writeln!(out, "*STEP, NAME=PRELOAD\n*STATIC");
    for l in &s.preload {
        let b = body_index(scene, &l.body);
        match l.kind {
            PreloadKind::Pressure => {
                let f = l.face.expect("validated");
                let name = format!("PRESSURE_{}_{}", names.bodies[b], face_label(f));
                // The surface is model data (`surfaces`).
                let _ = writeln!(
                    out,
                    "*DSLOAD\n{name}, P, {}",
                    num(l.pressure.expect("validated"))
                );
            }
            PreloadKind::Force => {
                let n = nearest(m, b, l.at.unwrap_or(m.nodes[m.bodies[b].first_node]));
                let _ = writeln!(out, "*CLOAD");
                cload(out, n, l.force.expect("validated"));
            }
        }
    }
    for (sc, built) in s.screws.iter().zip(&p.screws) {
        let d = unit(sc.direction);
        let _ = writeln!(
            out,
            "** screw {}: {} (force) of its preload {} (torque {})\n*CLOAD",
            sc.name,
            num(built.applied),
            num(built.preload),
            num(sc.torque)
        );
        for (&(n, w), sign) in built
            .head
            .iter()
            .map(|x| (x, 1.0))
            .chain(built.nut.iter().map(|x| (x, -1.0)))
        {
            cload(out, n, [0, 1, 2].map(|c| sign * built.applied * w * d[c]));
        }
    }
    output_requests(out, s.outputs.len(), names);
    let _ = writeln!(out, "*END STEP");

    let _ = writeln!(
        out,
        "**\n** Step 2: the sweep, one increment per frequency (UINTER with LINPER = 1,\n\
         ** k* and d* from the UEXTERNALDB iteration store; jointlin.cfg: sweep_step = 2)."
    );
    let _ = writeln!(
        out,
        "*STEP, NAME=SWEEP\n*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR\n*INCLUDE, INPUT={FREQUENCY_FILE}"
    );
    for e in &s.excitation {
        let b = body_index(scene, &e.body);
        let d = unit(e.direction);
        // As model::build forms it: F e^{iφ} times each node's weight and direction.
        let amp = Complex::from_polar(e.amplitude, e.phase_deg.to_radians());
        let nodes: Vec<(usize, f64)> = match e.kind {
            ExcitationKind::Point => {
                let n = nearest(m, b, e.at.unwrap_or(m.nodes[m.bodies[b].first_node]));
                vec![(n, 1.0)]
            }
            ExcitationKind::Face => {
                let f = e.face.expect("validated");
                let _ = writeln!(
                    out,
                    "** traction {} along {:?} on {} {}: the consistent nodal forces",
                    num(e.amplitude),
                    e.direction,
                    e.body,
                    face_label(f)
                );
                let quads = m.bodies[b].face_quads(mesh_face(f), &m.elements);
                nodal_areas(m, &quads)
            }
        };
        for (card, part) in [("*CLOAD", amp.re), ("*CLOAD, IMAGINARY", amp.im)] {
            if part == 0.0 && card != "*CLOAD" {
                continue;
            }
            let _ = writeln!(out, "{card}");
            for &(n, w) in &nodes {
                cload(out, n, [0, 1, 2].map(|c| part * (w * d[c])));
            }
        }
    }
    output_requests(out, s.outputs.len(), names);
    contact_file(out, names);
    let _ = writeln!(out, "*END STEP");
}

/// The contact output URDFIL reads (fortran-shim/urdfil.f): per interface the slaves'
/// relative displacements CDISP to the results file, each frequency's real and imaginary
/// parts, so that the job reports its contact amplitudes to the iteration store.
fn contact_file(out: &mut String, names: &Names) {
    for name in &names.interfaces {
        let _ = writeln!(
            out,
            "*CONTACT FILE, SLAVE={name}_SLAVE, MASTER={name}_MASTER
CDISP"
        );
    }
}

/// Displacements of the output node sets: printed to the .dat file and written to the
/// .odb (U; in the sweep its real and imaginary parts per frequency).
fn output_requests(out: &mut String, n: usize, names: &Names) {
    for set in names.outputs.iter().take(n) {
        let _ = writeln!(out, "*NODE PRINT, NSET={set}\nU");
    }
    let _ = writeln!(out, "*OUTPUT, FIELD");
    for set in names.outputs.iter().take(n) {
        let _ = writeln!(out, "*NODE OUTPUT, NSET={set}\nU");
    }
}

/// The surfaces the preload's pressures act on and the outputs' node sets (model data,
/// written before the steps).
pub fn surfaces(out: &mut String, scene: &Scene, p: &Problem, names: &Names) {
    let m = &p.model;
    for l in &scene.spec.preload {
        if l.kind != PreloadKind::Pressure {
            continue;
        }
        let b = body_index(scene, &l.body);
        let f = l.face.expect("validated");
        let name = format!("PRESSURE_{}_{}", names.bodies[b], face_label(f));
        if out.contains(&format!("*SURFACE, NAME={name},")) {
            continue;
        }
        let _ = writeln!(out, "*SURFACE, NAME={name}, TYPE=ELEMENT");
        for (e, _) in super::mesh::face_elements(m, &m.bodies[b], mesh_face(f)) {
            let _ = writeln!(out, "{}, {}", e + 1, super::mesh::s_label(mesh_face(f)));
        }
    }
    for (o, out_node) in p.outputs.iter().enumerate() {
        let _ = writeln!(out, "*NSET, NSET={}", names.outputs[o]);
        id_lines(out, [out_node.node]);
    }
}
