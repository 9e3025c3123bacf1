//! Scene → [`Problem`]: meshes the boxes, adds lumped masses on a fixed ground node each,
//! finds the contact pairs, assembles K and M, material damping, loads and outputs.

mod contacts;
mod loads;
mod parts;

use nalgebra::{Matrix3, Vector3};

use super::damping::material_damping;
use super::screw_load::Spread;
use super::subgrid::coupling_pairs;
use super::{BuildError, Output, Problem};
use crate::fe::assembly::{assemble, System};
use crate::fe::csc::Csc;
use crate::fe::mesh::{Face, Material, Model};
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
    let names: Vec<&String> = s.materials.keys().collect();
    let mats = s
        .materials
        .values()
        .map(|m| Material::new(m.e, m.nu, m.rho))
        .collect::<Result<Vec<_>, _>>()?;
    let mat_index = |n: &str| names.iter().position(|m| *m == n).expect("validated");
    let mut model = Model::new(mats);

    let (bodies, mut pairs) = parts::bodies(s, &mut model, &mat_index)?;
    let body = |n: &str| bodies[n];

    parts::hold(s, &mut model, &body)?;

    // Interfaces and their contact pairs (before assembly: the pattern needs them).
    let (interfaces, raw_points, sampled_faces) = contacts::interfaces(s, &model, &body)?;
    let first_contact = pairs.len();
    pairs.extend(raw_points.iter().map(|r| r.0));
    let samples = contacts::samples(&model, &raw_points, sampled_faces);
    pairs.extend(coupling_pairs(&raw_points, &samples));

    let mut sys = assemble(&model, &pairs)?;

    let (cubic_springs, dash) = parts::masses_and_springs(s, &model, &body, &mut sys);
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
        if let Some(dash) = &dash {
            let dd = d.get_or_insert_with(|| Csc::zeros(sys.pattern.clone()));
            for (a, b) in dd.values.iter_mut().zip(&dash.values) {
                *a += b;
            }
        }
        d
    } else {
        None
    };

    let contacts = contacts::points(&raw_points, samples, &sys, &model, first_contact);

    let (pre, screws) = loads::preload(s, &model, &body)?;
    let preload = sys.dofs.restrict(&pre);

    let excitation = sys.dofs.restrict(&loads::excitation(s, &model, &body));

    let outputs = outputs(s, &model, &body, &sys);

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

/// The outputs of scene `s`: the node nearest each `at` and its unit direction's
/// weights on the free DOFs of `sys`.
fn outputs(
    s: &SceneFile,
    model: &Model,
    body: &dyn Fn(&str) -> BodyRef,
    sys: &System,
) -> Vec<Output> {
    s.outputs
        .iter()
        .map(|o| {
            let n = nearest(model, body(&o.body), o.at);
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
        .collect()
}

/// Frame with n = +z, t₁ = +x, t₂ = +y (columns).
fn frame_z() -> Matrix3<f64> {
    Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0)
}
