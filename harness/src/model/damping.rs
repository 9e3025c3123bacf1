//! The material (Rayleigh) damping matrix of a model's elements.

use super::BuildError;
use crate::fe::assembly::{element_free_dofs, element_matrices, System};
use crate::fe::csc::Csc;
use crate::fe::mesh::Model;

/// D = Σₑ (αₑ Mₑ + βₑ Kₑ) with each element's material's Rayleigh coefficients
/// `coef[material]` = (α 1/time, β time); `None` when every α and β is zero.
pub(super) fn material_damping(
    model: &Model,
    sys: &System,
    coef: &[(f64, f64)],
) -> Result<Option<Csc<f64>>, BuildError> {
    if coef.iter().all(|&(a, b)| a == 0.0 && b == 0.0) {
        return Ok(None);
    }
    let mut d = Csc::<f64>::zeros(sys.pattern.clone());
    for (e, el) in model.elements.iter().enumerate() {
        let (alpha, beta) = coef[el.material];
        if alpha == 0.0 && beta == 0.0 {
            continue;
        }
        let (ke, me) = element_matrices(model, e)?;
        let free = element_free_dofs(model, &sys.dofs, e);
        for &(lc, c) in &free {
            for &(lr, r) in &free {
                let slot = sys.pattern.find(r, c).expect("element entry in pattern");
                d.values[slot] += alpha * me[(lr, lc)] + beta * ke[(lr, lc)];
            }
        }
    }
    Ok(Some(d))
}
