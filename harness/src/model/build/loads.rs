//! A scene's loads: the static step's preload (forces, pressures, screw preloads
//! spread over their heads and nuts) and the harmonic excitation, on all DOFs.

use nalgebra::{Complex, Vector3};

use super::{mesh_face, nearest, screw_spread, unit, BodyRef};
use crate::fe::mesh::{Body, Model};
use crate::fe::surface::{add_pressure, nodal_areas};
use crate::input::scene::{ExcitationKind, PreloadKind, SceneFile, ScrewEnd};
use crate::model::screw_load;
use crate::model::{BuildError, Screw};

/// The preload of scene `s` on every DOF (force) and its screws; `body` names the
/// bodies.
pub(super) fn preload(
    s: &SceneFile,
    model: &Model,
    body: &dyn Fn(&str) -> BodyRef,
) -> Result<(Vec<f64>, Vec<Screw>), BuildError> {
    let mut pre = vec![0.0; model.n_dofs()];
    for l in &s.preload {
        match (l.kind, body(&l.body)) {
            (PreloadKind::Pressure, BodyRef::Box(b)) => {
                let quads = model.bodies[b]
                    .face_quads(mesh_face(l.face.expect("validated")), &model.elements);
                add_pressure(model, &quads, l.pressure.expect("validated"), &mut pre);
            }
            (PreloadKind::Force, r) => {
                let n = nearest(model, r, l.at);
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
                    return Ok(vec![(nearest(model, r, Some(end.at)), 1.0)]);
                }
            }
            let boxes: Vec<Body> = names
                .iter()
                .map(|n| match body(n) {
                    BodyRef::Box(b) => model.bodies[b],
                    BodyRef::Mass { .. } => unreachable!("validated: a mass body alone"),
                })
                .collect();
            screw_load::weights(model, &boxes, end.at, axis.into(), screw_spread(end))
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
    Ok((pre, screws))
}

/// The complex excitation amplitudes of scene `s` on every DOF (force).
pub(super) fn excitation(
    s: &SceneFile,
    model: &Model,
    body: &dyn Fn(&str) -> BodyRef,
) -> Vec<Complex<f64>> {
    let mut exc = vec![Complex::new(0.0, 0.0); model.n_dofs()];
    for e in &s.excitation {
        let d = unit(e.direction);
        let amp = Complex::from_polar(e.amplitude, e.phase_deg.to_radians());
        let r = body(&e.body);
        let loads: Vec<(usize, f64)> = match (e.kind, r) {
            (ExcitationKind::Point, _) => vec![(nearest(model, r, e.at), 1.0)],
            (ExcitationKind::Face, BodyRef::Box(b)) => {
                let quads = model.bodies[b]
                    .face_quads(mesh_face(e.face.expect("validated")), &model.elements);
                nodal_areas(model, &quads)
            }
            (ExcitationKind::Face, BodyRef::Mass { .. }) => unreachable!("validated"),
        };
        for (n, w) in loads {
            for c in 0..3 {
                exc[3 * n + c] += amp * (w * d[c]);
            }
        }
    }
    exc
}
