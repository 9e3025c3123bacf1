//! Writes the Craig–Bampton model of `scenes/beam-cb.toml` into `scenes/beam-cb/`
//! (K.mtx, M.mtx, dofs.csv): CalculiX's stiffness and mass matrices of a steel
//! cantilever 100 × 10 × 5 mm (C3D8, `*FREQUENCY, SOLVER=MATRIXSTORAGE`, read by the
//! importer of `jointlin matrices import-ccx`), reduced onto the tip and mid-span nodes
//! and 12 fixed-interface modes (`model::craig_bampton`). Needs ccx (scripts/deps.sh).
//!
//! `cargo run --release -p jointlin-harness --example beam_cb [-- OUT_DIR]`

use std::path::PathBuf;

use jointlin_harness::validate::matrices_ccx;

/// Fixed-interface modes kept.
const MODES: usize = 12;

fn main() -> Result<(), String> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes/beam-cb"));
    let work = std::env::temp_dir().join(format!("jointlin-beam-cb-{}", std::process::id()));
    let full = matrices_ccx::full_model(&work)?;
    let cb = matrices_ccx::craig_bampton(&full, MODES)?;
    std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    for (name, text) in [
        ("K.mtx", &cb.stiffness),
        ("M.mtx", &cb.mass),
        ("dofs.csv", &cb.dofs),
    ] {
        let p = out.join(name);
        std::fs::write(&p, text).map_err(|e| format!("{}: {e}", p.display()))?;
        eprintln!("wrote {}", p.display());
    }
    let _ = std::fs::remove_dir_all(&work);
    eprintln!("{} full DOFs reduced to {}", full.dofs.len(), cb.k.nrows());
    Ok(())
}
