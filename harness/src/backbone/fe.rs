//! FE scenes (box bodies with `[[interfaces]]`, decks) as the lumped systems the
//! backbones take: after the static preload, the model with the closed contact points'
//! normal springs but without their tangential springs (K₀, M, Rayleigh D) is reduced
//! onto the tangential relative displacements r = B u of the closed points (two per
//! point, t₁ and t₂ of its frame; B the rows of `ContactPoint::rows`) plus interior
//! vectors, and each r_j carries one joint with the point's law in force form (normal
//! force p·A from the preload, k_T0·A; docs/model.md §3).
//!
//! The basis T = [Ψ, Θ] (u = Ψ r + Θ η):
//! - Ψ = X G⁻¹ with X = K_s⁻¹ Bᵀ, G = B X, K_s = K₀ + Bᵀ diag(k_T0·A) B the stuck
//!   stiffness: the Craig–Bampton constraint modes of K₀ onto r (the K₀-energy minimum
//!   with B u = r; the tangential springs add rᵀ diag(k_T0·A) r, constant on B u = r, so
//!   K_s has the same minimizers and is the one that is nonsingular). The joint forces
//!   act only through r, so every static state of the contact system is in span Ψ.
//! - Θ: the lowest stuck modes φ_k of (K_s, M) minus their constraint part,
//!   φ_k − Ψ B φ_k (so B Θ = 0 and r stays the joints' own coordinate), then
//!   M-orthonormalized as the Ritz modes of the interior block (Craig–Bampton's
//!   fixed-interface modes within this span). span T holds every stuck mode kept exactly,
//!   so the small-amplitude end of a backbone is the stuck FE mode.
//!
//! Not exact: the dynamics of the truncated stuck modes. The number of modes doubles
//! until the sliding frequencies (tangential springs removed) up to the traced mode
//! change by less than [`MODE_TOL`] of the stuck frequency.

use nalgebra::{Complex, DMatrix};

use crate::capi::Tangential;
use crate::mhb::{Element, Law, System};
use crate::model::lumped::{undamped_frequencies as frequencies, Lumped};
use crate::model::Problem;
use crate::settings::Effects;
use crate::solve::modal::{lowest_modes, ModalOptions};
use crate::solve::reduction::{
    basis, constraint_modes, interior_modes, project, stuck_contacts, Row, StuckContacts,
};
use crate::solve::static_step;
use crate::solve::sweep::Setup;

/// Convergence of the reduction: the sliding frequencies up to the traced mode change by
/// less than this fraction of its stuck frequency when the interior modes double.
pub const MODE_TOL: f64 = 1e-6;
/// Most joints (contact directions): the reduced model is dense, and the first-order
/// backbone factors it several times per amplitude (n³: 400 joints, about ten minutes
/// for the default 60 amplitudes). The bolted-lap deck's 720 did not finish its
/// reduction in five minutes.
pub const MAX_JOINTS: usize = 400;
/// Interior modes at the start of the doubling (at least twice the mode number).
const MIN_MODES: usize = 8;
/// Most interior modes (the dense systems downstream grow as their cube).
const MAX_MODES: usize = 256;

/// A reduced FE scene and how it was reduced.
#[derive(Debug, Clone)]
pub struct Reduced {
    /// The system (DOFs: r of every closed point's t₁, t₂, then the interior modes),
    /// its element names and output weights.
    pub lumped: Lumped,
    /// Contact points closed after the preload (each two joints) and open ones (none).
    pub closed: usize,
    pub open: usize,
    /// Interior modes kept.
    pub modes: usize,
    /// Sliding frequencies up to the traced mode at the kept count and at half of it
    /// (1/time): the convergence check.
    pub sliding: Vec<f64>,
    pub sliding_previous: Vec<f64>,
    /// The stuck frequencies of the reduced system up to the traced mode (1/time).
    pub stuck: Vec<f64>,
    /// The stuck frequencies of the full model the kept modes came from (1/time).
    pub stuck_full: Vec<f64>,
    /// Whether the check met [`MODE_TOL`] (false: [`MAX_MODES`] or the DOF count
    /// stopped it).
    pub converged: bool,
}

/// The reduced model's joints: per closed contact direction, then per cubic spring, its
/// row of B, its law (force form), k_T0·A (0 for a spring) and name.
struct Joints<'p> {
    rows: Vec<&'p [(usize, f64)]>,
    laws: Vec<Law>,
    kt: Vec<f64>,
    names: Vec<String>,
}

fn joints<'p>(p: &'p Problem, stuck: &[(usize, usize, &'p Row, Tangential)]) -> Joints<'p> {
    let mut j = Joints {
        rows: Vec::new(),
        laws: Vec::new(),
        kt: Vec::new(),
        names: Vec::new(),
    };
    for &(i, d, row, force) in stuck {
        j.rows.push(row);
        j.laws.push(Law::Point(force));
        j.kt.push(force.k_t0);
        let interface = &p.interfaces[p.contacts[i].interface].name;
        j.names.push(format!("{interface}.{i}.t{d}"));
    }
    for sp in &p.cubic_springs {
        j.rows.push(&sp.row);
        j.laws.push(Law::Cubic(sp.cubic));
        j.kt.push(0.0);
        j.names.push(format!("spring{}_cubic", sp.spring));
    }
    j
}

/// Reduces the FE problem `p` for a backbone of mode `mode` (1-based). `effects`:
/// `normal_contact_nonlinearity` for the static step, `material_damping` for D; the
/// three-direction point's effects are refused (not carried).
pub fn reduce(p: &Problem, effects: &Effects, mode: usize) -> Result<Reduced, String> {
    if p.has_area_samples() {
        return Err(
            "backbones take node-based contact points: an interface has `area_samples`".into(),
        );
    }
    if effects.normal_load_variation || effects.coupled_slip {
        return Err("the FE backbone reduces each closed point to the thesis's one-direction joints at its static normal force: [effects] normal_load_variation and coupled_slip are not carried; switch both off for that model (lumped scenes' joints with `normal` carry them)".into());
    }
    let stat =
        static_step::solve(p, effects.normal_contact_nonlinearity).map_err(|e| e.to_string())?;
    let mut eff = *effects;
    eff.tangential_microslip = true;
    let setup = Setup::new(p, &stat, &eff).map_err(|e| e.to_string())?;
    let n = p.sys.dofs.n_free();
    let StuckContacts {
        k0,
        ks,
        rows: stuck,
    } = stuck_contacts(p, &setup);
    let Joints {
        rows,
        laws,
        kt,
        names,
    } = joints(p, &stuck);
    let nb = rows.len();
    if nb > MAX_JOINTS {
        return Err(format!(
            "{nb} joints (two per closed contact point): backbones of FE scenes take at most \
             {MAX_JOINTS}, the reduced model is dense"
        ));
    }
    if nb == 0 {
        return Err("no contact point is closed after the preload: nothing to trace".into());
    }
    let psi = constraint_modes(&ks, &rows)?;
    if effects.material_damping && p.structural.is_some() {
        return Err("the model has structural damping (*DAMPING, STRUCTURAL=): backbones take viscous damping only".into());
    }
    let m = &p.sys.m;
    let damping = if effects.material_damping {
        p.damping.as_ref()
    } else {
        None
    };
    // Up to every mode of the model: a stuck mode in the joints' span adds nothing to
    // the interior (a block on a plane: its lowest modes are the joints' directions).
    let interior_max = n.min(MAX_MODES);
    let mut count = MIN_MODES.max(2 * mode).min(interior_max);
    let mut previous: Option<Vec<f64>> = None;
    loop {
        let modes = lowest_modes(
            &ks,
            m,
            &ModalOptions {
                n_modes: count,
                ..ModalOptions::default()
            },
        )
        .map_err(|e| e.to_string())?;
        let phi = DMatrix::from_fn(n, count, |i, c| modes.shapes[c][i]);
        let interior = interior_modes(&psi, &rows, &phi, (&k0, m));
        let ni = interior.ncols();
        let t = basis(&psi, &interior);
        let mr = project(m, &t);
        let kr = project(&k0, &t);
        let sliding: Vec<f64> = frequencies(&kr, &mr)?.into_iter().take(mode).collect();
        let mut kstuck = kr.clone();
        for (j, v) in kt.iter().enumerate() {
            kstuck[(j, j)] += v;
        }
        let stuck: Vec<f64> = frequencies(&kstuck, &mr)?.into_iter().take(mode).collect();
        let fref = stuck.last().copied().unwrap_or(1.0);
        // A basis spanning the model is exact.
        let spans = nb + ni == n;
        let converged = spans
            || previous.as_ref().is_some_and(|prev| {
                prev.len() == sliding.len()
                    && prev
                        .iter()
                        .zip(&sliding)
                        .all(|(a, b)| (a - b).abs() <= MODE_TOL * fref)
            });
        let last = count >= interior_max;
        if converged || last {
            let closed = stat.closed.iter().filter(|&&c| c).count();
            return Ok(Reduced {
                lumped: assemble(
                    p,
                    &t,
                    (mr, kr, damping.map(|d| project(d, &t))),
                    &laws,
                    &names,
                ),
                closed,
                open: p.contacts.len() - closed,
                modes: ni,
                sliding_previous: previous.unwrap_or_default(),
                sliding,
                stuck,
                stuck_full: modes.frequencies_hz().into_iter().take(mode).collect(),
                converged,
            });
        }
        previous = Some(sliding);
        count = (2 * count).min(interior_max);
    }
}

/// The reduced model on the basis `t` (n × (nb + ni): the nb joints' constraint modes,
/// then the interior modes): its projected mass, stiffness and material damping `mr`,
/// `kr`, `dr` (None: undamped), the load, the outputs' weights and one element per joint on its own
/// coordinate.
fn assemble(
    p: &Problem,
    t: &DMatrix<f64>,
    (mr, kr, dr): (DMatrix<f64>, DMatrix<f64>, Option<DMatrix<f64>>),
    laws: &[Law],
    names: &[String],
) -> Lumped {
    let (n, nb) = (t.nrows(), laws.len());
    let ni = t.ncols() - nb;
    let dr = dr.unwrap_or_else(|| DMatrix::zeros(nb + ni, nb + ni));
    let f1 = (0..nb + ni)
        .map(|c| {
            (0..n)
                .map(|i| p.excitation[i] * t[(i, c)])
                .sum::<Complex<f64>>()
        })
        .collect();
    let outputs = p
        .outputs
        .iter()
        .map(|o| {
            let w = (0..nb + ni)
                .map(|c| o.dofs.iter().map(|&(i, wi)| wi * t[(i, c)]).sum())
                .collect();
            (o.name.clone(), w)
        })
        .collect();
    let elements = laws
        .iter()
        .enumerate()
        .map(|(j, &law)| Element { i: j, j: None, law })
        .collect();
    let dofs = names
        .iter()
        .cloned()
        .chain((1..=ni).map(|c| format!("interior{c}")))
        .collect();
    Lumped::of_system(
        System {
            m: mr,
            d: dr,
            k: kr,
            f0: vec![0.0; nb + ni],
            f1,
            elements,
        },
        dofs,
        names.to_vec(),
        outputs,
    )
}
