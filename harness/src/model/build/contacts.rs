//! A scene's interfaces: the contact pairs found between two boxes (or a ground–mass
//! pair), their sub-grid area samples, and the contact points with their rows
//! δ = u_upper − u_lower in the frame Q = [n t₁ t₂] (the parent module's docs).

use std::collections::BTreeMap;

use nalgebra::Matrix3;

use super::{frame_z, BodyRef, PAIR_TOL};
use crate::fe::assembly::System;
use crate::fe::contact_pairs::{contact_quads, find_pairs_where};
use crate::fe::mesh::Model;
use crate::input::scene::validate::GROUND;
use crate::input::scene::SceneFile;
use crate::model::subgrid::{face_samples, AreaSample};
use crate::model::{BuildError, ContactPoint, Interface};

/// A contact point before assembly: its nodes (lower, upper), frame Q, area
/// (length²) and interface index.
pub(super) type RawPoint = ([usize; 2], Matrix3<f64>, f64, usize);
/// An interface with sub-grid area samples: its index, its element faces (corner
/// nodes) and the samples per side of each face.
pub(super) type SampledFace = (usize, Vec<[usize; 4]>, usize);
/// What [`interfaces`] finds.
type Found = (Vec<Interface>, Vec<RawPoint>, Vec<SampledFace>);

/// The interfaces of scene `s`, their contact points (a point whose nodes are held in
/// every direction is left out) and the faces to sample; `body` names the bodies.
pub(super) fn interfaces(
    s: &SceneFile,
    model: &Model,
    body: &dyn Fn(&str) -> BodyRef,
) -> Result<Found, BuildError> {
    let mut interfaces = Vec::new();
    let mut raw_points = Vec::new();
    let mut sampled_faces = Vec::new();
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
        let found =
            find_pairs_where(model, a, b, PAIR_TOL, &keep).map_err(|source| BuildError::Pairs {
                name: f.name.clone(),
                source,
            })?;
        if let Some(per_side) = f.area_samples {
            let quads = contact_quads(model, a, &keep).map_err(|source| BuildError::Pairs {
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
    Ok((interfaces, raw_points, sampled_faces))
}

/// The sub-grid area samples of each point (empty where its interface has none).
pub(super) fn samples(
    model: &Model,
    raw_points: &[RawPoint],
    sampled_faces: Vec<SampledFace>,
) -> Vec<Vec<AreaSample>> {
    let mut samples: Vec<Vec<AreaSample>> = vec![Vec::new(); raw_points.len()];
    for (itf, quads, per_side) in sampled_faces {
        let point_of_node: BTreeMap<usize, usize> = (0..raw_points.len())
            .filter(|&k| raw_points[k].3 == itf)
            .map(|k| (raw_points[k].0[0], k))
            .collect();
        let point_of = |n: usize| point_of_node.get(&n).copied();
        for (k, _, list) in face_samples(model, &quads, &point_of, per_side) {
            samples[k] = list;
        }
    }
    samples
}

/// The contact points with their rows on the free DOFs of `sys`; point k is pair
/// `first_contact + k`.
pub(super) fn points(
    raw_points: &[RawPoint],
    samples: Vec<Vec<AreaSample>>,
    sys: &System,
    model: &Model,
    first_contact: usize,
) -> Vec<ContactPoint> {
    raw_points
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
        .collect()
}
