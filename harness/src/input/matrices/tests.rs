//! Bad matrix files and DOF lists: each a named error at file:line.

use std::path::Path;

use super::*;
use crate::formats::ccx;
use crate::input::scene::schema::{DofsSpec, MatricesSpec};

const M2: &str = "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 1.0\n2 2 2.0\n";
const K2: &str = "%%MatrixMarket matrix coordinate real general\n% a comment\n2 2 4\n1 1 2.0\n2 1 -1.0\n1 2 -1.0\n2 2 1.0\n";

/// Writes M, K and the DOF list into a fresh directory and loads them.
fn load_with(name: &str, m: &str, k: &str, dofs: &str) -> Result<MatrixModel, MatrixError> {
    let dir = std::env::temp_dir().join(format!("jointlin-mtx-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("M.mtx"), m).unwrap();
    std::fs::write(dir.join("K.mtx"), k).unwrap();
    std::fs::write(dir.join("dofs.csv"), dofs).unwrap();
    let spec = MatricesSpec {
        name: "beam".into(),
        mass: "M.mtx".into(),
        stiffness: "K.mtx".into(),
        damping: None,
        dofs: DofsSpec::File("dofs.csv".into()),
    };
    let r = load(&spec, &dir);
    let _ = std::fs::remove_dir_all(&dir);
    r
}

fn err(name: &str, m: &str, k: &str, dofs: &str) -> MatrixError {
    load_with(name, m, k, dofs).unwrap_err()
}

const DOFS2: &str = "point,direction\ntip,x\nmodal,1\n";

#[test]
fn a_good_pair_reads_both_layouts() {
    let r = load_with("good", M2, K2, DOFS2).unwrap();
    assert_eq!(r.k[(0, 1)], -1.0);
    assert_eq!(r.m[(1, 1)], 2.0);
    assert_eq!(r.dofs[0].axis, Some(0));
    assert_eq!(r.dofs[1].axis, None);
    assert_eq!(r.dofs[1].name(), "modal.1");
    // A symmetric array (as scipy.io.mmwrite writes a dense symmetric NumPy matrix).
    let arr = "%%MatrixMarket matrix array real symmetric\n2 2\n2.0\n-1.0\n1.0\n";
    let r = load_with("array", M2, arr, DOFS2).unwrap();
    assert_eq!(r.k[(0, 1)], -1.0);
    assert_eq!(r.k[(1, 0)], -1.0);
    // Written and read back exactly.
    let back = mtx::parse("w", &mtx::write_symmetric(&r.k, "c")).unwrap();
    assert_eq!(back.matrix, r.k);
}

#[test]
fn wrong_size_names_the_size_line() {
    let e = err("size", M2, K2, "tip,x\ntip,y\ntip,z\n");
    assert_eq!(e.line, 2, "{e}");
    assert!(e.file.ends_with("M.mtx"), "{e}");
    assert!(e.to_string().contains("M is 2 × 2, the DOF list"), "{e}");
    let k3 = "%%MatrixMarket matrix coordinate real general\n3 2 0\n";
    let e = err("square", M2, k3, DOFS2);
    assert!(e.file.ends_with("K.mtx") && e.line == 2, "{e}");
    assert!(e.to_string().contains("square"), "{e}");
}

#[test]
fn asymmetry_names_the_entry_line() {
    let k = K2.replace("1 2 -1.0", "1 2 -1.5");
    let e = err("asym", M2, &k, DOFS2);
    assert!(e.file.ends_with("K.mtx") && e.line == 6, "{e}");
    assert!(e.to_string().contains("not symmetric"), "{e}");
    assert!(e.to_string().contains("tip.x"), "{e}");
    // A symmetric file stores the lower triangle only.
    let upper = "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1.0\n";
    let e = err("upper", M2, upper, DOFS2);
    assert_eq!(e.line, 3, "{e}");
}

#[test]
fn nan_and_bad_numbers_name_their_line() {
    let k = K2.replace("2 2 1.0", "2 2 NaN");
    let e = err("nan", M2, &k, DOFS2);
    assert!(e.line == 7 && e.to_string().contains("not finite"), "{e}");
    let k = K2.replace("2 2 1.0", "2 2 1.0x");
    assert_eq!(err("num", M2, &k, DOFS2).line, 7);
    let k = K2.replace("2 2 1.0", "3 2 1.0");
    assert!(err("idx", M2, &k, DOFS2)
        .to_string()
        .contains("outside 1..=2"));
    let k = K2.replace("2 2 1.0", "1 1 1.0");
    assert!(err("dup", M2, &k, DOFS2)
        .to_string()
        .contains("given twice (first at line 4)"));
    let k = K2.replace("2 2 4", "2 2 5");
    assert!(err("count", M2, &k, DOFS2)
        .to_string()
        .contains("announces 5 entries"));
}

#[test]
fn missing_file_and_bad_header_are_named() {
    let spec = MatricesSpec {
        name: "beam".into(),
        mass: "none.mtx".into(),
        stiffness: "K.mtx".into(),
        damping: None,
        dofs: DofsSpec::Inline(vec!["tip,x".into(), "modal,1".into()]),
    };
    let e = load(&spec, Path::new("/nonexistent-dir")).unwrap_err();
    assert!(
        e.file.ends_with("none.mtx") && e.to_string().contains("cannot read"),
        "{e}"
    );
    let e = err(
        "header",
        "%%MatrixMarket matrix coordinate complex general\n2 2 0\n",
        K2,
        DOFS2,
    );
    assert!(e.line == 1 && e.to_string().contains("complex"), "{e}");
}

#[test]
fn mass_must_be_positive_definite() {
    let m = "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 1 1.0\n";
    let e = err("mass", m, K2, DOFS2);
    assert!(
        e.to_string()
            .contains("not positive definite: row 2 (modal.1)"),
        "{e}"
    );
}

#[test]
fn dof_lists_are_strict() {
    let e = err("dofs", M2, K2, "tip,x\ntip;y\n");
    assert!(e.file.ends_with("dofs.csv") && e.line == 2, "{e}");
    let e = err("dofs2", M2, K2, "tip,x\n# c\ntip,x\n");
    assert!(
        e.line == 3 && e.to_string().contains("first at line 1"),
        "{e}"
    );
}

#[test]
fn ccx_files_convert_to_matrix_market() {
    let dir = std::env::temp_dir().join(format!("jointlin-ccx-imp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("j.dof"), "2.1\n2.3\n").unwrap();
    std::fs::write(dir.join("j.sti"), "1 1  2.0\n1 2 -1.0\n2 2  1.0\n").unwrap();
    std::fs::write(dir.join("j.mas"), "1 1  1.0\n1 2  0.0\n2 2  2.0\n").unwrap();
    let imp = ccx::import(&dir.join("j")).unwrap();
    assert_eq!(imp.dofs, "point,direction\n2,x\n2,z\n");
    let k = mtx::parse("K", &imp.stiffness).unwrap().matrix;
    assert_eq!(
        k,
        nalgebra::DMatrix::from_row_slice(2, 2, &[2.0, -1.0, -1.0, 1.0])
    );
    std::fs::write(dir.join("j.sti"), "1 1 2.0\n2 1 -1.0\n").unwrap();
    let e = ccx::import(&dir.join("j")).unwrap_err();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(e.file.ends_with("j.sti") && e.line == 2, "{e}");
}
