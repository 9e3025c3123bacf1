//! CalculiX's C3D8I as matrices. ccx expands each C3D8I into its 8 corner nodes and 3
//! bubble nodes carrying the 9 incompatible modes as DOFs; `*FREQUENCY,
//! SOLVER=MATRIXSTORAGE` writes K and M over all of them. Its bubble DOFs carry mass
//! in M, which lowers ccx's own eigenfrequencies. jointlin's element (`fe::hex8`: Wilson,
//! Taylor, 9 modes, condensed) takes the mass from the corner nodes' shape functions
//! only, the incompatible modes enriching the strain field alone. Condensing ccx's
//! bubble DOFs statically, without their mass, gives the element jointlin forms: on a
//! mesh of parallelepipeds the same frequencies to round-off; on distorted cells within
//! 1e-3 (the incompatible modes' treatment of distortion differs: jointlin applies
//! Taylor's correction).

use std::path::Path;

use nalgebra::DMatrix;

use super::ccx::{
    case_model, dense_frequencies, frequency_deck, generalized_frequencies, run_frequencies,
    CcxError, CASE_MODES,
};
use crate::fe::elements::ElementKind;
use crate::formats::{ccx, dofs, mtx};

/// The element case's C3D8I frequencies (Hz), [`CASE_MODES`] of them: jointlin's,
/// ccx's own eigenvalue run, and ccx's K and M with the bubble DOFs condensed massless.
pub struct C3d8iFrequencies {
    pub ours: Vec<f64>,
    pub ccx: Vec<f64>,
    /// ccx's K and M over all its DOFs, the bubbles' mass included.
    pub ccx_matrices: Vec<f64>,
    pub ccx_massless_bubbles: Vec<f64>,
}

/// Runs ccx twice in `dir` (eigenvalues; matrix storage) on the element case with its
/// interior corners moved by up to `jitter` of a cell.
pub fn c3d8i_frequencies(dir: &Path, jitter: f64) -> Result<C3d8iFrequencies, CcxError> {
    let (mesh, mat, fixed) = case_model(ElementKind::C3D8I, jitter)?;
    let ours = dense_frequencies(&mesh, &mat, &fixed, CASE_MODES)?;
    let deck = frequency_deck(&mesh, &mat, &fixed, CASE_MODES);
    let ccx_own = run_frequencies(&deck, dir, "c3d8i")?;
    let storage = deck.replace(
        &format!("*FREQUENCY\n{CASE_MODES}\n"),
        "*FREQUENCY, SOLVER=MATRIXSTORAGE\n",
    );
    // run_frequencies fails on the missing eigenvalue table only after ccx ran.
    match run_frequencies(&storage, dir, "c3d8i_k") {
        Err(CcxError::Failed { why, .. }) if why.starts_with("no eigenvalue") => {}
        Err(e) => return Err(e),
        Ok(_) => {}
    }
    let failed = |why: String| CcxError::Failed {
        job: "c3d8i_k".into(),
        why,
    };
    let imp = ccx::import(&dir.join("c3d8i_k")).map_err(|e| failed(e.to_string()))?;
    let rows = dofs::parse("c3d8i_k.dof", &imp.dofs).map_err(|e| failed(e.to_string()))?;
    let k = mtx::parse("c3d8i_k.sti", &imp.stiffness)
        .map_err(|e| failed(e.to_string()))?
        .matrix;
    let m = mtx::parse("c3d8i_k.mas", &imp.mass)
        .map_err(|e| failed(e.to_string()))?
        .matrix;
    // The deck's nodes are 1..=n; ccx numbers the bubble nodes after them.
    let n = mesh.nodes.len();
    let is_corner = |r: usize| rows[r].point.parse::<usize>().is_ok_and(|id| id <= n);
    let (corner, bubble): (Vec<usize>, Vec<usize>) = (0..rows.len()).partition(|&r| is_corner(r));
    if bubble.is_empty() {
        return Err(failed("no bubble DOFs in ccx's matrices".into()));
    }
    let sub = |a: &DMatrix<f64>, r: &[usize], c: &[usize]| {
        DMatrix::from_fn(r.len(), c.len(), |i, j| a[(r[i], c[j])])
    };
    let kbb = sub(&k, &bubble, &bubble)
        .cholesky()
        .ok_or_else(|| failed("bubble stiffness not positive definite".into()))?;
    let kbc = sub(&k, &bubble, &corner);
    let kc = sub(&k, &corner, &corner) - kbc.transpose() * kbb.solve(&kbc);
    let kc = (&kc + kc.transpose()) * 0.5;
    let massless = generalized_frequencies(kc, sub(&m, &corner, &corner), CASE_MODES)?;
    Ok(C3d8iFrequencies {
        ours,
        ccx: ccx_own,
        ccx_matrices: frequencies_singular_mass(&k, &m)
            .ok_or_else(|| failed("ccx's stiffness is not positive definite".into()))?,
        ccx_massless_bubbles: massless,
    })
}

/// The lowest [`CASE_MODES`] frequencies (Hz) of K φ = ω² M φ with K positive definite
/// and M only semidefinite (ccx's M is singular): the largest eigenvalues 1/ω² of
/// L⁻¹ M L⁻ᵀ, K = L Lᵀ.
fn frequencies_singular_mass(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Option<Vec<f64>> {
    let l = k.clone().cholesky()?.l();
    let linv = l.try_inverse()?;
    let a = &linv * m * linv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let mut mu: Vec<f64> = a.symmetric_eigenvalues().iter().copied().collect();
    mu.sort_by(|x, y| y.total_cmp(x));
    Some(
        mu.into_iter()
            .take(CASE_MODES)
            .map(|x| 1.0 / (x.max(f64::MIN_POSITIVE).sqrt() * 2.0 * std::f64::consts::PI))
            .collect(),
    )
}
