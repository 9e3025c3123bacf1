//! Reduced or full models from any FE code (`[[matrices]]` of a scene): Matrix Market
//! files for M, K and optionally D ([`mtx`]) and the DOF list that names each row by a
//! point and a direction ([`dofs`]), read by the readers of `formats/` and checked into a
//! [`MatrixModel`]. Values are in the scene's `[units]` (M in mass, K in force/length, D in force·time/length; a generalized
//! coordinate's rows in whatever units its mode shape normalization gives).

#[cfg(test)]
mod tests;

use std::path::Path;

use nalgebra::DMatrix;

pub use crate::formats::dofs::Dof;
pub use crate::formats::{MatrixError, MatrixModel};

use crate::formats::{dofs, mtx};
use crate::input::scene::schema::{DofsSpec, MatricesSpec};
use crate::util::provenance::SourceFile;

/// Relative asymmetry |a_ij − a_ji| / max|a| above which a `general` file is refused.
pub const SYMMETRY_TOL: f64 = 1e-9;
/// Smallest pivot² / diagonal of M's Cholesky factor: below it M is not positive
/// definite enough to be a mass matrix (a row without mass, or a singular combination).
pub const MASS_PIVOT_TOL: f64 = 1e-12;

fn read_text(path: &Path) -> Result<String, MatrixError> {
    std::fs::read_to_string(path)
        .map_err(|e| MatrixError::at(&path.display().to_string(), 0, format!("cannot read: {e}")))
}

/// Reads one matrix file and checks it against the DOF list: square of the list's size,
/// symmetric (a `general` file to [`SYMMETRY_TOL`]), finite.
fn matrix(
    path: &Path,
    what: &str,
    dofs: &[Dof],
    dofs_file: &str,
) -> Result<DMatrix<f64>, MatrixError> {
    let file = path.display().to_string();
    let r = mtx::parse(&file, &read_text(path)?)?;
    let n = r.matrix.nrows();
    if n != dofs.len() {
        return Err(MatrixError::at(
            &file,
            r.size_line,
            format!(
                "{what} is {n} × {n}, the DOF list ({dofs_file}) has {} rows",
                dofs.len()
            ),
        ));
    }
    if !r.symmetric {
        let scale = r.matrix.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for j in 0..n {
            for i in j + 1..n {
                let (a, b) = (r.matrix[(i, j)], r.matrix[(j, i)]);
                if (a - b).abs() > SYMMETRY_TOL * scale {
                    let line = r.lines[(i, j)].max(r.lines[(j, i)]) as usize;
                    return Err(MatrixError::at(
                        &file,
                        line,
                        format!(
                            "{what} is not symmetric: ({}, {}) = {a:e} but ({}, {}) = {b:e} (rows {} and {})",
                            i + 1,
                            j + 1,
                            j + 1,
                            i + 1,
                            dofs[i].name(),
                            dofs[j].name()
                        ),
                    ));
                }
            }
        }
    }
    Ok(r.matrix)
}

/// The files of `[[matrices]]` entries (M, K, D, the DOF list; paths relative to `dir`)
/// as read for run.json's `inputs`; one that cannot be read is left to [`load`] to name.
pub fn sources(specs: &[MatricesSpec], dir: &Path) -> Vec<SourceFile> {
    let files = specs.iter().flat_map(|m| {
        let dofs = match &m.dofs {
            DofsSpec::File(f) => Some(f),
            DofsSpec::Inline(_) => None,
        };
        [Some(&m.mass), Some(&m.stiffness), m.damping.as_ref(), dofs]
            .into_iter()
            .flatten()
    });
    files
        .filter_map(|f| {
            let p = dir.join(f);
            let bytes = std::fs::read(&p).ok()?;
            Some(SourceFile::of(&p.display().to_string(), &bytes))
        })
        .collect()
}

/// Reads a `[[matrices]]` entry; paths are relative to `dir` (the scene's directory).
pub fn load(spec: &MatricesSpec, dir: &Path) -> Result<MatrixModel, MatrixError> {
    let (dofs, dofs_file) = match &spec.dofs {
        DofsSpec::File(f) => {
            let p = dir.join(f);
            let file = p.display().to_string();
            (dofs::parse(&file, &read_text(&p)?)?, file)
        }
        DofsSpec::Inline(list) => {
            let file = format!("matrices `{}` dofs", spec.name);
            let lines = list.iter().enumerate().map(|(i, l)| (i + 1, l.as_str()));
            (dofs::parse_lines(&file, lines)?, file)
        }
    };
    let m_path = dir.join(&spec.mass);
    let m = matrix(&m_path, "M", &dofs, &dofs_file)?;
    let k = matrix(&dir.join(&spec.stiffness), "K", &dofs, &dofs_file)?;
    let d = match &spec.damping {
        Some(f) => Some(matrix(&dir.join(f), "D", &dofs, &dofs_file)?),
        None => None,
    };
    positive_mass(&m, &dofs, &m_path.display().to_string())?;
    Ok(MatrixModel {
        name: spec.name.clone(),
        dofs,
        m,
        k,
        d,
    })
}

/// M must be positive definite: a Cholesky factor whose every pivot² is at least
/// [`MASS_PIVOT_TOL`] of its diagonal entry.
fn positive_mass(m: &DMatrix<f64>, dofs: &[Dof], file: &str) -> Result<(), MatrixError> {
    let n = m.nrows();
    let mut l = DMatrix::<f64>::zeros(n, n);
    for j in 0..n {
        let s = m[(j, j)] - (0..j).map(|k| l[(j, k)] * l[(j, k)]).sum::<f64>();
        if s.is_nan() || s <= MASS_PIVOT_TOL * m[(j, j)].abs() || m[(j, j)] <= 0.0 {
            return Err(MatrixError::at(
                file,
                0,
                format!(
                    "M is not positive definite: row {} ({}) has no mass of its own (Cholesky pivot {s:e}, diagonal {:e}); every row needs mass, a massless row is to be condensed out (Guyan) before export",
                    j + 1,
                    dofs[j].name(),
                    m[(j, j)]
                ),
            ));
        }
        l[(j, j)] = s.sqrt();
        for i in j + 1..n {
            let v = m[(i, j)] - (0..j).map(|k| l[(i, k)] * l[(j, k)]).sum::<f64>();
            l[(i, j)] = v / l[(j, j)];
        }
    }
    Ok(())
}
