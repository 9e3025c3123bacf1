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
use crate::fe::csc::Csc;
use crate::mhb::{Element, Law, System};
use crate::model::lumped::{undamped_frequencies as frequencies, Lumped};
use crate::model::Problem;
use crate::settings::Effects;
use crate::solve::contact::tangential;
use crate::solve::modal::{lowest_modes, ModalOptions};
use crate::solve::static_step;
use crate::solve::sweep::Setup;
use crate::solve::umfpack::Symbolic;

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
/// Interior Ritz vectors whose M-norm falls below this fraction of the largest are
/// dependent on the constraint modes and left out.
const DEPENDENT: f64 = 1e-12;

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

/// Columns of `x` times the sparse `a`.
fn mul_cols(a: &Csc<f64>, x: &DMatrix<f64>) -> DMatrix<f64> {
    let mut y = DMatrix::zeros(x.nrows(), x.ncols());
    for c in 0..x.ncols() {
        let col = a.mul_vec(x.column(c).as_slice());
        y.column_mut(c).copy_from_slice(&col);
    }
    y
}

/// Reduces the FE problem `p` for a backbone of mode `mode` (1-based). `effects`:
/// `normal_contact_nonlinearity` for the static step, `material_damping` for D.
pub fn reduce(p: &Problem, effects: &Effects, mode: usize) -> Result<Reduced, String> {
    if p.has_area_samples() {
        return Err(
            "backbones take node-based contact points: an interface has `area_samples`".into(),
        );
    }
    let stat =
        static_step::solve(p, effects.normal_contact_nonlinearity).map_err(|e| e.to_string())?;
    let mut eff = *effects;
    eff.tangential_microslip = true;
    let setup = Setup::new(p, &stat, &eff).map_err(|e| e.to_string())?;
    let n = p.sys.dofs.n_free();
    let pattern = p.sys.pattern.clone();
    let k0 = Csc {
        pattern: pattern.clone(),
        values: setup.base.clone(),
    };
    // Rows of B, the joints' laws (force form) and k_T0·A per row; then cubic springs.
    let mut rows: Vec<&[(usize, f64)]> = Vec::new();
    let mut laws = Vec::new();
    let mut kt = Vec::new();
    let mut names = Vec::new();
    let mut ks = k0.clone();
    for (j, &i) in setup.active.iter().enumerate() {
        let c = &p.contacts[i];
        let itf = &p.interfaces[c.interface];
        let t = tangential(itf, setup.pressure[i]);
        let force = Tangential {
            normal: t.normal * c.area,
            k_t0: t.k_t0 * c.area,
            ..t
        };
        for d in 1..=2 {
            rows.push(&c.rows[d]);
            laws.push(Law::Point(force));
            kt.push(force.k_t0);
            names.push(format!("{}.{i}.t{d}", itf.name));
        }
        let [b1, b2] = &setup.unit_blocks[j];
        p.sys.pairs.add(
            &mut ks.values,
            c.pair,
            &((b1 + b2) * itf.contact.k_t0_per_area),
        );
    }
    for sp in &p.cubic_springs {
        rows.push(&sp.row);
        laws.push(Law::Cubic(sp.cubic));
        kt.push(0.0);
        names.push(format!("spring{}_cubic", sp.spring));
    }
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
    // X = K_s⁻¹ Bᵀ (one factorization, nb solves), G = B X.
    let symbolic = Symbolic::<f64>::symmetric(pattern.clone()).map_err(|e| e.to_string())?;
    let num = symbolic.factor(&ks).map_err(|e| e.to_string())?;
    let mut rhs = vec![0.0; n * nb];
    for (j, row) in rows.iter().enumerate() {
        for &(i, w) in row.iter() {
            rhs[j * n + i] += w;
        }
    }
    let xs = num.solve_many(&rhs).map_err(|e| e.to_string())?;
    let x = DMatrix::from_fn(n, nb, |i, j| xs[j * n + i]);
    let apply_b = |v: &DMatrix<f64>| {
        DMatrix::from_fn(nb, v.ncols(), |r, c| {
            rows[r].iter().map(|&(i, w)| w * v[(i, c)]).sum::<f64>()
        })
    };
    let g = apply_b(&x);
    let g = (&g + g.transpose()) * 0.5;
    let chol = g
        .cholesky()
        .ok_or("B K_s⁻¹ Bᵀ is not positive definite: two contact directions coincide")?;
    // Ψ = X G⁻¹ (G symmetric): Ψᵀ = G⁻¹ Xᵀ.
    let psi = chol.solve(&x.transpose()).transpose();
    if effects.material_damping && p.structural.is_some() {
        return Err("the model has structural damping (*DAMPING, STRUCTURAL=): backbones take viscous damping only".into());
    }
    let m = &p.sys.m;
    let damping = if effects.material_damping {
        p.damping.as_ref()
    } else {
        None
    };
    let interior_max = n.saturating_sub(nb).min(MAX_MODES);
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
        let theta = &phi - &psi * apply_b(&phi);
        // Interior block as Ritz modes: M-orthonormal, ascending.
        let mt = theta.transpose() * mul_cols(m, &theta);
        let kt_ = theta.transpose() * mul_cols(&k0, &theta);
        let mt = (&mt + mt.transpose()) * 0.5;
        let eig = mt.clone().symmetric_eigen();
        let big = eig.eigenvalues.iter().copied().fold(0.0f64, f64::max);
        let keep: Vec<usize> = (0..count)
            .filter(|&c| eig.eigenvalues[c] > DEPENDENT * big)
            .collect();
        // Whitened basis W (count × kept): Wᵀ M_θ W = I.
        let w = DMatrix::from_fn(count, keep.len(), |r, c| {
            eig.eigenvectors[(r, keep[c])] / eig.eigenvalues[keep[c]].sqrt()
        });
        let kw = w.transpose() * &kt_ * &w;
        let e2 = ((&kw + kw.transpose()) * 0.5).symmetric_eigen();
        let mut order: Vec<usize> = (0..keep.len()).collect();
        order.sort_by(|&a, &b| e2.eigenvalues[a].total_cmp(&e2.eigenvalues[b]));
        let ritz = DMatrix::from_fn(keep.len(), keep.len(), |r, c| {
            e2.eigenvectors[(r, order[c])]
        });
        let interior = &theta * (w * ritz);
        let ni = interior.ncols();
        let mut t = DMatrix::zeros(n, nb + ni);
        t.view_mut((0, 0), (n, nb)).copy_from(&psi);
        t.view_mut((0, nb), (n, ni)).copy_from(&interior);
        let sym = |a: DMatrix<f64>| (&a + a.transpose()) * 0.5;
        let mr = sym(t.transpose() * mul_cols(m, &t));
        let kr = sym(t.transpose() * mul_cols(&k0, &t));
        let sliding: Vec<f64> = frequencies(&kr, &mr)?.into_iter().take(mode).collect();
        let mut kstuck = kr.clone();
        for (j, v) in kt.iter().enumerate() {
            kstuck[(j, j)] += v;
        }
        let stuck: Vec<f64> = frequencies(&kstuck, &mr)?.into_iter().take(mode).collect();
        let fref = stuck.last().copied().unwrap_or(1.0);
        let converged = previous.as_ref().is_some_and(|prev| {
            prev.len() == sliding.len()
                && prev
                    .iter()
                    .zip(&sliding)
                    .all(|(a, b)| (a - b).abs() <= MODE_TOL * fref)
        });
        let last = count >= interior_max;
        if converged || last {
            let dr = match damping {
                Some(d) => sym(t.transpose() * mul_cols(d, &t)),
                None => DMatrix::zeros(nb + ni, nb + ni),
            };
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
            let closed = stat.closed.iter().filter(|&&c| c).count();
            return Ok(Reduced {
                lumped: Lumped::of_system(
                    System {
                        m: mr,
                        d: dr,
                        k: kr,
                        f0: vec![0.0; nb + ni],
                        f1,
                        elements,
                    },
                    dofs,
                    names,
                    outputs,
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
