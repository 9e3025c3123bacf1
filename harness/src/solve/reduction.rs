//! The Craig–Bampton basis of a sparse model onto retained rows (docs/backbone-fe.md,
//! docs/reduce.md): u = Ψ r + Θ η with r = B u the retained coordinates (contact
//! directions, outputs, the load) and η interior amplitudes.
//!
//! - Ψ = X G⁻¹ with X = K_s⁻¹ Bᵀ, G = B X: the constraint modes (the K_s-energy minimum
//!   with B u = r; Craig & Bampton, AIAA J. 6 (1968) 1313, written for general rows B
//!   instead of selected DOFs). B Ψ = I.
//! - Θ: the lowest stuck modes φ_k of (K_s, M) minus their constraint part φ_k − Ψ B φ_k
//!   (so B Θ = 0 and r stays the retained coordinate), as the Ritz modes of the interior
//!   block of (K₀, M): M-orthonormal, ascending. span [Ψ, Θ] holds every kept stuck mode
//!   exactly.

use nalgebra::DMatrix;

use crate::capi::Tangential;
use crate::fe::csc::Csc;
use crate::model::Problem;
use crate::solve::contact::tangential;
use crate::solve::sweep::Setup;
use crate::solve::umfpack::Symbolic;

/// Interior Ritz vectors whose squared M-norm falls below this fraction of the largest
/// stuck mode's (or of the largest interior one's) are dependent on the constraint modes
/// and left out.
const DEPENDENT: f64 = 1e-12;

/// A sparse row of B: (free DOF, weight).
pub type Row = [(usize, f64)];

/// Columns of `x` times the sparse `a`.
pub fn mul_cols(a: &Csc<f64>, x: &DMatrix<f64>) -> DMatrix<f64> {
    let mut y = DMatrix::zeros(x.nrows(), x.ncols());
    for c in 0..x.ncols() {
        let col = a.mul_vec(x.column(c).as_slice());
        y.column_mut(c).copy_from_slice(&col);
    }
    y
}

/// B v for the rows `rows` (one output row per row of B).
pub fn apply_rows(rows: &[&Row], v: &DMatrix<f64>) -> DMatrix<f64> {
    DMatrix::from_fn(rows.len(), v.ncols(), |r, c| {
        rows[r].iter().map(|&(i, w)| w * v[(i, c)]).sum::<f64>()
    })
}

/// Tᵀ A T, symmetrized.
pub fn project(a: &Csc<f64>, t: &DMatrix<f64>) -> DMatrix<f64> {
    symmetric(t.transpose() * mul_cols(a, t))
}

/// (A + Aᵀ)/2.
pub fn symmetric(a: DMatrix<f64>) -> DMatrix<f64> {
    (&a + a.transpose()) * 0.5
}

/// The constraint modes Ψ = X G⁻¹ (n × rows) of the symmetric positive definite `ks`:
/// one factorization, one solve per row.
pub fn constraint_modes(ks: &Csc<f64>, rows: &[&Row]) -> Result<DMatrix<f64>, String> {
    let n = ks.n();
    let nb = rows.len();
    let symbolic = Symbolic::<f64>::symmetric(ks.pattern.clone()).map_err(|e| e.to_string())?;
    let num = symbolic.factor(ks).map_err(|e| e.to_string())?;
    let mut rhs = vec![0.0; n * nb];
    for (j, row) in rows.iter().enumerate() {
        for &(i, w) in row.iter() {
            rhs[j * n + i] += w;
        }
    }
    let xs = num.solve_many(&rhs).map_err(|e| e.to_string())?;
    let x = DMatrix::from_fn(n, nb, |i, j| xs[j * n + i]);
    let g = symmetric(apply_rows(rows, &x));
    let chol = g.cholesky().ok_or(
        "B K_s⁻¹ Bᵀ is not positive definite: two retained directions coincide or depend on each other",
    )?;
    // Ψ = X G⁻¹ (G symmetric): Ψᵀ = G⁻¹ Xᵀ.
    Ok(chol.solve(&x.transpose()).transpose())
}

/// The interior basis Θ from the stuck mode shapes `phi` (n × count): their parts with
/// B Θ = 0, as Ritz modes of (K₀, M) on that span (M-orthonormal, ascending); dependent
/// directions left out.
pub fn interior_modes(
    psi: &DMatrix<f64>,
    rows: &[&Row],
    phi: &DMatrix<f64>,
    (k0, m): (&Csc<f64>, &Csc<f64>),
) -> DMatrix<f64> {
    let count = phi.ncols();
    let theta = phi - psi * apply_rows(rows, phi);
    let mt = project(m, &theta);
    let kt = project(k0, &theta);
    let eig = mt.symmetric_eigen();
    // The stuck modes' own M-norms scale the test: when every mode lies in the span of
    // the constraint modes (a block on a plane: its lowest modes are the joints'
    // directions), all of Θ is round-off and none of it is kept.
    let modes_norm = project(m, phi).diagonal().max();
    let big = eig.eigenvalues.iter().copied().fold(modes_norm, f64::max);
    let keep: Vec<usize> = (0..count)
        .filter(|&c| eig.eigenvalues[c] > DEPENDENT * big)
        .collect();
    if keep.is_empty() {
        return DMatrix::zeros(phi.nrows(), 0);
    }
    // Whitened basis W (count × kept): Wᵀ M_θ W = I.
    let w = DMatrix::from_fn(count, keep.len(), |r, c| {
        eig.eigenvectors[(r, keep[c])] / eig.eigenvalues[keep[c]].sqrt()
    });
    let kw = symmetric(w.transpose() * &kt * &w).symmetric_eigen();
    let mut order: Vec<usize> = (0..keep.len()).collect();
    order.sort_by(|&a, &b| kw.eigenvalues[a].total_cmp(&kw.eigenvalues[b]));
    let ritz = DMatrix::from_fn(keep.len(), keep.len(), |r, c| {
        kw.eigenvectors[(r, order[c])]
    });
    theta * (w * ritz)
}

/// T = [Ψ, Θ] (n × (retained + interior)).
pub fn basis(psi: &DMatrix<f64>, interior: &DMatrix<f64>) -> DMatrix<f64> {
    let (n, nb, ni) = (psi.nrows(), psi.ncols(), interior.ncols());
    let mut t = DMatrix::zeros(n, nb + ni);
    t.view_mut((0, 0), (n, nb)).copy_from(psi);
    t.view_mut((0, nb), (n, ni)).copy_from(interior);
    t
}

/// The closed contact points of a sweep setup as retained directions: two rows per point
/// (t₁, t₂ of its frame), the point's law in force form (normal force p·A, k_T0·A;
/// docs/model.md §3), and the stuck stiffness K_s = K₀ + Bᵀ diag(k_T0·A) B.
pub struct StuckContacts<'p> {
    /// K₀: the model with the closed points' normal springs, without tangential ones.
    pub k0: Csc<f64>,
    pub ks: Csc<f64>,
    /// Per row: the contact point (index into `Problem::contacts`), its tangential
    /// direction (1 or 2), its row of B and its law.
    pub rows: Vec<(usize, usize, &'p Row, Tangential)>,
}

/// The closed points of `setup` (built with `tangential_microslip` on) on problem `p`.
pub fn stuck_contacts<'p>(p: &'p Problem, setup: &Setup) -> StuckContacts<'p> {
    let k0 = Csc {
        pattern: p.sys.pattern.clone(),
        values: setup.base.clone(),
    };
    let mut ks = k0.clone();
    let mut rows = Vec::new();
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
            rows.push((i, d, c.rows[d].as_slice(), force));
        }
        let [b1, b2] = &setup.unit_blocks[j];
        p.sys.pairs.add(
            &mut ks.values,
            c.pair,
            &((b1 + b2) * itf.contact.k_t0_per_area),
        );
    }
    StuckContacts { k0, ks, rows }
}
