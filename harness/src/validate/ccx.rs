//! CalculiX (`ccx`, Debian package calculix-ccx) as the reference FE code: writes
//! Abaqus-format decks of [`SolidMesh`]es, runs `ccx` and reads its `*FREQUENCY`
//! eigenfrequencies from the .dat file; and the same eigenproblem solved densely with
//! this crate's elements, for comparisons on the same mesh.

use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

use nalgebra::DMatrix;
use thiserror::Error;

use crate::fe::elements::box_mesh::SolidMesh;
use crate::fe::elements::ElementError;
use crate::fe::mesh::Material;

/// Errors of running ccx or of the dense reference solve.
#[derive(Debug, Error)]
pub enum CcxError {
    #[error(
        "ccx could not be started ({0}); Debian: apt-get install calculix-ccx (scripts/deps.sh)"
    )]
    Missing(std::io::Error),
    #[error("ccx failed on {job}: {why}")]
    Failed { job: String, why: String },
    #[error("io error in {path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error(transparent)]
    Element(#[from] ElementError),
    #[error("the mass matrix is not positive definite")]
    Mass,
}

/// Why ccx cannot run here, if it cannot.
pub fn ccx_missing() -> Option<String> {
    match Command::new("ccx").arg("-v").output() {
        Ok(_) => None,
        Err(e) => Some(format!(
            "ccx not found ({e}); Debian: calculix-ccx (scripts/deps.sh)"
        )),
    }
}

/// An Abaqus-format deck of `mesh` (node and element ids 1-based in mesh order, element
/// set ALL, material STEEL), with the nodes `fixed` (0-based) held in x, y, z (node set
/// FIXED) and one `*FREQUENCY` step asking for `modes` eigenpairs.
pub fn frequency_deck(mesh: &SolidMesh, mat: &Material, fixed: &[usize], modes: usize) -> String {
    let mut s = String::from("*HEADING\nbox mesh, frequency step\n*NODE, NSET=NALL\n");
    for (i, p) in mesh.nodes.iter().enumerate() {
        let _ = writeln!(s, "{}, {}, {}, {}", i + 1, p[0], p[1], p[2]);
    }
    let _ = writeln!(s, "*ELEMENT, TYPE={}, ELSET=ALL", mesh.kind);
    for (e, conn) in mesh.elements.iter().enumerate() {
        // At most 16 entries per line (Abaqus): continue long connectivities.
        let mut line = format!("{}", e + 1);
        for (k, n) in conn.iter().enumerate() {
            line.push_str(if k == 15 { ",\n" } else { ", " });
            let _ = write!(line, "{}", n + 1);
        }
        s.push_str(&line);
        s.push('\n');
    }
    s.push_str("*NSET, NSET=FIXED\n");
    for chunk in fixed.chunks(16) {
        let ids: Vec<String> = chunk.iter().map(|n| (n + 1).to_string()).collect();
        let _ = writeln!(s, "{}", ids.join(", "));
    }
    let _ = writeln!(
        s,
        "*MATERIAL, NAME=STEEL\n*ELASTIC\n{:e}, {}\n*DENSITY\n{:e}\n\
         *SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n*BOUNDARY\nFIXED, 1, 3\n\
         *STEP\n*FREQUENCY\n{modes}\n*END STEP",
        mat.youngs_modulus, mat.poisson_ratio, mat.density
    );
    s
}

/// Runs `ccx` on `deck` as job `job` in directory `dir` and returns the eigenfrequencies
/// (Hz, i.e. cycles per time unit of the deck) from the .dat file.
pub fn run_frequencies(deck: &str, dir: &Path, job: &str) -> Result<Vec<f64>, CcxError> {
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |source| CcxError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let inp = dir.join(format!("{job}.inp"));
    std::fs::write(&inp, deck).map_err(io(&inp))?;
    let out = Command::new("ccx")
        .arg("-i")
        .arg(job)
        .current_dir(dir)
        .env("OMP_NUM_THREADS", "1")
        .output()
        .map_err(CcxError::Missing)?;
    let log = String::from_utf8_lossy(&out.stdout);
    let failed = |why: String| CcxError::Failed {
        job: job.to_string(),
        why,
    };
    if let Some(line) = log.lines().find(|l| l.contains("*ERROR")) {
        return Err(failed(line.trim().to_string()));
    }
    let dat = dir.join(format!("{job}.dat"));
    let text = std::fs::read_to_string(&dat).map_err(io(&dat))?;
    let f = parse_frequencies(&text);
    if f.is_empty() {
        return Err(failed(format!("no eigenvalue table in {}", dat.display())));
    }
    Ok(f)
}

/// The CYCLES/TIME column of the .dat file's eigenvalue table.
pub fn parse_frequencies(dat: &str) -> Vec<f64> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in dat.lines() {
        if line.contains("E I G E N V A L U E   O U T P U T") {
            inside = true;
            continue;
        }
        if !inside {
            continue;
        }
        if line.contains("P A R T I C I P A T I O N") {
            break;
        }
        let cols: Vec<&str> = line.split_whitespace().collect();
        if cols.len() == 5 && cols[0].parse::<usize>().is_ok() {
            if let Ok(f) = cols[3].parse::<f64>() {
                out.push(f);
            }
        }
    }
    out
}

/// A steady-state dynamics .dat file's displacements of `node`: per frequency (the
/// blocks' "time", cycles/time) the complex amplitudes of u1…u3; ccx writes each
/// frequency's real block, then its imaginary one.
pub fn parse_steady_state(dat: &str, node: usize) -> Vec<(f64, [nalgebra::Complex<f64>; 3])> {
    let mut parts: Vec<(f64, [f64; 3])> = Vec::new();
    let mut time = None;
    for line in dat.lines() {
        let t = line.trim_start();
        if t.starts_with("displacements") {
            time = t
                .split_whitespace()
                .last()
                .and_then(|v| v.parse::<f64>().ok());
            continue;
        }
        let cols: Vec<&str> = t.split_whitespace().collect();
        if let (Some(f), 4) = (time, cols.len()) {
            if cols[0].parse::<usize>() == Ok(node) {
                let v: Vec<f64> = cols[1..].iter().filter_map(|c| c.parse().ok()).collect();
                if v.len() == 3 {
                    parts.push((f, [v[0], v[1], v[2]]));
                    time = None;
                }
            }
        }
    }
    parts
        .chunks(2)
        .filter(|c| c.len() == 2)
        .map(|c| {
            let (re, im) = (c[0].1, c[1].1);
            (
                c[0].0,
                [0, 1, 2].map(|i| nalgebra::Complex::new(re[i], im[i])),
            )
        })
        .collect()
}

/// The lowest `modes` eigenfrequencies (Hz) of `mesh` with the nodes `fixed` held, by
/// a dense generalized eigensolve with this crate's elements (small meshes only).
pub fn dense_frequencies(
    mesh: &SolidMesh,
    mat: &Material,
    fixed: &[usize],
    modes: usize,
) -> Result<Vec<f64>, CcxError> {
    let (k, m) = mesh.dense_matrices(mat)?;
    held_frequencies(mesh, k, m, fixed, modes)
}

/// The lowest `modes` eigenfrequencies (Hz) of the dense (K, M) of `mesh` with the nodes
/// `fixed` held.
fn held_frequencies(
    mesh: &SolidMesh,
    k: DMatrix<f64>,
    m: DMatrix<f64>,
    fixed: &[usize],
    modes: usize,
) -> Result<Vec<f64>, CcxError> {
    let mut held = vec![false; mesh.nodes.len()];
    fixed.iter().for_each(|&n| held[n] = true);
    let free: Vec<usize> = (0..k.nrows()).filter(|r| !held[r / 3]).collect();
    let sub =
        |a: &DMatrix<f64>| DMatrix::from_fn(free.len(), free.len(), |i, j| a[(free[i], free[j])]);
    generalized_frequencies(sub(&k), sub(&m), modes)
}

/// The lowest `modes` frequencies (Hz) of K φ = λ M φ, dense, M positive definite.
pub fn generalized_frequencies(
    kf: DMatrix<f64>,
    mf: DMatrix<f64>,
    modes: usize,
) -> Result<Vec<f64>, CcxError> {
    // K φ = λ M φ with M = L Lᵀ → (L⁻¹ K L⁻ᵀ) ψ = λ ψ.
    let l = mf.cholesky().ok_or(CcxError::Mass)?.l();
    let linv = l.clone().try_inverse().ok_or(CcxError::Mass)?;
    let a = &linv * kf * linv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let mut lam: Vec<f64> = a.symmetric_eigenvalues().iter().copied().collect();
    lam.sort_by(f64::total_cmp);
    Ok(lam
        .into_iter()
        .take(modes)
        .map(|l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect())
}

/// The element comparison case: a steel cantilever 40 × 10 × 10 mm of 4 × 2 × 2 cells
/// (tetrahedral types: 6 tetrahedra per cell, wedges: 2), interior corner nodes moved by
/// up to ±0.15 cell, clamped at x = 0; its lowest [`CASE_MODES`] eigenfrequencies (Hz)
/// by this crate's elements and by ccx, on the same mesh, in directory `dir`.
pub fn element_case(
    kind: crate::fe::elements::ElementKind,
    dir: &Path,
) -> Result<(Vec<f64>, Vec<f64>), CcxError> {
    element_case_of(kind.element(), dir)
}

/// [`element_case`] with the element routines `element` for ours (e.g. another
/// quadrature rule for the type), ccx with the type's own.
pub fn element_case_of(
    element: &dyn crate::fe::elements::SolidElement,
    dir: &Path,
) -> Result<(Vec<f64>, Vec<f64>), CcxError> {
    let kind = element.kind();
    let (mesh, mat, fixed) = case_model(kind, 0.15)?;
    let (k, m) = mesh.dense_matrices_of(element, &mat)?;
    let ours = held_frequencies(&mesh, k, m, &fixed, CASE_MODES)?;
    let deck = frequency_deck(&mesh, &mat, &fixed, CASE_MODES);
    let theirs = run_frequencies(&deck, dir, &kind.name().to_lowercase())?;
    Ok((ours, theirs))
}

/// The mesh, material and clamped nodes (x = 0) of [`element_case`], its interior
/// corners moved by up to `jitter` of a cell (0.15 there).
pub fn case_model(
    kind: crate::fe::elements::ElementKind,
    jitter: f64,
) -> Result<(SolidMesh, Material, Vec<usize>), CcxError> {
    let mesh =
        crate::fe::elements::box_mesh::box_mesh(kind, [40.0, 10.0, 10.0], [4, 2, 2], jitter, 3);
    // N, mm, s, t: E in MPa, ρ in t/mm³.
    let mat = Material::new(210_000.0, 0.3, 7.85e-9).map_err(|e| CcxError::Failed {
        job: "material".into(),
        why: e.to_string(),
    })?;
    let fixed: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&n| mesh.nodes[n][0] == 0.0)
        .collect();
    Ok((mesh, mat, fixed))
}

/// Modes compared per element type.
pub const CASE_MODES: usize = 8;
