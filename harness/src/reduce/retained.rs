//! The retained coordinates of a reduction: two per closed contact point (its tangential
//! relative displacements), one per output, one for the load; each named as a row of a
//! `[[matrices]]` DOF list, `point,direction`.
//!
//! A direction along a global axis (±e_k) is named by that axis, the row's sign turned
//! so that the coordinate is the displacement along +e_k. Any other direction is named
//! `x` (and a contact point's second `y`) of the point's own frame, which the DOF list's
//! comments state: joints and outputs of a lumped scene name coordinate axes.

use crate::capi::Tangential;
use crate::fe::dofs::DofMap;
use crate::model::Problem;
use crate::solve::reduction::StuckContacts;

/// A tangential row of a stuck contact ([`StuckContacts::rows`]).
type ContactRow<'p> = (usize, usize, &'p [(usize, f64)], Tangential);

/// One retained coordinate r = Σ w·u over free DOFs.
#[derive(Debug, Clone, PartialEq)]
pub struct Retained {
    pub point: String,
    /// `x`, `y` or `z`.
    pub label: char,
    pub row: Vec<(usize, f64)>,
}

/// A joint of the reduced scene: one tangential direction of a contact point.
#[derive(Debug, Clone)]
pub struct Joint {
    /// `<interface>.<point index>.t<1|2>`.
    pub name: String,
    /// Index of its coordinate in the retained list.
    pub coordinate: usize,
    /// The point's law in force form.
    pub law: Tangential,
}

/// A three-direction joint of the reduced scene (with `[effects] normal_load_variation`
/// or `coupled_slip`): one closed contact point, its two tangential relative
/// displacements and its opening along n.
#[derive(Debug, Clone)]
pub struct PointJoint {
    /// `<interface>.<point index>`.
    pub name: String,
    /// The retained coordinates of u₁ (t₁), u₂ (t₂) and the opening δ_n (n).
    pub coordinates: [usize; 3],
    /// Per coordinate: the global axis ±e_k its frame axis is (the coordinate is the
    /// displacement along +e_k), or (k, 1) of the point's own x, y, z (t₁, t₂, n).
    pub axes: [(usize, f64); 3],
    /// The point's law in force form (normal force N₀ = pA, k_T0·A).
    pub law: Tangential,
    /// The closed contact's normal stiffness k_N·A (force/length).
    pub k_n: f64,
}

/// The harmonic load on its retained coordinate: F = sign·amplitude·e^{iφ} along +label.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    pub coordinate: usize,
    pub amplitude: f64,
    pub phase_deg: f64,
    pub sign: f64,
}

/// An output of the reduced scene: its coordinate and the sign of its direction.
#[derive(Debug, Clone, PartialEq)]
pub struct OutputRow {
    pub name: String,
    pub coordinate: usize,
    pub sign: f64,
}

/// Everything retained, in the order of the reduced model's first rows.
#[derive(Debug, Clone, Default)]
pub struct RetainedSet {
    pub rows: Vec<Retained>,
    /// DOF-list comments: the frames of points not named by global axes.
    pub notes: Vec<String>,
    pub joints: Vec<Joint>,
    /// Three-direction joints (instead of `joints`, with the effects).
    pub points: Vec<PointJoint>,
    pub outputs: Vec<OutputRow>,
    pub load: Option<Load>,
    /// Contact directions whose relative displacement is held at zero by clamps (no row,
    /// no joint).
    pub held: usize,
}

const AXES: [char; 3] = ['x', 'y', 'z'];

/// The axis k and sign s of a unit vector v = s·e_k (to 1e-12), if it is one.
fn axis_of(v: [f64; 3]) -> Option<(usize, f64)> {
    let k = (0..3).max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))?;
    let off = (0..3).filter(|&c| c != k).map(|c| v[c].abs()).sum::<f64>();
    (off <= 1e-12 && (v[k].abs() - 1.0).abs() <= 1e-12).then(|| (k, v[k].signum()))
}

fn scaled(row: &[(usize, f64)], s: f64) -> Vec<(usize, f64)> {
    row.iter().map(|&(i, w)| (i, s * w)).collect()
}

fn show(v: [f64; 3]) -> String {
    format!("({}, {}, {})", v[0], v[1], v[2])
}

impl RetainedSet {
    /// The index of `row` among the rows (the same row retained once), or a new one.
    fn add(&mut self, point: &str, label: char, row: Vec<(usize, f64)>) -> usize {
        if let Some(i) = self.rows.iter().position(|r| r.row == row) {
            return i;
        }
        self.rows.push(Retained {
            point: point.to_string(),
            label,
            row,
        });
        self.rows.len() - 1
    }

    /// A point name not yet used, of the characters a DOF list takes (others become
    /// `_`): `name`, else `name_2`, `name_3`, …
    fn fresh(&self, name: &str) -> String {
        let name: String = name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let name = name.as_str();
        let taken = |n: &str| self.rows.iter().any(|r| r.point == n);
        (1..)
            .map(|k| {
                if k == 1 {
                    name.to_string()
                } else {
                    format!("{name}_{k}")
                }
            })
            .find(|n| !taken(n))
            .expect("an unused name")
    }
}

/// The retained set of problem `p`: the stuck contacts' rows, then the outputs, then
/// the load; with `normal_k` (per contact point, force/length³) each closed point is a
/// three-direction joint, its opening retained too. Errors: a load whose entries differ
/// in phase; a three-direction point with a held direction.
pub fn retained(
    p: &Problem,
    stuck: &StuckContacts,
    normal_k: Option<&[f64]>,
) -> Result<RetainedSet, String> {
    let mut set = RetainedSet::default();
    for pair in stuck.rows.chunks(2) {
        match normal_k {
            Some(kn) => point_joint(p, &mut set, pair, kn)?,
            None => direction_joints(p, &mut set, pair),
        }
    }
    for o in &p.outputs {
        let point = set.fresh(&o.name);
        let (label, row, sign) = match single_axis(&p.sys.dofs, &o.dofs) {
            Some((k, i, w)) => (AXES[k], vec![(i, 1.0)], w),
            None => ('x', o.dofs.clone(), 1.0),
        };
        let before = set.rows.len();
        let k = set.add(&point, label, row);
        if set.rows.len() > before && single_axis(&p.sys.dofs, &o.dofs).is_none() {
            set.notes.push(format!(
                "{point}: x along the output's direction {}",
                show(direction(&p.sys.dofs, &o.dofs))
            ));
        }
        set.outputs.push(OutputRow {
            name: o.name.clone(),
            coordinate: k,
            sign,
        });
    }
    set.load = load(p, &mut set)?;
    Ok(set)
}

/// The one-direction joints of one closed point: a joint per tangential `pair` row that
/// moves (thesis's model).
fn direction_joints(p: &Problem, set: &mut RetainedSet, pair: &[ContactRow]) {
    let (i, _, _, law) = pair[0];
    let c = &p.contacts[i];
    let itf = &p.interfaces[c.interface].name;
    let point = set.fresh(&format!("{itf}.{i}"));
    let t: Vec<[f64; 3]> = (1..=2)
        .map(|d| [c.frame[(0, d)], c.frame[(1, d)], c.frame[(2, d)]])
        .collect();
    let axes = [axis_of(t[0]), axis_of(t[1])];
    let named = match axes {
        [Some(a), Some(b)] => [(AXES[a.0], a.1), (AXES[b.0], b.1)],
        _ => {
            set.notes.push(format!(
                "{point}: x along t1 = {}, y along t2 = {} (its contact frame)",
                show(t[0]),
                show(t[1])
            ));
            [('x', 1.0), ('y', 1.0)]
        }
    };
    for (d, &(_, _, row, _)) in pair.iter().enumerate() {
        // Both nodes held in this direction (a symmetry plane's clamp): it never
        // moves, its joint never acts.
        if row.iter().all(|&(_, w)| w == 0.0) {
            set.held += 1;
            continue;
        }
        let k = set.add(&point, named[d].0, scaled(row, named[d].1));
        set.joints.push(Joint {
            name: format!("{itf}.{i}.t{}", d + 1),
            coordinate: k,
            law,
        });
    }
}

/// The three-direction joint of one closed point (its two tangential `pair` rows, its
/// normal row from the problem) with its three coordinates.
fn point_joint(
    p: &Problem,
    set: &mut RetainedSet,
    pair: &[ContactRow],
    normal_k: &[f64],
) -> Result<(), String> {
    let (i, _, _, law) = pair[0];
    let c = &p.contacts[i];
    let itf = &p.interfaces[c.interface].name;
    let point = set.fresh(&format!("{itf}.{i}"));
    // Frame columns t₁, t₂, n (the problem's frame is n, t₁, t₂).
    let v: Vec<[f64; 3]> = [1, 2, 0]
        .iter()
        .map(|&d| [c.frame[(0, d)], c.frame[(1, d)], c.frame[(2, d)]])
        .collect();
    let global: Option<Vec<(usize, f64)>> = v.iter().map(|&d| axis_of(d)).collect();
    let axes: [(usize, f64); 3] = match global {
        Some(a) => [a[0], a[1], a[2]],
        None => {
            set.notes.push(format!(
                "{point}: x along t1 = {}, y along t2 = {}, z along n = {} (its contact frame)",
                show(v[0]),
                show(v[1]),
                show(v[2])
            ));
            [(0, 1.0), (1, 1.0), (2, 1.0)]
        }
    };
    let rows = [
        c.rows[1].as_slice(),
        c.rows[2].as_slice(),
        c.rows[0].as_slice(),
    ];
    if rows.iter().any(|r| r.iter().all(|&(_, w)| w == 0.0)) {
        return Err(format!(
            "contact point {i} ({itf}) has a direction held by clamps: a three-direction joint needs all three"
        ));
    }
    let coordinates =
        [0, 1, 2].map(|a| set.add(&point, AXES[axes[a].0], scaled(rows[a], axes[a].1)));
    set.points.push(PointJoint {
        name: format!("{itf}.{i}"),
        coordinates,
        axes,
        law,
        k_n: normal_k[i] * c.area,
    });
    Ok(())
}

/// The output's direction at its node from its weights (clamped components absent).
fn direction(dofs: &DofMap, w: &[(usize, f64)]) -> [f64; 3] {
    let mut d = [0.0; 3];
    for &(i, wi) in w {
        d[dofs.full(i) % 3] += wi;
    }
    d
}

/// (axis, free DOF, weight) of a row that is one free DOF's displacement times ±1.
fn single_axis(dofs: &DofMap, w: &[(usize, f64)]) -> Option<(usize, usize, f64)> {
    match w {
        [(i, wi)] if (wi.abs() - 1.0).abs() <= 1e-12 => Some((dofs.full(*i) % 3, *i, *wi)),
        _ => None,
    }
}

/// The load f̂ = e^{iφ} g (g real) on its coordinate: one free DOF's axis when it acts
/// on one, else the unit pattern g/‖g‖ with amplitude ‖g‖.
fn load(p: &Problem, set: &mut RetainedSet) -> Result<Option<Load>, String> {
    let f = &p.excitation;
    let Some(big) = f.iter().max_by(|a, b| a.norm().total_cmp(&b.norm())) else {
        return Ok(None);
    };
    if big.norm() == 0.0 {
        return Ok(None);
    }
    let phase = big.arg();
    let turn = nalgebra::Complex::from_polar(1.0, -phase);
    let g: Vec<f64> = f.iter().map(|v| (v * turn).re).collect();
    let worst = f.iter().map(|v| (v * turn).im.abs()).fold(0.0f64, f64::max);
    if worst > 1e-12 * big.norm() {
        return Err(
            "the load's entries differ in phase: a reduced model carries one load pattern".into(),
        );
    }
    let nonzero: Vec<(usize, f64)> = g
        .iter()
        .enumerate()
        .filter(|(_, &v)| v != 0.0)
        .map(|(i, &v)| (i, v))
        .collect();
    let point = set.fresh("load");
    let before = set.rows.len();
    let (k, amplitude, sign) = match nonzero[..] {
        [(i, v)] => {
            let axis = p.sys.dofs.full(i) % 3;
            (
                set.add(&point, AXES[axis], vec![(i, 1.0)]),
                v.abs(),
                v.signum(),
            )
        }
        _ => {
            let a = g.iter().map(|v| v * v).sum::<f64>().sqrt();
            let k = set.add(&point, 'x', scaled(&nonzero, 1.0 / a));
            if set.rows.len() > before {
                set.notes
                    .push(format!("{point}: x along the load's pattern (unit length)"));
            }
            (k, a, 1.0)
        }
    };
    Ok(Some(Load {
        coordinate: k,
        amplitude,
        phase_deg: phase.to_degrees(),
        sign,
    }))
}
