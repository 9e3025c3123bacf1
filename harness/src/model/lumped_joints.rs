//! `[[joints]]` with `normal`: three-direction points of a lumped system
//! (docs/contact3d.md), switched by `[effects]` as in FE scenes. The static step
//! ([`super::lumped_static`]) gives each joint's normal force N₀; then
//!
//! - `normal_load_variation`: the point's normal row stays in the balance, N(t) =
//!   max(0, k_N·h(t)) within the cycle (separation, slip limit μN(t));
//! - without it the normal direction is the linear spring k_N of the closed contact and
//!   the point's overclosure stays at N₀/k_N;
//! - `coupled_slip`: both tangential directions under one circular limit; without it
//!   (and without the normal variation) the joint is two independent thesis-model
//!   points at N₀, 1D elements of the lumped system (first order or harmonic balance).
//!
//! Rows: the relative displacement r = x₂ − x₁ of the second end of `between` against the
//! first (ground: zero) projected on `direction` (u₁), normal × direction (u₂) and
//! `normal` (the opening g). A joint's `normal_force` is a clamp inside the joint (a
//! bolt): the point starts closed by g₀ = F_N/k_N and an equal and opposite external
//! pair −F_N·n on the ends balances it, so with no load the joint carries F_N and the
//! static step adds the loads' share.

use nalgebra::Vector3;

use super::lumped_static;
use super::lumped_system::{Element, Element3, Law, Row, System, System3};
use crate::capi::{Contact3, Tangential};
use crate::input::scene::schema::JointSpec;
use crate::settings::Effects;

/// Per axis x, y, z: the DOF of a named end in the full system, if it has one.
pub type Site = [Option<usize>; 3];

/// How a `[[joints]]` entry entered the lumped system.
#[derive(Debug, Clone, PartialEq)]
pub struct JointInfo {
    pub name: String,
    /// Its 1D elements (indices into the system's elements).
    pub elements: Vec<usize>,
    /// Its three-direction point (index into the points).
    pub point: Option<usize>,
    /// The static normal force N₀ (force) of a joint with `normal`.
    pub static_normal: Option<f64>,
    /// Whether N(t) varies within the cycle (`normal_load_variation`).
    pub normal_varies: bool,
}

/// A joint with `normal` in the full DOF numbering, before the static step.
#[derive(Debug, Clone)]
pub struct Planned {
    pub name: String,
    pub rows: [Row; 3],
    pub tangential: Tangential,
    pub k_n: f64,
    /// The clamp force inside the joint, F_N (force; 0 without `normal_force`).
    pub clamp: f64,
}

/// The rows of joint `j` between ends `first` and `second` (None: ground), each axis
/// resolved to the end's DOF; an error names an end without the DOF.
pub fn plan(
    j: &JointSpec,
    normal: [f64; 3],
    k_n: f64,
    ends: [Option<(&str, Site)>; 2],
) -> Result<Planned, String> {
    let n = Vector3::from(normal).normalize();
    let t1 = Vector3::from(j.direction).normalize();
    let t2 = n.cross(&t1);
    let row = |v: &Vector3<f64>| -> Result<Row, String> {
        let mut r = Row::new();
        for c in (0..3).filter(|&c| v[c].abs() > 0.5) {
            for (end, sign) in ends.iter().zip([-1.0, 1.0]) {
                if let Some((name, site)) = end {
                    let d = site[c].ok_or_else(|| {
                        format!(
                            "joint `{}`: `{name}` has no {} DOF in its DOF list",
                            j.name,
                            ["x", "y", "z"][c]
                        )
                    })?;
                    r.push((d, sign * v[c].signum()));
                }
            }
        }
        Ok(r)
    };
    Ok(Planned {
        name: j.name.clone(),
        rows: [row(&t1)?, row(&t2)?, row(&n)?],
        tangential: Tangential {
            law: j.law,
            rule: j.rule,
            mu: j.mu,
            normal: 0.0,
            k_t0: j.k_t0,
        },
        k_n,
        clamp: j.normal_force.unwrap_or(0.0),
    })
}

/// A planned joint's rows in the kept DOF numbering (`new`), or an error when it acts
/// on a clamped direction.
pub fn renumber(p: &mut Planned, new: impl Fn(usize) -> Option<usize>) -> Result<(), String> {
    for row in &mut p.rows {
        for (d, _) in row.iter_mut() {
            *d = new(*d).ok_or(format!("`{}` acts on a clamped direction", p.name))?;
        }
    }
    Ok(())
}

/// Adds the planned joints to `system` as `[effects]` say (module docs): 1D elements
/// (named `<joint>_t1`, `<joint>_t2`, appended to `names`), linear normal springs and
/// three-direction points; returns the points and each joint's [`JointInfo`].
pub fn finish(
    system: &mut System,
    names: &mut Vec<String>,
    planned: &[Planned],
    effects: &Effects,
) -> Result<(Vec<Element3>, Vec<JointInfo>), String> {
    let mut points: Vec<Element3> = Vec::new();
    for p in planned {
        for &(d, w) in &p.rows[2] {
            system.f0[d] -= p.clamp * w;
        }
        let t = &p.tangential;
        points.push(Element3 {
            rows: p.rows.clone(),
            contact: Contact3::new(t.law, t.mu, t.k_t0, p.k_n),
            gap: p.clamp / p.k_n,
            coupled: effects.coupled_slip,
        });
    }
    let joint_names: Vec<String> = planned.iter().map(|p| p.name.clone()).collect();
    let full = System3 {
        linear: system.clone(),
        elements: points.clone(),
    };
    let st = lumped_static::solve(&full, &joint_names)?;
    let mut kept = Vec::new();
    let mut info = Vec::new();
    for (k, (p, mut e)) in planned.iter().zip(points).enumerate() {
        let (n0, t0) = (st.normal[k], st.tangential[k]);
        if t0 > p.tangential.mu * n0 * (1.0 + 1e-12) {
            return Err(format!(
                "joint `{}` slides under the static load: stuck tangential force {t0:.6e} > μN₀ = {:.6e}",
                p.name,
                p.tangential.mu * n0
            ));
        }
        let mut joint = JointInfo {
            name: p.name.clone(),
            elements: Vec::new(),
            point: None,
            static_normal: Some(n0),
            normal_varies: effects.normal_load_variation,
        };
        if !effects.normal_load_variation {
            if n0 <= 0.0 {
                return Err(format!(
                    "joint `{}` is open under the static load (N₀ = 0): at a constant normal force it carries nothing; [effects] normal_load_variation follows its contact",
                    p.name
                ));
            }
            // The closed contact's linear normal spring about x = 0 with its preload
            // k_N·g₀, which cancels the clamp's balancing pair.
            let w = std::mem::take(&mut e.rows[2]);
            for &(a, wa) in &w {
                for &(b, wb) in &w {
                    system.k[(a, b)] += p.k_n * wa * wb;
                }
                system.f0[a] += p.clamp * wa;
            }
            e.gap = n0 / p.k_n;
        }
        if effects.normal_load_variation || effects.coupled_slip {
            joint.point = Some(kept.len());
            kept.push(e);
        } else {
            for (a, row) in e.rows[..2].iter().enumerate() {
                joint.elements.push(system.elements.len());
                system.elements.push(one_direction(row, p.tangential, n0));
                names.push(format!("{}_t{}", p.name, a + 1));
            }
        }
        info.push(joint);
    }
    Ok((kept, info))
}

/// The thesis-model element of one tangential row (one DOF per end on an axis) at
/// normal force N₀: relative displacement x_i − x_j (the friction law is odd, so the
/// row's sign does not matter).
fn one_direction(row: &Row, t: Tangential, n0: f64) -> Element {
    Element {
        i: row[0].0,
        j: row.get(1).map(|r| r.0),
        law: Law::Point(Tangential { normal: n0, ..t }),
    }
}
