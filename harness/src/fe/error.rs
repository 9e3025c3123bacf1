//! Errors in building a mesh or model.

use thiserror::Error;

/// Errors in building a mesh or model.
#[derive(Debug, Error, PartialEq)]
pub enum MeshError {
    #[error("box size must be positive and finite, got {0:?}")]
    BadSize([f64; 3]),
    #[error("box grading ratio must be finite and at least 1, got {0}")]
    BadGrading(f64),
    #[error("box divisions must be at least 1, got {0:?}")]
    BadDivisions([usize; 3]),
    #[error("material {0} does not exist")]
    UnknownMaterial(usize),
    #[error("invalid material: E = {e} (must be > 0), nu = {nu} (must be in (-1, 0.5)), rho = {rho} (must be >= 0)")]
    BadMaterial { e: f64, nu: f64, rho: f64 },
    #[error("body {0} does not exist")]
    UnknownBody(usize),
    #[error("node {0} does not exist")]
    UnknownNode(usize),
}
