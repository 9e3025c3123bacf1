//! `*DAMPING, STRUCTURAL=s` in a deck: the run's steady state is (K(1 + i s) − ω²M) u = f
//! for the material's stiffness K, as Abaqus's direct steady-state dynamics applies it.
//! Checked on the steel cantilever of `validate::matrices_ccx` (100 × 10 × 5 mm, C3D8)
//! through its first bending resonance against a dense complex solve with CalculiX's
//! own K and M of the same mesh (`*FREQUENCY, SOLVER=MATRIXSTORAGE`): the same
//! amplitude computed independently of the harness's assembly and sweep.
//!
//! Skipped with a printed reason where ccx is missing, except under CI=true.

#[path = "../../tests/tools/mod.rs"]
mod tools;

use std::path::PathBuf;
use std::process::Command;

use nalgebra::{Complex, DMatrix, DVector};

use jointlin_harness::validate::ccx::ccx_missing;
use jointlin_harness::validate::matrices_ccx::{
    ccx_frequencies, deck, full_model, rows_of, tip_node,
};

/// The loss factor of the test.
const S: f64 = 0.02;

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-structural-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn structural_damping_is_the_complex_stiffness_of_a_direct_solve() {
    if let Some(why) = ccx_missing() {
        tools::missing("structural_damping", "ccx", &why);
        return;
    }
    let d = tmp("beam");
    let f1 = ccx_frequencies(&d, 1).unwrap()[0];
    let tip = tip_node();
    // Five frequencies across the first bending resonance, 1 N along z at the tip.
    let (lo, hi) = (0.98 * f1, 1.02 * f1);
    let step = format!(
        "*NSET, NSET=TIPN\n{tip}\n*STEP, PERTURBATION\n*STEADY STATE DYNAMICS, DIRECT, FREQUENCY SCALE=LINEAR\n{lo:?}, {hi:?}, 5\n*CLOAD\n{tip}, 3, 1.\n*NODE PRINT, NSET=TIPN\nU\n*END STEP\n"
    );
    let text = deck(&step)
        .replacen(
            "*DENSITY\n7.85e-9\n",
            &format!("*DENSITY\n7.85e-9\n*DAMPING, STRUCTURAL={S}\n"),
            1,
        )
        .replacen(
            "*HEADING\n",
            "*HEADING\n** jointlin units: length=mm force=N time=s mass=t\n",
            1,
        );
    assert!(text.contains("STRUCTURAL"));
    let inp = d.join("damped.inp");
    std::fs::write(&inp, &text).unwrap();
    let out = d.join("out");
    let run = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args([
            "run",
            inp.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            "--no-plots",
        ])
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header
        .iter()
        .position(|h| h.starts_with("TIPN_") && h.ends_with("_u3_amp_mm"))
        .unwrap_or_else(|| panic!("{header:?}"));
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();

    // The independent solve: ccx's K and M of the free DOFs, dense, complex.
    let model = full_model(&d).unwrap();
    let n = model.k.nrows();
    let z = rows_of(&model, tip)[2];
    let mut f = DVector::<Complex<f64>>::zeros(n);
    f[z] = Complex::new(1.0, 0.0);
    let mut peak: f64 = 0.0;
    for row in &rows {
        let freq: f64 = row[0].parse().unwrap();
        let w2 = (2.0 * std::f64::consts::PI * freq).powi(2);
        let a = DMatrix::from_fn(n, n, |i, j| {
            Complex::new(model.k[(i, j)] - w2 * model.m[(i, j)], S * model.k[(i, j)])
        });
        let u = a.lu().solve(&f).unwrap();
        let expected = u[z].norm();
        let got: f64 = row[col].parse().unwrap();
        eprintln!("{freq:.3} Hz: jointlin {got:.6e} mm, dense K(1 + i s) − ω²M {expected:.6e} mm");
        assert!(
            (got / expected - 1.0).abs() < 1e-6,
            "{freq} Hz: {got} vs {expected}"
        );
        peak = peak.max(got);
    }
    // At resonance the response is bounded by the loss factor alone: about
    // static / s, far above the static tip deflection and finite.
    let static_tip = {
        let u = model.k.clone().lu().solve(&f.map(|c| c.re)).unwrap();
        u[z]
    };
    assert!(
        peak.is_finite() && peak > 10.0 * static_tip,
        "{peak} vs {static_tip}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
