//! Scene → [`Problem`]: meshes the boxes, adds lumped masses on a fixed ground node each,
//! finds the contact pairs, assembles K and M, material damping, loads and outputs.

use std::collections::BTreeMap;

use nalgebra::{Complex, Matrix3, Vector3};

use super::damping::material_damping;
use super::screw_load::{self, Spread};
use super::subgrid::{coupling_pairs, face_samples, AreaSample};
use super::{BuildError, ContactPoint, CubicSpring, Interface, Output, Problem, Screw};
use crate::fe::assembly::assemble;
use crate::fe::contact_pairs::{contact_quads, find_pairs_where};
use crate::fe::csc::Csc;
use crate::fe::mesh::{Body, BoxSpec, Face, Material, Model};
use crate::fe::surface::{add_pressure, nodal_areas};
use crate::fe::ties::find_ties;
use crate::input::scene::validate::GROUND;
use crate::input::scene::*;

/// Relative tolerance for coincident interface nodes (of the smallest element size).
pub const PAIR_TOL: f64 = 1e-6;

/// A body of the model.
#[derive(Debug, Clone, Copy)]
enum BodyRef {
    Box(usize),
    /// A point mass: its fixed ground node, its own node, mass, and the index of its
    /// ground pair among the pairs given to `assemble`.
    Mass {
        ground: usize,
        node: usize,
        mass: f64,
        pair: usize,
    },
}

/// The mesh face of a scene face name.
pub fn mesh_face(f: FaceName) -> Face {
    match f {
        FaceName::XMin => Face::XMin,
        FaceName::XMax => Face::XMax,
        FaceName::YMin => Face::YMin,
        FaceName::YMax => Face::YMax,
        FaceName::ZMin => Face::ZMin,
        FaceName::ZMax => Face::ZMax,
    }
}

fn unit(v: [f64; 3]) -> Vector3<f64> {
    Vector3::from(v).normalize()
}

/// The node of `body` nearest to `p` (a mass body: its node).
fn nearest(model: &Model, body: BodyRef, p: Option<[f64; 3]>) -> usize {
    match body {
        BodyRef::Mass { node, .. } => node,
        BodyRef::Box(b) => {
            let b = model.bodies[b];
            let p = p.expect("validated: `at` present for boxes");
            (b.first_node..b.first_node + b.n_nodes())
                .min_by(|&x, &y| {
                    let d = |n: usize| {
                        (0..3)
                            .map(|c| (model.nodes[n][c] - p[c]).powi(2))
                            .sum::<f64>()
                    };
                    d(x).total_cmp(&d(y))
                })
                .expect("a box has nodes")
        }
    }
}

/// How a screw end's force is spread (radii from the scene's diameters).
fn screw_spread(end: &ScrewEnd) -> Spread {
    match (end.bearing, end.thread) {
        (Some([inner, outer]), _) => Spread::Ring {
            inner: 0.5 * inner,
            outer: 0.5 * outer,
        },
        (None, Some(t)) => Spread::Thread {
            radius: 0.5 * t.diameter,
            length: t.length,
        },
        (None, None) => Spread::Node,
    }
}

/// Builds the problem of a validated scene (from its deck when it has one, see
/// [`super::deck`]).
pub fn build(scene: &Scene) -> Result<Problem, BuildError> {
    if let Some(job) = &scene.deck {
        return super::deck::build(scene, job);
    }
    if let Some(m) = &scene.spec.model {
        return Err(BuildError::Other(format!(
            "{}: `model = \"{m}\"`: the deck is read by `input::load`, not by `Scene::load`",
            scene.file
        )));
    }
    let s = &scene.spec;
    if s.is_lumped() {
        return Err(BuildError::Other(
            "a lumped system ([[matrices]], [[joints]], springs `between` two bodies) has no FE model: `jointlin run` (first order, harmonic balance or --time-domain), `tradeoff`, `modes` and `backbone` take it"
                .into(),
        ));
    }
    let names: Vec<&String> = s.materials.keys().collect();
    let mats = s
        .materials
        .values()
        .map(|m| Material::new(m.e, m.nu, m.rho))
        .collect::<Result<Vec<_>, _>>()?;
    let mat_index = |n: &str| names.iter().position(|m| *m == n).expect("validated");
    let mut model = Model::new(mats);

    // Bodies: boxes meshed, masses as (ground, node) with a ground pair.
    let mut bodies: BTreeMap<&str, BodyRef> = BTreeMap::new();
    let mut pairs: Vec<[usize; 2]> = Vec::new();
    for b in &s.bodies {
        let r = match b.kind {
            BodyKind::Box => BodyRef::Box(model.add_graded_box(
                BoxSpec {
                    origin: b.origin.expect("validated"),
                    size: b.size.expect("validated"),
                    divisions: b.divisions.expect("validated"),
                    material: mat_index(b.material.as_deref().expect("validated")),
                },
                b.grading.unwrap_or_default().axes(),
            )?),
            BodyKind::Mass => {
                let p = b.position.expect("validated");
                let ground = model.nodes.len();
                model.nodes.push(p);
                model.nodes.push(p);
                model.fixed.resize(model.n_dofs(), false);
                model.loads.resize(model.n_dofs(), 0.0);
                model.fix(&[ground], [true; 3])?;
                pairs.push([ground, ground + 1]);
                BodyRef::Mass {
                    ground,
                    node: ground + 1,
                    mass: b.mass.expect("validated"),
                    pair: pairs.len() - 1,
                }
            }
        };
        bodies.insert(&b.name, r);
    }
    let body = |n: &str| bodies[n];

    // Clamps.
    for c in &s.clamp {
        match body(&c.body) {
            BodyRef::Box(b) => {
                let nodes = model.bodies[b].face_nodes(mesh_face(c.face.expect("validated")));
                model.fix(&nodes, c.components)?;
            }
            BodyRef::Mass { node, .. } => model.fix(&[node], c.components)?,
        }
    }

    // Ties: coincident boundary nodes share DOFs (before assembly).
    for t in &s.ties {
        let [a, b] = &t.between;
        let (BodyRef::Box(ia), BodyRef::Box(ib)) = (body(a), body(b)) else {
            unreachable!("validated: ties join boxes")
        };
        let pairs = find_ties(&model, ia, ib, PAIR_TOL).map_err(|source| BuildError::Tie {
            a: a.clone(),
            b: b.clone(),
            source,
        })?;
        model.ties.extend(pairs);
    }

    // Interfaces and their contact pairs (before assembly: the pattern needs them).
    let mut interfaces = Vec::new();
    let mut raw_points = Vec::new(); // (nodes, frame, area, interface)
    let mut sampled_faces = Vec::new(); // (interface, its element faces, samples per side)
    for (i, f) in s.interfaces.iter().enumerate() {
        let [lo, hi] = &f.between;
        interfaces.push(Interface {
            name: f.name.clone(),
            contact: f.contact_law(),
            initial_gap: f.initial_gap,
        });
        if lo == GROUND {
            let BodyRef::Mass { ground, node, .. } = body(hi) else {
                unreachable!("validated: ground pairs with a mass body")
            };
            raw_points.push(([ground, node], frame_z(), f.area.expect("validated"), i));
            continue;
        }
        let (BodyRef::Box(a), BodyRef::Box(b)) = (body(lo), body(hi)) else {
            unreachable!("validated: box interfaces join boxes")
        };
        let keep = |c: [f64; 3]| !f.exclude.iter().any(|r| r.contains(c));
        let found = find_pairs_where(&model, a, b, PAIR_TOL, &keep).map_err(|source| {
            BuildError::Pairs {
                name: f.name.clone(),
                source,
            }
        })?;
        if let Some(per_side) = f.area_samples {
            let quads = contact_quads(&model, a, &keep).map_err(|source| BuildError::Pairs {
                name: f.name.clone(),
                source,
            })?;
            sampled_faces.push((i, quads, per_side));
        }
        for p in found {
            let all_fixed = p
                .nodes
                .iter()
                .all(|&n| (0..3).all(|c| model.fixed[3 * n + c]));
            if !all_fixed {
                raw_points.push((p.nodes, p.frame, p.area, i));
            }
        }
    }
    let first_contact = pairs.len();
    pairs.extend(raw_points.iter().map(|r| r.0));
    // Sub-grid samples (point k = raw_points[k]); the static step's normal tangent
    // couples a sampled point to the corners of its samples, so the pattern gets node
    // pairs for every such couple (after the contact pairs; nothing else uses them).
    let mut samples: Vec<Vec<AreaSample>> = vec![Vec::new(); raw_points.len()];
    for (itf, quads, per_side) in sampled_faces {
        let point_of_node: BTreeMap<usize, usize> = (0..raw_points.len())
            .filter(|&k| raw_points[k].3 == itf)
            .map(|k| (raw_points[k].0[0], k))
            .collect();
        let point_of = |n: usize| point_of_node.get(&n).copied();
        for (k, _, list) in face_samples(&model, &quads, &point_of, per_side) {
            samples[k] = list;
        }
    }
    pairs.extend(coupling_pairs(&raw_points, &samples));

    let mut sys = assemble(&model, &pairs)?;

    // Lumped masses and springs (blocks on the ground pair: the ground is fixed, so
    // only the mass node's 3×3 block remains).
    let mut dash = Csc::<f64>::zeros(sys.pattern.clone());
    let mut any_dash = false;
    for b in &s.bodies {
        if let BodyRef::Mass { mass, pair, .. } = body(&b.name) {
            sys.pairs.add(
                &mut sys.m.values,
                pair,
                &Matrix3::from_diagonal_element(mass),
            );
        }
    }
    let mut cubic_springs = Vec::new();
    for (i, sp) in s.springs.iter().enumerate() {
        let BodyRef::Mass { pair, node, .. } = body(&sp.body) else {
            unreachable!("validated: springs on masses")
        };
        let d = unit(sp.direction);
        let ddt = d * d.transpose();
        sys.pairs
            .add(&mut sys.k.values, pair, &(ddt * sp.stiffness));
        if sp.cubic != 0.0 {
            cubic_springs.push(CubicSpring {
                spring: i,
                pair,
                node,
                position: model.nodes[node],
                stiffness: sp.stiffness,
                cubic: sp.cubic,
                block: ddt,
                row: (0..3)
                    .filter_map(|c| sys.dofs.free(3 * node + c).map(|f| (f, d[c])))
                    .filter(|&(_, w)| w != 0.0)
                    .collect(),
            });
        }
        if sp.damping > 0.0 {
            sys.pairs.add(&mut dash.values, pair, &(ddt * sp.damping));
            any_dash = true;
        }
    }
    let damping = if s.effects.material_damping {
        let coef: Vec<(f64, f64)> = names
            .iter()
            .map(|n| {
                (
                    s.materials[*n].rayleigh_alpha,
                    s.materials[*n].rayleigh_beta,
                )
            })
            .collect();
        let mut d = material_damping(&model, &sys, &coef)?;
        if any_dash {
            let dd = d.get_or_insert_with(|| Csc::zeros(sys.pattern.clone()));
            for (a, b) in dd.values.iter_mut().zip(&dash.values) {
                *a += b;
            }
        }
        d
    } else {
        None
    };

    // Contact points with their B rows.
    let contacts = raw_points
        .iter()
        .zip(samples)
        .enumerate()
        .map(|(k, (&(nodes, frame, area, interface), samples))| {
            let rows = std::array::from_fn(|c| {
                let mut r = Vec::new();
                for (side, sign) in [(0, -1.0), (1, 1.0)] {
                    for g in 0..3 {
                        let w = sign * frame[(g, c)];
                        if let Some(f) = sys.dofs.free(3 * nodes[side] + g) {
                            if w != 0.0 {
                                r.push((f, w));
                            }
                        }
                    }
                }
                r
            });
            ContactPoint {
                pair: first_contact + k,
                nodes,
                frame,
                area,
                interface,
                position: model.nodes[nodes[0]],
                rows,
                samples,
            }
        })
        .collect();

    // Preload.
    let mut pre = vec![0.0; model.n_dofs()];
    for l in &s.preload {
        match (l.kind, body(&l.body)) {
            (PreloadKind::Pressure, BodyRef::Box(b)) => {
                let quads = model.bodies[b]
                    .face_quads(mesh_face(l.face.expect("validated")), &model.elements);
                add_pressure(&model, &quads, l.pressure.expect("validated"), &mut pre);
            }
            (PreloadKind::Force, r) => {
                let n = nearest(&model, r, l.at);
                let f = l.force.expect("validated");
                for c in 0..3 {
                    pre[3 * n + c] += f[c];
                }
            }
            (PreloadKind::Pressure, BodyRef::Mass { .. }) => unreachable!("validated"),
        }
    }
    let mut screws = Vec::new();
    for sc in &s.screws {
        let preload = crate::capi::screw_preload(
            sc.torque,
            sc.pitch,
            sc.d2,
            sc.mu_thread,
            sc.mu_head,
            sc.d_km,
        )
        .map_err(|source| BuildError::Screw {
            name: sc.name.clone(),
            source,
        })?;
        let applied = preload * sc.share;
        let d = unit(sc.direction);
        let spread = |end: &ScrewEnd, axis: Vector3<f64>| {
            let names = end.body.names();
            if let [one] = names[..] {
                if let r @ BodyRef::Mass { .. } = body(one) {
                    return Ok(vec![(nearest(&model, r, Some(end.at)), 1.0)]);
                }
            }
            let boxes: Vec<Body> = names
                .iter()
                .map(|n| match body(n) {
                    BodyRef::Box(b) => model.bodies[b],
                    BodyRef::Mass { .. } => unreachable!("validated: a mass body alone"),
                })
                .collect();
            screw_load::weights(&model, &boxes, end.at, axis.into(), screw_spread(end))
                .map_err(|e| BuildError::Other(format!("screw `{}`: {e}", sc.name)))
        };
        // The head is pulled towards the nut and the nut side towards the head.
        let head = spread(&sc.head, d)?;
        let nut = spread(&sc.nut, -d)?;
        for (&(n, w), sign) in head
            .iter()
            .map(|x| (x, 1.0))
            .chain(nut.iter().map(|x| (x, -1.0)))
        {
            for c in 0..3 {
                pre[3 * n + c] += sign * applied * w * d[c];
            }
        }
        screws.push(Screw {
            name: sc.name.clone(),
            preload,
            applied,
            head,
            nut,
        });
    }
    let preload = sys.dofs.restrict(&pre);

    // Excitation.
    let mut exc = vec![Complex::new(0.0, 0.0); model.n_dofs()];
    for e in &s.excitation {
        let d = unit(e.direction);
        let amp = Complex::from_polar(e.amplitude, e.phase_deg.to_radians());
        let r = body(&e.body);
        let loads: Vec<(usize, f64)> = match (e.kind, r) {
            (ExcitationKind::Point, _) => vec![(nearest(&model, r, e.at), 1.0)],
            (ExcitationKind::Face, BodyRef::Box(b)) => {
                let quads = model.bodies[b]
                    .face_quads(mesh_face(e.face.expect("validated")), &model.elements);
                nodal_areas(&model, &quads)
            }
            (ExcitationKind::Face, BodyRef::Mass { .. }) => unreachable!("validated"),
        };
        for (n, w) in loads {
            for c in 0..3 {
                exc[3 * n + c] += amp * (w * d[c]);
            }
        }
    }
    let excitation = sys.dofs.restrict(&exc);

    let outputs = s
        .outputs
        .iter()
        .map(|o| {
            let n = nearest(&model, body(&o.body), o.at);
            let d = unit(o.direction);
            let dofs = (0..3)
                .filter_map(|c| sys.dofs.free(3 * n + c).map(|f| (f, d[c])))
                .filter(|&(_, w)| w != 0.0)
                .collect();
            Output {
                name: o.name.clone(),
                node: n,
                dofs,
            }
        })
        .collect();

    Ok(Problem {
        model,
        sys,
        damping,
        structural: None,
        modal_damping: s.sweep.modal_damping.clone(),
        interfaces,
        contacts,
        cubic_springs,
        preload,
        excitation,
        outputs,
        screws,
        warnings: Vec::new(),
        notes: Vec::new(),
    })
}

/// Frame with n = +z, t₁ = +x, t₂ = +y (columns).
fn frame_z() -> Matrix3<f64> {
    Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0)
}
