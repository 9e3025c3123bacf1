//! A scene's bodies and what holds them: boxes meshed, point masses as (ground, node)
//! with a ground pair, clamps, ties; the masses' and springs' blocks (on the ground
//! pair: the ground is fixed, so only the mass node's 3×3 block remains).

use std::collections::BTreeMap;

use nalgebra::Matrix3;

use super::{mesh_face, unit, BodyRef, PAIR_TOL};
use crate::fe::assembly::System;
use crate::fe::csc::Csc;
use crate::fe::mesh::{BoxSpec, Model};
use crate::fe::ties::find_ties;
use crate::input::scene::{BodyKind, SceneFile};
use crate::model::{BuildError, CubicSpring};

/// The bodies of a scene by name.
pub(super) type Bodies<'s> = BTreeMap<&'s str, BodyRef>;

/// The bodies of scene `s` by name, meshed into `model` (`mat_index`: a material's
/// index by name), and the node pairs so far (one ground pair per mass).
pub(super) fn bodies<'s>(
    s: &'s SceneFile,
    model: &mut Model,
    mat_index: &dyn Fn(&str) -> usize,
) -> Result<(Bodies<'s>, Vec<[usize; 2]>), BuildError> {
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
    Ok((bodies, pairs))
}

/// The clamps and ties of scene `s` applied to `model` (ties: coincident boundary nodes
/// share DOFs, before assembly); `body` names the bodies.
pub(super) fn hold(
    s: &SceneFile,
    model: &mut Model,
    body: &dyn Fn(&str) -> BodyRef,
) -> Result<(), BuildError> {
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
        let pairs = find_ties(model, ia, ib, PAIR_TOL).map_err(|source| BuildError::Tie {
            a: a.clone(),
            b: b.clone(),
            source,
        })?;
        model.ties.extend(pairs);
    }
    Ok(())
}

/// The masses' and springs' blocks of scene `s` added to `sys` (M and K), the cubic
/// springs, and the springs' dashpots (a damping matrix on `sys`'s pattern, `None`
/// without any).
pub(super) fn masses_and_springs(
    s: &SceneFile,
    model: &Model,
    body: &dyn Fn(&str) -> BodyRef,
    sys: &mut System,
) -> (Vec<CubicSpring>, Option<Csc<f64>>) {
    let mut dash = Csc::<f64>::zeros(sys.pattern.clone());
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
        }
    }
    let any_dash = s.springs.iter().any(|sp| sp.damping > 0.0);
    (cubic_springs, any_dash.then_some(dash))
}
