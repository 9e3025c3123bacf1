//! Where a lumped scene's parts attach: its named ends (mass bodies, `[[matrices]]`
//! points) and their DOFs, the one-direction joints and the outputs and loads on them,
//! and the kept DOFs after clamps and unused directions are removed.

use std::collections::BTreeMap;

use nalgebra::{Complex, Vector3};

use super::lumped_joints::{JointInfo, Site};
use super::lumped_system::{Element, Law};
use crate::capi::Tangential;
use crate::input::scene::schema::{JointSpec, SceneFile};

pub(super) const GROUND: &str = "ground";

pub(super) fn axis(d: &[f64; 3]) -> Option<usize> {
    let nz: Vec<usize> = (0..3).filter(|&c| d[c] != 0.0).collect();
    (nz.len() == 1).then(|| nz[0])
}

/// A named end and its site.
pub(super) type End = (String, Site);

/// The scene's named ends (mass bodies, `[[matrices]]` points) and their sites.
pub(super) struct Ends<'a> {
    pub(super) s: &'a SceneFile,
    pub(super) sites: &'a BTreeMap<String, Site>,
}

/// The outputs' weights and the loads over the kept DOFs.
pub(super) struct Loads {
    pub(super) outputs: Vec<(String, Vec<f64>)>,
    /// First harmonic of the excitation (force).
    pub(super) f1: Vec<Complex<f64>>,
    /// Static preload (force).
    pub(super) f0: Vec<f64>,
}

impl Ends<'_> {
    /// The site of end `name`, or an error naming what is unknown.
    pub(super) fn site(&self, name: &str) -> Result<Site, String> {
        self.sites.get(name).copied().ok_or_else(|| match name.split_once('.') {
            Some((mat, _)) if self.s.matrices.iter().any(|x| x.name == mat) => format!(
                "unknown point `{name}`: the DOF list of matrices `{mat}` has no x, y or z row of it"
            ),
            _ => format!("unknown body `{name}`"),
        })
    }

    /// The two ends of an element between `x` and `y`, the ground (if either) second.
    pub(super) fn pair(&self, x: &str, y: &str) -> Result<(End, Option<End>), String> {
        let look = |n: &str| -> Result<Option<End>, String> {
            if n == GROUND {
                Ok(None)
            } else {
                self.site(n).map(|st| Some((n.to_string(), st)))
            }
        };
        match (look(x)?, look(y)?) {
            (Some(i), j) => Ok((i, j)),
            (None, Some(j)) => Ok((j, None)),
            (None, None) => Err(format!("`{x}`–`{y}`: no mass body")),
        }
    }

    /// Which of the `n` full DOFs `[[clamp]]` holds.
    pub(super) fn clamped(&self, n: usize) -> Result<Vec<bool>, String> {
        let mut clamped = vec![false; n];
        for cl in &self.s.clamp {
            let st = self.site(&cl.body)?;
            for c in (0..3).filter(|&c| cl.components[c]) {
                if let Some(r) = st[c] {
                    clamped[r] = true;
                }
            }
        }
        Ok(clamped)
    }

    /// A `[[joints]]` entry without `normal`: one library point on its axis (force form),
    /// element number `index`.
    pub(super) fn one_direction_joint(
        &self,
        j: &JointSpec,
        index: usize,
    ) -> Result<(JointInfo, Element), String> {
        let c =
            axis(&j.direction).ok_or(format!("joint `{}`: direction must be an axis", j.name))?;
        let (a, b) = self.pair(&j.between[0], &j.between[1])?;
        let at = |e: &End| component(&e.0, &e.1, c).map_err(|m| format!("joint `{}`: {m}", j.name));
        let info = JointInfo {
            name: j.name.clone(),
            elements: vec![index],
            point: None,
            static_normal: None,
            normal_varies: false,
        };
        let element = Element {
            i: at(&a)?,
            j: b.as_ref().map(at).transpose()?,
            law: Law::Point(Tangential {
                law: j.law,
                rule: j.rule,
                mu: j.mu,
                normal: j.normal_force.unwrap_or(0.0),
                k_t0: j.k_t0,
            }),
        };
        Ok((info, element))
    }

    /// The outputs' weights, the point excitations f̂ = F e^{iφ} along their direction
    /// (f(t) = Re(f̂ e^{iωt})) and the preload forces over the kept DOFs `at`.
    pub(super) fn loads(&self, at: &Along) -> Result<Loads, String> {
        let s = self.s;
        let dir = |name: &str, d: [f64; 3], loaded: bool| -> Result<Vec<f64>, String> {
            at.weights(name, &self.site(name)?, d, loaded)
        };
        let outputs = s
            .outputs
            .iter()
            .map(|o| {
                let w = dir(&o.body, o.direction, false)
                    .map_err(|e| format!("output `{}`: {e}", o.name))?;
                Ok((o.name.clone(), w))
            })
            .collect::<Result<Vec<_>, String>>()?;
        let mut f1 = vec![Complex::new(0.0, 0.0); at.n];
        for (i, e) in s.excitation.iter().enumerate() {
            let w = dir(&e.body, e.direction, true).map_err(|m| format!("excitation[{i}]: {m}"))?;
            let amp = Complex::from_polar(e.amplitude, e.phase_deg.to_radians());
            f1.iter_mut().zip(&w).for_each(|(f, w)| *f += amp * *w);
        }
        let mut f0 = vec![0.0; at.n];
        for (i, l) in s.preload.iter().enumerate() {
            let force = Vector3::from(l.force.unwrap_or([0.0; 3]));
            if force.norm() > 0.0 {
                let w =
                    dir(&l.body, force.into(), true).map_err(|m| format!("preload[{i}]: {m}"))?;
                f0.iter_mut()
                    .zip(&w)
                    .for_each(|(f, w)| *f += force.norm() * w);
            }
        }
        Ok(Loads { outputs, f1, f0 })
    }
}

/// The elements (named `names`) on the kept DOFs (`new`: a full DOF's kept index); one
/// on a clamped direction is an error.
pub(super) fn renumbered(
    elements: &[Element],
    names: &[String],
    new: &dyn Fn(usize) -> Option<usize>,
) -> Result<Vec<Element>, String> {
    let kept = |r: usize, name: &str| new(r).ok_or(format!("`{name}` acts on a clamped direction"));
    elements
        .iter()
        .zip(names)
        .map(|(e, name)| {
            let i = kept(e.i, name)?;
            let j = e.j.map(|j| kept(j, name)).transpose()?;
            Ok(Element { i, j, law: e.law })
        })
        .collect()
}

/// The DOF of `name` along axis `c`, or an error naming what lacks it.
pub(super) fn component(name: &str, st: &Site, c: usize) -> Result<usize, String> {
    st[c].ok_or_else(|| format!("`{name}` has no {} DOF in its DOF list", ["x", "y", "z"][c]))
}

/// The kept DOFs: their count, the new index of a full one, which full ones are clamped.
pub(super) struct Along<'a> {
    pub(super) n: usize,
    pub(super) new: &'a dyn Fn(usize) -> Option<usize>,
    pub(super) clamped: &'a [bool],
}

impl Along<'_> {
    /// Weights over the kept DOFs of the unit vector along `d` at end `name` (its
    /// components at the end's DOFs; a clamped component carries none). A `loaded`
    /// direction (a force) with a component along a direction nothing holds is an
    /// error; an output there reads zero.
    pub(super) fn weights(
        &self,
        name: &str,
        st: &Site,
        d: [f64; 3],
        loaded: bool,
    ) -> Result<Vec<f64>, String> {
        let d = Vector3::from(d).normalize();
        let mut w = vec![0.0; self.n];
        for c in (0..3).filter(|&c| d[c] != 0.0) {
            let axis = ["x", "y", "z"][c];
            let r = st[c].ok_or_else(|| format!("`{name}` has no {axis} DOF in its DOF list"))?;
            match (self.new)(r) {
                Some(p) => w[p] = d[c],
                None if self.clamped[r] || !loaded => {}
                None => {
                    return Err(format!(
                        "a force along {axis} of `{name}`, where nothing holds the body"
                    ))
                }
            }
        }
        Ok(w)
    }
}
