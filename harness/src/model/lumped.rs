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

use nalgebra::{DMatrix, Vector3};

use super::lumped_ends::{axis, component, renumbered, Along, End, Ends, Loads, GROUND};
use super::lumped_joints::{self, JointInfo, Planned, Site};
use super::lumped_system::{Element, Element3, Law, System, System3};
use crate::formats::MatrixModel;
use crate::input::matrices;
use crate::input::scene::schema::{BodyKind, SceneFile, SpringSpec};
use crate::input::scene::Scene;

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
    /// The three-direction points of joints with `normal` whose `[effects]` need them.
    pub points: Vec<Element3>,
    /// Per `[[joints]]` entry: its elements or point and its static normal force.
    pub joints: Vec<JointInfo>,
}

impl Lumped {
    /// A lumped system of 1D elements only (a reduced FE scene's), with its DOF, element
    /// and output names.
    pub fn of_system(
        system: System,
        dofs: Vec<String>,
        elements: Vec<String>,
        outputs: Vec<(String, Vec<f64>)>,
    ) -> Self {
        Lumped {
            system,
            dofs,
            elements,
            outputs,
            points: Vec::new(),
            joints: Vec::new(),
        }
    }

    /// Undamped natural frequencies (1/time, ascending) with every joint stuck and
    /// every point closed ([`System3::stuck`]): K_s φ = ω² M φ solved as the symmetric
    /// (L⁻¹ K_s L⁻ᵀ) with M = L Lᵀ.
    pub fn stuck_frequencies(&self) -> Result<Vec<f64>, String> {
        undamped_frequencies(&self.system3().stuck().0, &self.system.m)
    }

    /// The system with its three-direction points.
    pub fn system3(&self) -> System3 {
        System3 {
            linear: self.system.clone(),
            elements: self.points.clone(),
        }
    }
}

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
    // Full system first; unused and clamped directions are removed at the end.
    let Full {
        mut k,
        mut d,
        m,
        sites,
        names: all_names,
    } = full_system(s, &models);
    let n = k.nrows();
    let ends = Ends { s, sites: &sites };
    let site = |name: &str| ends.site(name);
    let mut elements = Vec::new();
    let mut names = Vec::new();
    for (i, sp) in s.springs.iter().enumerate() {
        let (a, b) = match &sp.between {
            Some([x, y]) => ends.pair(x, y)?,
            None => ((sp.body.clone(), site(&sp.body)?), None),
        };
        if let Some(e) = add_spring(sp, &a, b.as_ref(), &mut k, &mut d)
            .map_err(|e| format!("springs[{i}]: {e}"))?
        {
            elements.push(e);
            names.push(format!("spring{i}_cubic"));
        }
    }
    let mut joints = Vec::new();
    let mut planned: Vec<Planned> = Vec::new();
    for j in &s.joints {
        if let (Some(normal), Some(k_n)) = (j.normal, j.normal_stiffness) {
            let mut ends = [None, None];
            for (e, x) in ends.iter_mut().zip(&j.between) {
                if x != GROUND {
                    *e = Some((x.as_str(), site(x)?));
                }
            }
            planned.push(lumped_joints::plan(j, normal, k_n, ends)?);
            continue;
        }
        let (info, element) = ends.one_direction_joint(j, elements.len())?;
        joints.push(info);
        elements.push(element);
        names.push(j.name.clone());
    }
    // Kept DOFs: not clamped, and (a mass body's) something acts on them.
    let clamped = ends.clamped(n)?;
    let used = |r: usize| {
        r < nm
            || (0..n).any(|c| k[(r, c)] != 0.0 || d[(r, c)] != 0.0)
            || elements.iter().any(|e| e.i == r || e.j == Some(r))
            || planned
                .iter()
                .any(|p| p.rows.iter().flatten().any(|&(d, _)| d == r))
    };
    let keep: Vec<usize> = (0..n).filter(|&r| !clamped[r] && used(r)).collect();
    let new = |r: usize| keep.iter().position(|&x| x == r);
    let kept_elements = renumbered(&elements, &names, &new)?;
    for p in &mut planned {
        lumped_joints::renumber(p, new)?;
    }
    let pick =
        |a: &DMatrix<f64>| DMatrix::from_fn(keep.len(), keep.len(), |r, c| a[(keep[r], keep[c])]);
    let mk = pick(&m);
    if (0..keep.len()).any(|r| mk[(r, r)] <= 0.0) {
        return Err("every loaded direction needs a mass body with mass > 0".into());
    }
    let dofs = keep.iter().map(|&r| all_names[r].clone()).collect();
    let along = Along {
        n: keep.len(),
        new: &new,
        clamped: &clamped,
    };
    let Loads { outputs, f1, f0 } = ends.loads(&along)?;
    let damping = if s.effects.material_damping {
        pick(&d)
    } else {
        DMatrix::zeros(keep.len(), keep.len())
    };
    let mut system = System {
        m: mk,
        d: damping,
        k: pick(&k),
        f0,
        f1,
        elements: kept_elements,
    };
    let (points, more) = if planned.is_empty() {
        (Vec::new(), Vec::new())
    } else {
        lumped_joints::finish(&mut system, &mut names, &planned, &s.effects)?
    };
    // The joints in file order: 1D ones were numbered as read, those with `normal` follow.
    joints.extend(more);
    joints.sort_by_key(|j| s.joints.iter().position(|x| x.name == j.name));
    Ok(Lumped {
        system,
        dofs,
        elements: names,
        outputs,
        points,
        joints,
    })
}

/// Adds spring `sp` between ends `a` and `b` (None: ground) to K and D (k·nnᵀ, c·nnᵀ
/// blocks); its cubic term, along a coordinate axis, as an element F = αδ³.
fn add_spring(
    sp: &SpringSpec,
    a: &End,
    b: Option<&End>,
    k: &mut DMatrix<f64>,
    d: &mut DMatrix<f64>,
) -> Result<Option<Element>, String> {
    let dir = Vector3::from(sp.direction).normalize();
    let axes: Vec<usize> = (0..3).filter(|&c| dir[c] != 0.0).collect();
    let dofs = |e: &End| -> Result<Vec<usize>, String> {
        axes.iter().map(|&c| component(&e.0, &e.1, c)).collect()
    };
    let da = dofs(a)?;
    let db = b.map(dofs).transpose()?;
    for (mat, v) in [(k, sp.stiffness), (d, sp.damping)] {
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
    if sp.cubic == 0.0 {
        return Ok(None);
    }
    let c = axis(&sp.direction).ok_or("a cubic term needs a coordinate axis")?;
    let p = axes
        .iter()
        .position(|&x| x == c)
        .expect("the axis is a component");
    Ok(Some(Element {
        i: da[p],
        j: db.as_ref().map(|db| db[p]),
        law: Law::Cubic(sp.cubic),
    }))
}

/// The full system before DOFs are removed: `[[matrices]]` blocks, then three
/// translations per mass body (its mass on the diagonal), each DOF's name and each
/// named end's site.
struct Full {
    k: DMatrix<f64>,
    d: DMatrix<f64>,
    m: DMatrix<f64>,
    sites: BTreeMap<String, Site>,
    names: Vec<String>,
}

fn full_system(s: &SceneFile, models: &[MatrixModel]) -> Full {
    let nm: usize = models.iter().map(|m| m.dofs.len()).sum();
    let n = nm + 3 * s.bodies.len();
    let mut f = Full {
        k: DMatrix::zeros(n, n),
        d: DMatrix::zeros(n, n),
        m: DMatrix::zeros(n, n),
        sites: BTreeMap::new(),
        names: Vec::with_capacity(n),
    };
    let mut off = 0;
    for model in models {
        let r = model.dofs.len();
        f.m.view_mut((off, off), (r, r)).copy_from(&model.m);
        f.k.view_mut((off, off), (r, r)).copy_from(&model.k);
        if let Some(md) = &model.d {
            f.d.view_mut((off, off), (r, r)).copy_from(md);
        }
        for (i, dof) in model.dofs.iter().enumerate() {
            f.names.push(format!("{}.{}", model.name, dof.name()));
            if let Some(a) = dof.axis {
                f.sites
                    .entry(format!("{}.{}", model.name, dof.point))
                    .or_insert([None; 3])[a] = Some(off + i);
            }
        }
        off += r;
    }
    for (b, body) in s.bodies.iter().enumerate() {
        for c in 0..3 {
            f.m[(nm + 3 * b + c, nm + 3 * b + c)] = body.mass.unwrap_or(0.0);
            f.names
                .push(format!("{}.{}", body.name, ["x", "y", "z"][c]));
        }
        f.sites.insert(
            body.name.clone(),
            std::array::from_fn(|c| Some(nm + 3 * b + c)),
        );
    }
    f
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
