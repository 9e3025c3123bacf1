//! A lumped scene as a [`System`] of the lumped harmonic balance: `mass` bodies (three
//! translational DOFs each, minus `[[clamp]]` components, minus directions nothing acts
//! on), `[[springs]]` grounded (`body`) or `between` two bodies (k·nnᵀ and c·nnᵀ blocks;
//! a cubic term α along a coordinate axis becomes an element F = αδ³), `[[joints]]`
//! (a library contact point on one axis: μ, F_N, k_T0 in force form), `[[outputs]]`
//! (a direction at a mass body or point), point `[[excitation]]`s (the first-harmonic load). `[[matrices]]` models (`input::matrices`) add
//! their M, K, D blocks; their points `<name>.<point>` are ends, clamps and outputs like
//! mass bodies, with the directions their DOF list has.

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::{Complex, DMatrix, Vector3};

use super::lumped_system::{Element, Law, System};
use crate::capi::Tangential;
use crate::input::matrices;
use crate::input::scene::schema::{BodyKind, SceneFile};
use crate::input::scene::Scene;

const GROUND: &str = "ground";

/// The lumped system of a scene with its names.
#[derive(Debug, Clone)]
pub struct Lumped {
    pub system: System,
    /// `body.x|y|z` (a matrices row: `<name>.<point>.<direction>`) per DOF.
    pub dofs: Vec<String>,
    /// Per element of `system`: the joint's name, or `spring<i>_cubic`.
    pub elements: Vec<String>,
    /// Per `[[outputs]]`: name and weights over the DOFs (the unit direction).
    pub outputs: Vec<(String, Vec<f64>)>,
}

impl Lumped {
    /// Undamped natural frequencies (1/time, ascending) with every joint stuck
    /// ([`System::stuck_stiffness`]): K_s φ = ω² M φ solved as the symmetric
    /// (L⁻¹ K_s L⁻ᵀ) with M = L Lᵀ.
    pub fn stuck_frequencies(&self) -> Result<Vec<f64>, String> {
        undamped_frequencies(&self.system.stuck_stiffness(), &self.system.m)
    }
}

fn axis(d: &[f64; 3]) -> Option<usize> {
    let nz: Vec<usize> = (0..3).filter(|&c| d[c] != 0.0).collect();
    (nz.len() == 1).then(|| nz[0])
}

/// Per axis x, y, z: the DOF of a named end in the full system, if it has one.
type Site = [Option<usize>; 3];

/// A named end and its site.
type End = (String, Site);

/// Builds the lumped system; a scene with FE (`box`) bodies or interfaces is refused
/// with a message. `[[matrices]]` models come first in the DOF order (their rows as
/// listed), then three translations per mass body.
pub fn build(scene: &Scene) -> Result<Lumped, String> {
    let s: &SceneFile = &scene.spec;
    if s.bodies.iter().any(|b| b.kind != BodyKind::Mass) || !s.interfaces.is_empty() {
        return Err(
            "backbones read lumped scenes: mass bodies, [[matrices]], springs, [[joints]] (no box bodies, no [[interfaces]])"
                .into(),
        );
    }
    let dir = Path::new(&scene.file).parent().unwrap_or(Path::new(""));
    let models = s
        .matrices
        .iter()
        .map(|m| matrices::load(m, dir))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())?;
    let nm: usize = models.iter().map(|m| m.dofs.len()).sum();
    let nb = s.bodies.len();
    let n = nm + 3 * nb;
    // Full system first; unused and clamped directions are removed at the end.
    let mut k = DMatrix::<f64>::zeros(n, n);
    let mut d = DMatrix::<f64>::zeros(n, n);
    let mut m = DMatrix::<f64>::zeros(n, n);
    let mut sites: BTreeMap<String, Site> = BTreeMap::new();
    let mut all_names = Vec::with_capacity(n);
    let mut off = 0;
    for model in &models {
        let r = model.dofs.len();
        m.view_mut((off, off), (r, r)).copy_from(&model.m);
        k.view_mut((off, off), (r, r)).copy_from(&model.k);
        if let Some(md) = &model.d {
            d.view_mut((off, off), (r, r)).copy_from(md);
        }
        for (i, dof) in model.dofs.iter().enumerate() {
            all_names.push(format!("{}.{}", model.name, dof.name()));
            if let Some(a) = dof.axis {
                sites
                    .entry(format!("{}.{}", model.name, dof.point))
                    .or_insert([None; 3])[a] = Some(off + i);
            }
        }
        off += r;
    }
    for (b, body) in s.bodies.iter().enumerate() {
        for c in 0..3 {
            m[(nm + 3 * b + c, nm + 3 * b + c)] = body.mass.unwrap_or(0.0);
            all_names.push(format!("{}.{}", body.name, ["x", "y", "z"][c]));
        }
        sites.insert(
            body.name.clone(),
            std::array::from_fn(|c| Some(nm + 3 * b + c)),
        );
    }
    let site = |name: &str| -> Result<Site, String> {
        sites.get(name).copied().ok_or_else(|| match name.split_once('.') {
            Some((mat, _)) if s.matrices.iter().any(|x| x.name == mat) => format!(
                "unknown point `{name}`: the DOF list of matrices `{mat}` has no x, y or z row of it"
            ),
            _ => format!("unknown body `{name}`"),
        })
    };
    // The DOF of `name` along axis `c`, or an error naming what lacks it.
    let component = |name: &str, st: &Site, c: usize| -> Result<usize, String> {
        st[c].ok_or_else(|| format!("`{name}` has no {} DOF in its DOF list", ["x", "y", "z"][c]))
    };
    let ends = |x: &str, y: &str| -> Result<(End, Option<End>), String> {
        let look = |n: &str| -> Result<Option<End>, String> {
            if n == GROUND {
                Ok(None)
            } else {
                site(n).map(|st| Some((n.to_string(), st)))
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
            None => ((sp.body.clone(), site(&sp.body)?), None),
        };
        let dir = Vector3::from(sp.direction).normalize();
        let axes: Vec<usize> = (0..3).filter(|&c| dir[c] != 0.0).collect();
        let da = axes
            .iter()
            .map(|&c| component(&a.0, &a.1, c))
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| format!("springs[{i}]: {e}"))?;
        let db = match &b {
            Some(b) => Some(
                axes.iter()
                    .map(|&c| component(&b.0, &b.1, c))
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(|e| format!("springs[{i}]: {e}"))?,
            ),
            None => None,
        };
        for (mat, v) in [(&mut k, sp.stiffness), (&mut d, sp.damping)] {
            for (p, &r) in axes.iter().enumerate() {
                for (q, &c) in axes.iter().enumerate() {
                    let x = v * dir[r] * dir[c];
                    mat[(da[p], da[q])] += x;
                    if let Some(db) = &db {
                        mat[(db[p], db[q])] += x;
                        mat[(da[p], db[q])] -= x;
                        mat[(db[p], da[q])] -= x;
                    }
                }
            }
        }
        if sp.cubic != 0.0 {
            let c = axis(&sp.direction).ok_or(format!(
                "springs[{i}]: a cubic term needs a coordinate axis"
            ))?;
            let p = axes
                .iter()
                .position(|&x| x == c)
                .expect("the axis is a component");
            elements.push(Element {
                i: da[p],
                j: db.as_ref().map(|db| db[p]),
                law: Law::Cubic(sp.cubic),
            });
            names.push(format!("spring{i}_cubic"));
        }
    }
    for j in &s.joints {
        let c =
            axis(&j.direction).ok_or(format!("joint `{}`: direction must be an axis", j.name))?;
        let (a, b) = ends(&j.between[0], &j.between[1])?;
        let at = |e: &End| component(&e.0, &e.1, c).map_err(|m| format!("joint `{}`: {m}", j.name));
        elements.push(Element {
            i: at(&a)?,
            j: b.as_ref().map(at).transpose()?,
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
    // Kept DOFs: not clamped, and (a mass body's) something acts on them.
    let mut clamped = vec![false; n];
    for cl in &s.clamp {
        let st = site(&cl.body)?;
        for c in 0..3 {
            if let (true, Some(r)) = (cl.components[c], st[c]) {
                clamped[r] = true;
            }
        }
    }
    let used = |r: usize| {
        r < nm
            || (0..n).any(|c| k[(r, c)] != 0.0 || d[(r, c)] != 0.0)
            || elements.iter().any(|e| e.i == r || e.j == Some(r))
    };
    let keep: Vec<usize> = (0..n).filter(|&r| !clamped[r] && used(r)).collect();
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
    let dofs = keep.iter().map(|&r| all_names[r].clone()).collect();
    let mut outputs = Vec::new();
    for o in &s.outputs {
        let st = site(&o.body).map_err(|e| format!("output `{}`: {e}", o.name))?;
        let dir = Vector3::from(o.direction).normalize();
        let mut w = vec![0.0; keep.len()];
        for c in (0..3).filter(|&c| dir[c] != 0.0) {
            let r = component(&o.body, &st, c).map_err(|e| format!("output `{}`: {e}", o.name))?;
            if let Some(p) = new(r) {
                w[p] = dir[c];
            }
        }
        outputs.push((o.name.clone(), w));
    }
    let zero = Complex::new(0.0, 0.0);
    // Point excitations: f̂ = F e^{iφ} along their direction (f(t) = Re(f̂ e^{iωt})).
    let mut f1 = vec![zero; keep.len()];
    for (i, e) in s.excitation.iter().enumerate() {
        let st = site(&e.body).map_err(|m| format!("excitation[{i}]: {m}"))?;
        let dir = Vector3::from(e.direction).normalize();
        let amp = Complex::from_polar(e.amplitude, e.phase_deg.to_radians());
        for c in (0..3).filter(|&c| dir[c] != 0.0) {
            let r = component(&e.body, &st, c).map_err(|m| format!("excitation[{i}]: {m}"))?;
            if let Some(p) = new(r) {
                f1[p] += amp * dir[c];
            }
        }
    }
    Ok(Lumped {
        system: System {
            m: mk,
            d: pick(&d),
            k: pick(&k),
            f0: vec![0.0; keep.len()],
            f1,
            elements: kept_elements,
        },
        dofs,
        elements: names,
        outputs,
    })
}

/// Undamped frequencies (1/time, ascending) of (K, M), M positive definite: the
/// eigenvalues of L⁻¹KL⁻ᵀ with M = LLᵀ.
pub fn undamped_frequencies(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Result<Vec<f64>, String> {
    let l = m
        .clone()
        .cholesky()
        .ok_or("the mass matrix is not positive definite")?
        .l();
    let li = l.try_inverse().ok_or("the mass matrix is singular")?;
    let a = &li * k * li.transpose();
    let mut f: Vec<f64> = ((&a + a.transpose()) * 0.5)
        .symmetric_eigenvalues()
        .iter()
        .map(|w2| w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect();
    f.sort_by(f64::total_cmp);
    Ok(f)
}
