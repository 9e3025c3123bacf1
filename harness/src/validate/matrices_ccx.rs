//! `[[matrices]]` against CalculiX: a steel cantilever 100 × 10 × 5 mm of 10 × 2 × 1
//! C3D8 elements (clamped at x = 0) whose stiffness and mass matrices ccx writes
//! (`*FREQUENCY, SOLVER=MATRIXSTORAGE`) and whose modes ccx computes (`*FREQUENCY`); and
//! its Craig–Bampton reduction onto the tip and mid-span nodes and a few fixed-interface
//! modes, the model of `scenes/beam-cb.toml`
//! (`cargo run --release -p jointlin-harness --example beam_cb` writes it).

use std::fmt::Write as _;
use std::path::Path;

use nalgebra::DMatrix;

use super::mesh_cards::mesh_cards;
use crate::fe::elements::box_mesh::box_mesh;
use crate::fe::elements::ElementKind;
use crate::formats::{ccx, dofs, mtx, MatrixModel};
use crate::model::craig_bampton;

/// Elements along x, y, z and the beam's size (mm).
pub const DIVISIONS: [usize; 3] = [10, 2, 1];
pub const SIZE: [f64; 3] = [100.0, 10.0, 5.0];

/// The deck's node id of grid node (i, j, k).
pub fn node_id(i: usize, j: usize, k: usize) -> usize {
    let [nx, ny, _] = DIVISIONS;
    1 + i + (nx + 1) * (j + (ny + 1) * k)
}

/// The tip node (x = 100, y = 0, z = 0) and the mid-span node (x = 50, y = 0, z = 0).
pub fn tip_node() -> usize {
    node_id(DIVISIONS[0], 0, 0)
}
pub fn mid_node() -> usize {
    node_id(DIVISIONS[0] / 2, 0, 0)
}

/// The beam deck with `step` (the lines from `*STEP` to `*END STEP`); units N, mm, s, t.
/// Node ids follow [`node_id`] (the mesh's node order).
pub fn deck(step: &str) -> String {
    let [_, ny, nz] = DIVISIONS;
    let m = box_mesh(ElementKind::C3D8, SIZE, DIVISIONS, 0.0, 0);
    let mut s = String::from("*HEADING\nsteel cantilever 100 x 10 x 5 mm, C3D8\n");
    mesh_cards(&mut s, &m, "EALL", (0, 0), [0.0; 3]);
    s.push_str("*NSET, NSET=ROOT\n");
    for k in 0..=nz {
        for j in 0..=ny {
            writeln!(s, "{},", node_id(0, j, k)).expect("string");
        }
    }
    s.push_str(
        "*BOUNDARY\nROOT, 1, 3\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n7.85e-9\n\
         *SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n",
    );
    s.push_str(step);
    s
}

/// Runs ccx's matrix storage on the beam in `dir` (job `beam_k`) and reads the free
/// DOFs' K and M through the importer, as a `[[matrices]]` model would be.
pub fn full_model(dir: &Path) -> Result<MatrixModel, String> {
    let deck = deck("*STEP\n*FREQUENCY, SOLVER=MATRIXSTORAGE\n*END STEP\n");
    // run_frequencies fails on the missing eigenvalue table only after ccx ran.
    match super::ccx::run_frequencies(&deck, dir, "beam_k") {
        Err(super::ccx::CcxError::Failed { why, .. }) if why.starts_with("no eigenvalue") => {}
        Err(e) => return Err(e.to_string()),
        Ok(_) => {}
    }
    let imp = ccx::import(&dir.join("beam_k")).map_err(|e| e.to_string())?;
    let file = "import";
    let rows = dofs::parse(file, &imp.dofs).map_err(|e| e.to_string())?;
    let k = mtx::parse(file, &imp.stiffness)
        .map_err(|e| e.to_string())?
        .matrix;
    let m = mtx::parse(file, &imp.mass)
        .map_err(|e| e.to_string())?
        .matrix;
    Ok(MatrixModel {
        name: "beam".into(),
        dofs: rows,
        m,
        k,
        d: None,
    })
}

/// ccx's lowest `n` eigenfrequencies of the beam (Hz).
pub fn ccx_frequencies(dir: &Path, n: usize) -> Result<Vec<f64>, String> {
    let deck = deck(&format!("*STEP\n*FREQUENCY\n{n}\n*END STEP\n"));
    super::ccx::run_frequencies(&deck, dir, "beam_f").map_err(|e| e.to_string())
}

/// The rows of node `node` (x, y, z) in `model`.
pub fn rows_of(model: &MatrixModel, node: usize) -> Vec<usize> {
    let p = node.to_string();
    (0..3)
        .filter_map(|a| {
            model
                .dofs
                .iter()
                .position(|d| d.point == p && d.axis == Some(a))
        })
        .collect()
}

/// The Craig–Bampton model: boundary rows `tip,x|y|z`, `mid,x|y|z`, then `modal,1…`.
pub struct CbFiles {
    pub stiffness: String,
    pub mass: String,
    pub dofs: String,
    pub k: DMatrix<f64>,
    pub m: DMatrix<f64>,
}

/// Reduces the full beam onto its tip and mid-span nodes and `modes` fixed-interface
/// modes, as Matrix Market text and a DOF list.
pub fn craig_bampton(full: &MatrixModel, modes: usize) -> Result<CbFiles, String> {
    let mut boundary = rows_of(full, tip_node());
    boundary.extend(rows_of(full, mid_node()));
    let r = craig_bampton::reduce(&full.k, &full.m, &boundary, modes)?;
    let mut dofs = String::from("point,direction\n");
    for p in ["tip", "mid"] {
        for a in ["x", "y", "z"] {
            writeln!(dofs, "{p},{a}").expect("string");
        }
    }
    for q in 1..=modes {
        writeln!(dofs, "modal,{q}").expect("string");
    }
    let note = |what: &str| {
        format!(
            "{what} of the Craig-Bampton reduction of a steel cantilever 100 x 10 x 5 mm (CalculiX C3D8,\n\
             10 x 2 x 1 elements) onto its tip and mid-span nodes and {modes} fixed-interface modes;\n\
             units N, mm, s, t; cargo run --release -p jointlin-harness --example beam_cb"
        )
    };
    Ok(CbFiles {
        stiffness: mtx::write_symmetric(&r.k, &note("stiffness K")),
        mass: mtx::write_symmetric(&r.m, &note("mass M")),
        dofs,
        k: r.k,
        m: r.m,
    })
}
