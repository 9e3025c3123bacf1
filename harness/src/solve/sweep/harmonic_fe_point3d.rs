//! The library's three-direction point in the FE harmonic balance
//! ([`super::harmonic_fe`]; docs/contact3d.md), switched per scene by `[effects]`:
//!
//! - `normal_load_variation`: the point's normal relative displacement r_n joins the
//!   balance; the overclosure h(t) = h₀ − r_n(t) (h = −δ_n − g₀, model.md §2) is marched
//!   with the tangential displacements, so N(t) follows the normal law within the cycle,
//!   the point may separate and the slip limit is μN(t);
//! - `coupled_slip`: the two tangential directions slip under one circular limit
//!   ‖t‖ ≤ μN (radial return of the Jenkins cells, docs/contact3d.md §2) instead of as
//!   two independent points; without it (and with `normal_load_variation`) each
//!   tangential direction is marched as its own point (u₁, 0, h) and (0, u₂, h), so only
//!   the normal load is shared.
//!
//! Forces in stress form (the C API's force form with per-area data), beyond the
//! reference springs of the condensation: tangential ĝ_t = A(t(t) − k_T0 r_t); normal,
//! as an internal force along δ_n, ĝ_n = A(−(N(t) − N₀) − k_N r_n) with N₀ = k_N h₀ the
//! static step's pressure: zero while the point stays closed, since then
//! N − N₀ = −k_N r_n. The Jacobian of a point's force coefficients is a forward
//! difference of the whole marched map, as in [`crate::mhb::contact3d`].

use crate::capi::{Contact3, Tangential};
use crate::mhb::aft::Transforms;
use crate::mhb::contact3d::{march_point, Marched, VIRGIN};
use crate::mhb::loops::LoopSample;
use crate::mhb::MhbError;
use crate::model::Problem;
use crate::names::{NormalLawName, RuleName};
use crate::settings::{Effects, Mode};

use super::{SweepError, C64};

/// Which of the two effects are on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PointModel {
    pub normal_load_variation: bool,
    pub coupled_slip: bool,
}

impl PointModel {
    pub fn from_effects(e: &Effects) -> Self {
        PointModel {
            normal_load_variation: e.normal_load_variation,
            coupled_slip: e.coupled_slip,
        }
    }

    /// The thesis's model: two independent tangential points at constant normal load.
    pub fn is_thesis(&self) -> bool {
        !(self.normal_load_variation || self.coupled_slip)
    }

    /// Local components of a point in the balance, in order: (n,) t₁, t₂.
    pub fn components(&self) -> &'static [usize] {
        if self.normal_load_variation {
            &[0, 1, 2]
        } else {
            &[1, 2]
        }
    }
}

/// The scene may ask for the effects only where they are computed: the harmonic balance
/// (or, for coupled slip alone, its first-order describing function in mode fast),
/// interfaces with Masing's rule (the three-direction point's) and, for the normal load
/// variation, a linear normal law (the point's stress form).
pub fn check_effects(problem: &Problem, effects: &Effects, mode: Mode) -> Result<(), SweepError> {
    let model = PointModel::from_effects(effects);
    if model.is_thesis() {
        return Ok(());
    }
    let first_order = mode == Mode::Fast && !model.normal_load_variation;
    if mode != Mode::HarmonicBalance && !first_order {
        return Err(SweepError::ContactEffectsNeedHarmonicBalance);
    }
    check_laws(problem, model)
}

/// The interfaces' laws fit the three-direction point of `model` (any mode: the time
/// domain uses it too).
pub fn check_laws(problem: &Problem, model: PointModel) -> Result<(), SweepError> {
    for itf in &problem.interfaces {
        let law = |needs| SweepError::ContactEffectsLaw {
            interface: itf.name.clone(),
            needs,
        };
        if itf.contact.rule != RuleName::Masing {
            return Err(law(
                "rule = \"masing\" (the point unloads by Masing's rule)",
            ));
        }
        if model.normal_load_variation && itf.contact.normal_law != NormalLawName::Linear {
            return Err(law("normal_law = \"linear\" for normal_load_variation"));
        }
    }
    Ok(())
}

/// One point of the balance with the three-direction law (stress form).
#[derive(Debug, Clone, Copy)]
pub struct Point3 {
    pub contact: Contact3,
    /// Static overclosure h₀ = N₀/k_N (length).
    pub h0: f64,
    /// Tributary area (length²).
    pub area: f64,
    /// Normal reference stiffness per area in the condensed S_h (force/length³).
    pub k_ref_n: f64,
    pub model: PointModel,
}

impl Point3 {
    /// The point for tangential data `t` (pressure N₀ = t.normal), normal stiffness k_N
    /// per area of the law and `k_ref_n` of the condensation.
    pub fn new(t: &Tangential, k_n: f64, k_ref_n: f64, area: f64, model: PointModel) -> Self {
        Point3 {
            contact: Contact3::new(t.law, t.mu, t.k_t0, k_n),
            h0: t.normal / k_n,
            area,
            k_ref_n,
            model,
        }
    }

    fn len(&self) -> usize {
        self.model.components().len()
    }
}

/// A point's forces beyond the reference springs, direction by direction in the order
/// of [`PointModel::components`].
pub struct PointForces {
    /// ĝ (len·(2H+1)).
    pub ghat: Vec<f64>,
    /// ∂ĝ/∂r row-major ((len·(2H+1))²); empty without Jacobian.
    pub gamma: Vec<f64>,
    /// Energy dissipated per cycle (force·length), the whole point.
    pub dissipated: f64,
    /// First-harmonic stress over displacement per direction.
    pub describing: Vec<C64>,
}

/// Where the marches of a point start: virgin, or the closed states of a nearby path's
/// marches (the forward-difference columns: docs of [`march_point`]).
#[derive(Clone, Copy)]
enum Start<'a> {
    Virgin,
    Near(&'a Marched),
}

/// The point's stress coefficients (t₁, t₂ or −(N − N₀) per direction), dissipation (per
/// area) and closed marches at the direction coefficients `dc`: one coupled point, or
/// one per tangential direction sharing h ([`march_point`]).
fn stresses(
    tr: &mut Transforms,
    p: &Point3,
    dc: &[f64],
    start: Start,
) -> Result<(Vec<f64>, f64, Marched), MhbError> {
    let nc = tr.ncoef();
    let comps = p.model.components();
    let path = path(tr, p, dc);
    let states = match start {
        Start::Virgin => &VIRGIN,
        Start::Near(m) => &m.states,
    };
    let marched = march_point(&p.contact, p.model.coupled_slip, &path, states)?;
    let n0 = p.contact.k_n * p.h0;
    let mut out = vec![0.0; comps.len() * nc];
    for (d, &c) in comps.iter().enumerate() {
        let series: Vec<f64> = match c {
            0 => marched.force[2].iter().map(|v| -(v - n0)).collect(),
            _ => marched.force[c - 1].clone(),
        };
        tr.analyse(&series, &mut out[d * nc..(d + 1) * nc]);
    }
    Ok((out, marched.dissipated, marched))
}

/// Point `p`'s path (u₁, u₂, h) over the samples of a period at its direction
/// coefficients `dc` (h = h₀ − r_n; h₀ where the normal is not in the balance).
fn path(tr: &mut Transforms, p: &Point3, dc: &[f64]) -> Vec<[f64; 3]> {
    let (n, nc) = (tr.n, tr.ncoef());
    let mut path = vec![[0.0, 0.0, p.h0]; n];
    let mut x = vec![0.0; n];
    for (d, &c) in p.model.components().iter().enumerate() {
        tr.synthesize(&dc[d * nc..(d + 1) * nc], &mut x);
        for (s, r) in path.iter_mut().zip(&x) {
            match c {
                0 => s[2] = p.h0 - r,
                _ => s[c - 1] = *r,
            }
        }
    }
    path
}

/// Point `p`'s closed loop at its direction coefficients `dc`: per sample (u₁, u₂, h)
/// and the forces (F₁, F₂, N) = area × stresses, marched from a virgin state as the
/// balance marches it.
pub fn loop_samples(
    tr: &mut Transforms,
    p: &Point3,
    dc: &[f64],
) -> Result<Vec<LoopSample>, MhbError> {
    let path = path(tr, p, dc);
    let m = march_point(&p.contact, p.model.coupled_slip, &path, &VIRGIN)?;
    Ok(path
        .iter()
        .enumerate()
        .map(|(k, d)| LoopSample {
            displacement: *d,
            force: [0, 1, 2].map(|a| p.area * m.force[a][k]),
        })
        .collect())
}

/// ĝ of point `p` at its direction coefficients `dc` (and Γ when `jac`).
pub fn forces(
    tr: &mut Transforms,
    p: &Point3,
    dc: &[f64],
    jac: bool,
) -> Result<PointForces, MhbError> {
    let nc = tr.ncoef();
    let len = p.len() * nc;
    let comps = p.model.components();
    let k_ref = |d: usize| {
        if comps[d] == 0 {
            p.k_ref_n
        } else {
            p.contact.k_t0
        }
    };
    let (s, diss, marched) = stresses(tr, p, dc, Start::Virgin)?;
    let ghat: Vec<f64> = (0..len)
        .map(|i| p.area * (s[i] - k_ref(i / nc) * dc[i]))
        .collect();
    let describing = (0..p.len())
        .map(|d| {
            let r1 = C64::new(dc[d * nc + 1], -dc[d * nc + 2]);
            if r1.norm() > 0.0 {
                C64::new(s[d * nc + 1], -s[d * nc + 2]) / r1
            } else {
                C64::new(0.0, 0.0)
            }
        })
        .collect();
    let mut gamma = Vec::new();
    if jac {
        // Forward differences: step 1e-7 of the larger of max|r| and the stick
        // displacement μN₀/k_T0; each column marched from the base path's closed state.
        let scale = dc.iter().fold(
            p.contact.mu * p.contact.k_n * p.h0 / p.contact.k_t0,
            |a, v| a.max(v.abs()),
        );
        let eps = 1e-7 * scale.max(f64::MIN_POSITIVE);
        gamma = vec![0.0; len * len];
        let mut cp = dc.to_vec();
        for col in 0..len {
            cp[col] = dc[col] + eps;
            let (sp, _, _) = stresses(tr, p, &cp, Start::Near(&marched))?;
            cp[col] = dc[col];
            for row in 0..len {
                gamma[row * len + col] = p.area * (sp[row] - s[row]) / eps;
            }
            gamma[col * len + col] -= p.area * k_ref(col / nc);
        }
    }
    Ok(PointForces {
        ghat,
        gamma,
        dissipated: p.area * diss,
        describing,
    })
}
