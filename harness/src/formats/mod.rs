//! Other codes' file formats, independent of the scene schema: the strict Matrix Market
//! reader and writer ([`mtx`]), the DOF list that names each row of a matrices model
//! ([`dofs`]), CalculiX's matrix storage files ([`ccx`]), and what such files make
//! together: a [`MatrixModel`]. The `[[matrices]]` input (`input/matrices/`) and the
//! CalculiX comparisons (`validate/`) read them; `export::reduced` writes them.

pub mod ccx;
pub mod dofs;
pub mod mtx;

use nalgebra::DMatrix;
use thiserror::Error;

use dofs::Dof;

/// A matrix file or DOF list that cannot be used: `file:line: message` (line 0: the
/// file as a whole).
#[derive(Debug, Clone, Error, PartialEq)]
#[error("{file}{}: {message}", if *.line > 0 { format!(":{}", .line) } else { String::new() })]
pub struct MatrixError {
    pub file: String,
    pub line: usize,
    pub message: String,
}

impl MatrixError {
    pub fn at(file: &str, line: usize, message: String) -> Self {
        MatrixError {
            file: file.to_string(),
            line,
            message,
        }
    }
}

/// One matrices model (a scene's `[[matrices]]` entry, or CalculiX's matrices of a
/// deck), read and checked.
#[derive(Debug, Clone)]
pub struct MatrixModel {
    pub name: String,
    pub dofs: Vec<Dof>,
    /// Mass (mass), stiffness (force/length), damping (force·time/length), n × n.
    pub m: DMatrix<f64>,
    pub k: DMatrix<f64>,
    pub d: Option<DMatrix<f64>>,
}
