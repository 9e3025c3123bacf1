//! A lumped scene as a [`System`] of the lumped harmonic balance: `mass` bodies (three
//! translational DOFs each, minus `[[clamp]]` components, minus directions nothing acts
//! on), `[[springs]]` grounded (`body`) or `between` two bodies (k·nnᵀ and c·nnᵀ blocks;
//! a cubic term α along a coordinate axis becomes an element F = αδ³), `[[joints]]`
//! (a library contact point on one axis: μ, F_N, k_T0 in force form), `[[outputs]]`
//! (a direction at a mass body).

use nalgebra::{Complex, DMatrix, Vector3};

use crate::capi::Tangential;
use crate::input::scene::schema::{BodyKind, SceneFile};
use crate::input::scene::Scene;
use crate::mhb::{Element, Law, System};

const GROUND: &str = "ground";

/// The lumped system of a scene with its names.
#[derive(Debug, Clone)]
pub struct Lumped {
    pub system: System,
    /// `body.x|y|z` per DOF.
    pub dofs: Vec<String>,
    /// Per element of `system`: the joint's name, or `spring<i>_cubic`.
    pub elements: Vec<String>,
    /// Per `[[outputs]]`: name and weights over the DOFs (the unit direction).
    pub outputs: Vec<(String, Vec<f64>)>,
}

fn axis(d: &[f64; 3]) -> Option<usize> {
    let nz: Vec<usize> = (0..3).filter(|&c| d[c] != 0.0).collect();
    (nz.len() == 1).then(|| nz[0])
}

/// Builds the lumped system; a scene with FE (`box`) bodies or interfaces is refused
/// with a message.
pub fn build(scene: &Scene) -> Result<Lumped, String> {
    let s: &SceneFile = &scene.spec;
    if s.bodies.iter().any(|b| b.kind != BodyKind::Mass) || !s.interfaces.is_empty() {
        return Err(
            "backbones read lumped scenes: mass bodies, springs, [[joints]] (no box bodies, no [[interfaces]])"
                .into(),
        );
    }
    let nb = s.bodies.len();
    let index = |name: &str| s.bodies.iter().position(|b| b.name == name);
    // Full 3·nb system first; unused and clamped directions are removed at the end.
    let mut k = DMatrix::<f64>::zeros(3 * nb, 3 * nb);
    let mut d = DMatrix::<f64>::zeros(3 * nb, 3 * nb);
    let mut m = DMatrix::<f64>::zeros(3 * nb, 3 * nb);
    for (b, body) in s.bodies.iter().enumerate() {
        for c in 0..3 {
            m[(3 * b + c, 3 * b + c)] = body.mass.unwrap_or(0.0);
        }
    }
    let ends = |x: &str, y: &str| -> Result<(usize, Option<usize>), String> {
        let look = |n: &str| -> Result<Option<usize>, String> {
            if n == GROUND {
                Ok(None)
            } else {
                index(n).map(Some).ok_or(format!("unknown body `{n}`"))
            }
        };
        match (look(x)?, look(y)?) {
            (Some(i), j) => Ok((i, j)),
            (None, Some(j)) => Ok((j, None)),
            (None, None) => Err(format!("`{x}`–`{y}`: no mass body")),
        }
    };
    let mut elements = Vec::new();
    let mut names = Vec::new();
    for (i, sp) in s.springs.iter().enumerate() {
        let (a, b) = match &sp.between {
            Some([x, y]) => ends(x, y)?,
            None => (
                index(&sp.body).ok_or(format!("unknown body `{}`", sp.body))?,
                None,
            ),
        };
        let n = Vector3::from(sp.direction).normalize();
        for (mat, v) in [(&mut k, sp.stiffness), (&mut d, sp.damping)] {
            for r in 0..3 {
                for c in 0..3 {
                    let x = v * n[r] * n[c];
                    mat[(3 * a + r, 3 * a + c)] += x;
                    if let Some(b) = b {
                        mat[(3 * b + r, 3 * b + c)] += x;
                        mat[(3 * a + r, 3 * b + c)] -= x;
                        mat[(3 * b + r, 3 * a + c)] -= x;
                    }
                }
            }
        }
        if sp.cubic != 0.0 {
            let c = axis(&sp.direction).ok_or(format!(
                "springs[{i}]: a cubic term needs a coordinate axis"
            ))?;
            elements.push(Element {
                i: 3 * a + c,
                j: b.map(|b| 3 * b + c),
                law: Law::Cubic(sp.cubic),
            });
            names.push(format!("spring{i}_cubic"));
        }
    }
    for j in &s.joints {
        let c =
            axis(&j.direction).ok_or(format!("joint `{}`: direction must be an axis", j.name))?;
        let (a, b) = ends(&j.between[0], &j.between[1])?;
        elements.push(Element {
            i: 3 * a + c,
            j: b.map(|b| 3 * b + c),
            law: Law::Point(Tangential {
                law: j.law,
                rule: j.rule,
                mu: j.mu,
                normal: j.normal_force,
                k_t0: j.k_t0,
            }),
        });
        names.push(j.name.clone());
    }
    // Kept DOFs: not clamped, and something acts on them.
    let mut clamped = vec![false; 3 * nb];
    for cl in &s.clamp {
        if let Some(b) = index(&cl.body) {
            for c in 0..3 {
                clamped[3 * b + c] |= cl.components[c];
            }
        }
    }
    let used = |r: usize| {
        (0..3 * nb).any(|c| k[(r, c)] != 0.0 || d[(r, c)] != 0.0)
            || elements.iter().any(|e| e.i == r || e.j == Some(r))
    };
    let keep: Vec<usize> = (0..3 * nb).filter(|&r| !clamped[r] && used(r)).collect();
    let new = |r: usize| keep.iter().position(|&x| x == r);
    let mut kept_elements = Vec::new();
    for (e, name) in elements.iter().zip(&names) {
        let i = new(e.i).ok_or(format!("`{name}` acts on a clamped direction"))?;
        let j = match e.j {
            Some(j) => Some(new(j).ok_or(format!("`{name}` acts on a clamped direction"))?),
            None => None,
        };
        kept_elements.push(Element { i, j, law: e.law });
    }
    let pick =
        |a: &DMatrix<f64>| DMatrix::from_fn(keep.len(), keep.len(), |r, c| a[(keep[r], keep[c])]);
    let mk = pick(&m);
    if (0..keep.len()).any(|r| mk[(r, r)] <= 0.0) {
        return Err("every loaded direction needs a mass body with mass > 0".into());
    }
    let dofs = keep
        .iter()
        .map(|&r| format!("{}.{}", s.bodies[r / 3].name, ["x", "y", "z"][r % 3]))
        .collect();
    let mut outputs = Vec::new();
    for o in &s.outputs {
        let b = index(&o.body).ok_or(format!("output `{}`: unknown body", o.name))?;
        let n = Vector3::from(o.direction).normalize();
        let w = keep
            .iter()
            .map(|&r| if r / 3 == b { n[r % 3] } else { 0.0 })
            .collect();
        outputs.push((o.name.clone(), w));
    }
    let zero = Complex::new(0.0, 0.0);
    Ok(Lumped {
        system: System {
            m: mk,
            d: pick(&d),
            k: pick(&k),
            f0: vec![0.0; keep.len()],
            f1: vec![zero; keep.len()],
            elements: kept_elements,
        },
        dofs,
        elements: names,
        outputs,
    })
}
