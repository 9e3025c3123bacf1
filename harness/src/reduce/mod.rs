//! `jointlin reduce`: an FE scene or deck written as a `[[matrices]]` model with the scene
//! that runs it (docs/reduce.md). After the static preload, the model with the closed
//! contact points' normal springs but without their tangential springs (K₀, M, the
//! material damping D) is reduced by Craig–Bampton ([`crate::solve::reduction`]) onto
//! the retained coordinates ([`retained`]: the closed points' two tangential relative
//! displacements, the outputs, the load) plus interior modes of the stuck structure.
//! Each contact direction becomes a `[[joints]]` entry to the ground on its coordinate
//! with the point's law in force form (normal force p·A from the preload, k_T0·A;
//! docs/model.md §3), so the reduced scene's joints with every one stuck give the full
//! model's stuck modes: the kept ones exactly (span [Ψ, Θ] holds them). The files are
//! written by `export::reduced`.

pub mod retained;

use nalgebra::DMatrix;

use crate::fe::csc::Csc;
use crate::model::Problem;
use crate::settings::Effects;
use crate::solve::modal::{lowest_modes, ModalOptions};
use crate::solve::modal_band::modes_below;
use crate::solve::reduction::{basis, constraint_modes, interior_modes, project, stuck_contacts};
use crate::solve::static_step;
use crate::solve::sweep::Setup;

pub use retained::RetainedSet;

/// Fewest interior modes of a band choice.
pub const MIN_MODES: usize = 8;
/// Most interior modes (the reduced model is dense).
pub const MAX_MODES: usize = 512;
/// Most retained coordinates: the reduced model is dense and its sweeps factor it per
/// frequency (n³).
pub const MAX_RETAINED: usize = 2000;
/// Default band: the stuck modes below this multiple of the sweep's highest frequency
/// (as the modal route's default, `solve::sweep::modal_route::BAND_FACTOR`).
pub const BAND_FACTOR: f64 = crate::solve::sweep::modal_route::BAND_FACTOR;

/// How many interior modes to keep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Interior {
    Count(usize),
    /// Every stuck mode below this frequency (1/time), at least [`MIN_MODES`].
    Below(f64),
}

/// A reduced model.
#[derive(Debug, Clone)]
pub struct Reduction {
    pub set: RetainedSet,
    /// K_r = Tᵀ K₀ T, M_r, D_r (the retained coordinates first, then the interior modes).
    pub k: DMatrix<f64>,
    pub m: DMatrix<f64>,
    pub d: Option<DMatrix<f64>>,
    pub interior: usize,
    /// Contact points closed and open after the preload.
    pub closed: usize,
    pub open: usize,
    /// The stuck frequencies (1/time) of the full model (every kept mode) and of the
    /// reduced one with its joints stuck, as many.
    pub stuck_full: Vec<f64>,
    pub stuck_reduced: Vec<f64>,
}

/// Reduces `p`; `effects`: `normal_contact_nonlinearity` for the static step,
/// `material_damping` for D; the three-direction point's effects are refused (not
/// carried).
pub fn reduce(p: &Problem, effects: &Effects, interior: Interior) -> Result<Reduction, String> {
    if p.has_area_samples() {
        return Err(
            "a reduction takes node-based contact points: an interface has `area_samples`".into(),
        );
    }
    if !p.cubic_springs.is_empty() {
        return Err("the model has cubic springs: a reduction carries contact points only".into());
    }
    if effects.material_damping && p.structural.is_some() {
        return Err("the model has structural damping (*DAMPING, STRUCTURAL=): a reduced model takes viscous damping only".into());
    }
    if !p.modal_damping.is_empty() {
        return Err("the model has modal damping: it belongs to the full model's modes, not to a reduced model's; give Rayleigh damping".into());
    }
    let stat =
        static_step::solve(p, effects.normal_contact_nonlinearity).map_err(|e| e.to_string())?;
    let mut eff = *effects;
    eff.tangential_microslip = true;
    let setup = Setup::new(p, &stat, &eff).map_err(|e| e.to_string())?;
    let stuck = stuck_contacts(p, &setup);
    // With the three-direction effects each closed point is one joint of three
    // coordinates, its normal spring moved from K₀ into the joint.
    let three = effects.normal_load_variation || effects.coupled_slip;
    let set = retained::retained(p, &stuck, three.then_some(setup.normal_k.as_slice()))?;
    let k0 = if three {
        without_normal_springs(p, &setup, &stuck.k0)
    } else {
        stuck.k0.clone()
    };
    let nb = set.rows.len();
    if nb > MAX_RETAINED {
        return Err(format!(
            "{nb} retained coordinates (two per closed contact point, the outputs, the load): \
             a reduced model takes at most {MAX_RETAINED}, it is dense"
        ));
    }
    let rows: Vec<&[(usize, f64)]> = set.rows.iter().map(|r| r.row.as_slice()).collect();
    let psi = constraint_modes(&stuck.ks, &rows)?;
    let n = p.sys.dofs.n_free();
    let m = &p.sys.m;
    let most = n.saturating_sub(nb).min(MAX_MODES);
    let opts = ModalOptions::default();
    let modes = match interior {
        Interior::Count(c) => lowest_modes(
            &stuck.ks,
            m,
            &ModalOptions {
                n_modes: c.clamp(1, most.max(1)),
                ..opts
            },
        ),
        Interior::Below(f) => {
            modes_below(&stuck.ks, m, f, MIN_MODES.min(most), most, &opts).map(|b| b.modes)
        }
    }
    .map_err(|e| e.to_string())?;
    let count = modes.eigenvalues.len();
    let phi = DMatrix::from_fn(n, count, |i, c| modes.shapes[c][i]);
    let inner = interior_modes(&psi, &rows, &phi, (&stuck.k0, m));
    let t = basis(&psi, &inner);
    let k = project(&k0, &t);
    let mr = project(m, &t);
    let d = match (&p.damping, effects.material_damping) {
        (Some(d), true) => Some(project(d, &t)),
        _ => None,
    };
    let mut kstuck = k.clone();
    for j in &set.joints {
        kstuck[(j.coordinate, j.coordinate)] += j.law.k_t0;
    }
    for pt in &set.points {
        let [c1, c2, cn] = pt.coordinates;
        kstuck[(c1, c1)] += pt.law.k_t0;
        kstuck[(c2, c2)] += pt.law.k_t0;
        kstuck[(cn, cn)] += pt.k_n;
    }
    let stuck_full = modes.frequencies_hz();
    let stuck_reduced: Vec<f64> = crate::model::lumped::undamped_frequencies(&kstuck, &mr)?
        .into_iter()
        .take(stuck_full.len())
        .collect();
    let closed = stat.closed.iter().filter(|&&c| c).count();
    Ok(Reduction {
        set,
        k,
        m: mr,
        d,
        interior: inner.ncols(),
        closed,
        open: p.contacts.len() - closed,
        stuck_full,
        stuck_reduced,
    })
}

/// K₀ without the closed points' normal springs k_N·A·n nᵀ (the three-direction joints
/// carry them on their normal coordinates).
fn without_normal_springs(p: &Problem, setup: &Setup, k0: &Csc<f64>) -> Csc<f64> {
    let mut k = k0.clone();
    for &i in &setup.active {
        let c = &p.contacts[i];
        let n = c.frame.column(0);
        let block = n * n.transpose() * (-setup.normal_k[i] * c.area);
        p.sys.pairs.add(&mut k.values, c.pair, &block);
    }
    k
}
