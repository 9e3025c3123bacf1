//! The linear isotropic elastic material of solid elements.

use crate::fe::error::MeshError;

/// Linear isotropic elastic material. Units: E in force/length² (MPa in N-mm-t),
/// ρ in mass/length³ (t/mm³ in N-mm-t); ν dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub density: f64,
}

impl Material {
    /// Checks E > 0, −1 < ν < 0.5, ρ ≥ 0 (all finite).
    pub fn new(youngs_modulus: f64, poisson_ratio: f64, density: f64) -> Result<Self, MeshError> {
        let ok = youngs_modulus.is_finite()
            && youngs_modulus > 0.0
            && poisson_ratio > -1.0
            && poisson_ratio < 0.5
            && density.is_finite()
            && density >= 0.0;
        if !ok {
            return Err(MeshError::BadMaterial {
                e: youngs_modulus,
                nu: poisson_ratio,
                rho: density,
            });
        }
        Ok(Material {
            youngs_modulus,
            poisson_ratio,
            density,
        })
    }

    /// Shear modulus G = E / (2(1+ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }
}
