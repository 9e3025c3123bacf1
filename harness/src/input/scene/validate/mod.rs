//! Validation of a deserialized scene: every check names the key it is about. One file
//! per subject; [`validate`] runs them in the order of the scene's tables.

mod bodies;
mod contact;
mod geometry;
mod loads;
mod lumped;
mod matrices;
pub mod size;
mod study;

use std::collections::{BTreeMap, BTreeSet};

use super::error::KeyPath;
pub use super::error::Problem;
use super::schema::*;
use super::Reading;
use crate::settings::units::frequency_spellings;

/// Name of the implicit fixed body a mass body can rest on.
pub const GROUND: &str = "ground";

/// The problems found so far, the body kinds by name (filled by the bodies' check) and
/// the names of the `[[matrices]]` models.
struct Checker {
    problems: Vec<Problem>,
    kinds: BTreeMap<String, BodyKind>,
    matrices: BTreeSet<String>,
}

impl Checker {
    /// The kind of a named body, if it exists; a point `<matrices>.<point>` of a
    /// `[[matrices]]` model counts as a mass body (whether the point exists is the
    /// model build's check: it reads the DOF list).
    fn kind(&self, name: &str) -> Option<BodyKind> {
        let point_of_matrices = name
            .split_once('.')
            .is_some_and(|(m, p)| !p.is_empty() && self.matrices.contains(m));
        self.kinds
            .get(name)
            .copied()
            .or(point_of_matrices.then_some(BodyKind::Mass))
    }

    /// The kind of a body named at `path`; a problem if there is none of that name.
    fn body(&mut self, path: KeyPath, name: &str) -> Option<BodyKind> {
        let k = self.kind(name);
        if k.is_none() {
            self.fail(path, format!("unknown body `{name}`"));
        }
        k
    }

    fn fail(&mut self, path: KeyPath, msg: impl Into<String>) {
        self.problems.push((path, msg.into()));
    }

    fn finite(&mut self, path: KeyPath, v: f64) -> bool {
        if v.is_finite() {
            true
        } else {
            self.fail(path, format!("must be finite, got {v}"));
            false
        }
    }

    fn positive(&mut self, path: KeyPath, v: f64) {
        if self.finite(path.clone(), v) && v <= 0.0 {
            self.fail(path, format!("must be > 0, got {v}"));
        }
    }

    fn non_negative(&mut self, path: KeyPath, v: f64) {
        if self.finite(path.clone(), v) && v < 0.0 {
            self.fail(path, format!("must be >= 0, got {v}"));
        }
    }

    fn vec3(&mut self, path: KeyPath, v: &[f64; 3]) {
        for (i, x) in v.iter().enumerate() {
            self.finite(path.index(i), *x);
        }
    }

    fn direction(&mut self, path: KeyPath, v: &[f64; 3]) {
        self.vec3(path.clone(), v);
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(n > 0.0 && n.is_finite()) {
            self.fail(path, "direction must be a nonzero vector");
        }
    }

    fn require<T>(&mut self, path: KeyPath, v: &Option<T>, why: &str) -> bool {
        if v.is_none() {
            self.fail(path, format!("missing: required {why}"));
            false
        } else {
            true
        }
    }

    fn forbid<T>(&mut self, path: KeyPath, v: &Option<T>, why: &str) {
        if v.is_some() {
            self.fail(path, format!("not allowed {why}"));
        }
    }
}

/// Checks a scene; returns every problem found, in file order of the tables.
/// [`validate_for`] a forced response.
pub fn validate(s: &SceneFile) -> Vec<Problem> {
    validate_for(s, Reading::Forced)
}

/// The scene's problems for a command that reads it as `reading`: without a forced
/// response an absent `[sweep]`, `[[excitation]]` or `[[outputs]]` is no problem (a
/// given one is checked all the same).
pub fn validate_for(s: &SceneFile, reading: Reading) -> Vec<Problem> {
    let problems = checked(s);
    if reading == Reading::Forced {
        return problems;
    }
    let no_sweep = s.sweep == SweepSpec::default();
    let absent = [
        ("excitation", s.excitation.is_empty()),
        ("outputs", s.outputs.is_empty()),
    ];
    problems
        .into_iter()
        .filter(|(p, _)| {
            let first = p.0.first();
            let is = |k: &str| matches!(first, Some(super::error::Seg::Key(x)) if x == k);
            let left_out = absent.iter().any(|&(k, a)| a && is(k) && p.0.len() == 1);
            let sweep_left_out = no_sweep && is("sweep");
            !(left_out || sweep_left_out)
        })
        .collect()
}

fn checked(s: &SceneFile) -> Vec<Problem> {
    let mut c = Checker {
        problems: Vec::new(),
        kinds: BTreeMap::new(),
        matrices: BTreeSet::new(),
    };
    units(&mut c, s);
    bodies::materials(&mut c, s);
    bodies::bodies(&mut c, s);
    matrices::matrices(&mut c, s);
    contact::interfaces(&mut c, s);
    contact::ties(&mut c, s);
    contact::screws(&mut c, s);
    if c.problems.is_empty() {
        geometry::interfaces(&mut c, s);
        geometry::ties(&mut c, s);
    }
    loads::preload(&mut c, s);
    loads::clamp(&mut c, s);
    lumped::joints(&mut c, s);
    lumped::springs(&mut c, s);
    lumped::effects(&mut c, s);
    lumped::no_fe_parts(&mut c, s);
    loads::excitation(&mut c, s);
    study::sweep(&mut c, s);
    study::iteration(&mut c, s);
    study::outputs(&mut c, s);
    study::loss_study(&mut c, s);
    study::time_domain(&mut c, s);
    study::field_output(&mut c, s);
    super::model_file::adjust(s, c.problems)
}

/// Unit names known and consistent (mass = force·time²/length).
fn units(c: &mut Checker, s: &SceneFile) {
    let u = KeyPath::root().key("units");
    for (k, message) in crate::settings::unit_names::problems(&s.units) {
        c.fail(u.key(k), message);
    }
    if let Some(f) = &s.units.frequency {
        let ok = frequency_spellings(&s.units);
        if !ok.contains(f) {
            c.fail(
                u.key("frequency"),
                format!("frequency unit \"{f}\": one of {}", ok.join(", ")),
            );
        }
    }
}

/// Most harmonics and samples per period a scene may ask for (H = 64 is far past where
/// the rungs have converged on any scene here; N bounds the march's memory and time).
pub const MAX_HARMONICS: usize = 64;
/// Most sub-grid samples per quarter face and direction (`area_samples`).
pub const MAX_AREA_SAMPLES: usize = 32;
pub const MAX_SAMPLES: usize = 1 << 16;
