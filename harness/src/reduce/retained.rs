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
/// the load. Errors: a load whose entries differ in phase.
pub fn retained(p: &Problem, stuck: &StuckContacts) -> Result<RetainedSet, String> {
    let mut set = RetainedSet::default();
    for pair in stuck.rows.chunks(2) {
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
