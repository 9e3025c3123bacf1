//! `[[matrices]]` against CalculiX (validate::matrices_ccx): a steel cantilever
//! 100 × 10 × 5 mm, C3D8, whose K and M ccx writes (`*FREQUENCY, SOLVER=MATRIXSTORAGE`)
//! and `jointlin matrices import-ccx` converts; its Craig–Bampton reduction onto the tip
//! and mid-span nodes, as scenes/beam-cb.toml drives it.
//!
//! Skipped with a printed reason where ccx is missing, except under CI=true.

#[path = "../../tests/tools/mod.rs"]
mod tools;

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use jointlin_harness::input::scene::Scene;
use jointlin_harness::model::lumped;
use jointlin_harness::validate::ccx::ccx_missing;
use jointlin_harness::validate::matrices_ccx::{self as beam, ccx_frequencies, full_model};

fn ccx_here() -> bool {
    if let Some(why) = ccx_missing() {
        tools::missing("matrices_ccx", "ccx", &why);
        return false;
    }
    true
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("jointlin-{name}-{}", std::process::id()))
}

/// Stuck-joint frequencies (Hz) of a scene's lumped system, ascending.
fn frequencies(scene: &Scene) -> Vec<f64> {
    lumped::build(scene).unwrap().stuck_frequencies().unwrap()
}

const UNITS: &str = "[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n";

/// A scene on the matrices in `dir` (K.mtx, M.mtx, dofs.csv), with `extra` tables.
fn scene_text(extra: &str, load_point: &str) -> String {
    format!(
        "{UNITS}[[matrices]]\nname = \"beam\"\nmass = \"M.mtx\"\nstiffness = \"K.mtx\"\ndofs = \"dofs.csv\"\n\
         {extra}\n[[excitation]]\nkind = \"point\"\nbody = \"beam.{load_point}\"\ndirection = [0.0, 0.0, 1.0]\namplitude = 1.0\n\
         [sweep]\nf_min = 300.0\nf_max = 2000.0\ncount = 10\n\
         [[outputs]]\nname = \"tip_z\"\nbody = \"beam.{load_point}\"\ndirection = [0.0, 0.0, 1.0]\n"
    )
}

/// `got` equals `want` word for word, each number to 1e-9 of itself plus 1e-15 of
/// `want`'s largest.
fn same_numbers(name: &str, got: &str, want: &str) {
    let words = |t: &str| -> Vec<String> {
        t.split(|c: char| c.is_whitespace() || c == ',')
            .filter(|w| !w.is_empty())
            .map(String::from)
            .collect()
    };
    let (g, w) = (words(got), words(want));
    assert_eq!(g.len(), w.len(), "{name}: word count");
    let scale = w
        .iter()
        .filter_map(|x| x.parse::<f64>().ok())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for (a, b) in g.iter().zip(&w) {
        match (a.parse::<f64>(), b.parse::<f64>()) {
            (Ok(x), Ok(y)) => assert!(
                (x - y).abs() <= 1e-9 * y.abs() + 1e-15 * scale,
                "{name}: {x} vs committed {y} (scale {scale})"
            ),
            _ => assert_eq!(a, b, "{name}"),
        }
    }
}

fn write_scene(dir: &Path, text: &str) -> Scene {
    let p = dir.join("scene.toml");
    std::fs::write(&p, text).unwrap();
    Scene::load(&p).unwrap()
}

/// (i) The full matrices ccx stores, converted by `jointlin matrices import-ccx` and read
/// as `[[matrices]]`, have ccx's own eigenfrequencies (ccx's *FREQUENCY on the same deck).
#[test]
fn imported_ccx_matrices_have_ccx_modes() {
    if !ccx_here() {
        return;
    }
    let dir = tmp("matrices-ccx");
    let _ = full_model(&dir).unwrap(); // runs ccx: beam_k.sti, .mas, .dof
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["matrices", "import-ccx"])
        .arg(dir.join("beam_k"))
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let tip = beam::tip_node();
    let scene = write_scene(&dir, &scene_text("", &tip.to_string()));
    let ours = frequencies(&scene);
    let ccx = ccx_frequencies(&dir, 6).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    eprintln!("ours {:?}\nccx  {ccx:?}", &ours[..6]);
    // ccx prints 7 significant digits.
    for (a, b) in ours.iter().zip(&ccx) {
        assert!((a / b - 1.0).abs() < 1e-6, "ours {ours:?}\nccx {ccx:?}");
    }
}

/// (ii) The Craig–Bampton model with the tip joint stuck has the low modes of the full
/// matrices with a spring k_T0 at the tip; and the first-order forced response converges at every frequency of the sweep.
#[test]
fn craig_bampton_with_joint_against_full_with_spring() {
    if !ccx_here() {
        return;
    }
    let dir = tmp("matrices-cb");
    let full = full_model(&dir).unwrap();
    let tip = beam::tip_node();
    // Full matrices with the stiff spring at the tip.
    let imp = jointlin_harness::formats::ccx::import(&dir.join("beam_k")).unwrap();
    std::fs::write(dir.join("K.mtx"), &imp.stiffness).unwrap();
    std::fs::write(dir.join("M.mtx"), &imp.mass).unwrap();
    std::fs::write(dir.join("dofs.csv"), &imp.dofs).unwrap();
    let spring = format!(
        "[[springs]]\nbody = \"beam.{tip}\"\ndirection = [0.0, 0.0, 1.0]\nstiffness = 1000.0\n"
    );
    let full_f = frequencies(&write_scene(&dir, &scene_text(&spring, &tip.to_string())));
    // The reduced model with the joint (k_T0 = 1000 N/mm) to the ground.
    let cb = beam::craig_bampton(&full, 12).unwrap();
    let cbdir = dir.join("cb");
    std::fs::create_dir_all(&cbdir).unwrap();
    std::fs::write(cbdir.join("K.mtx"), &cb.stiffness).unwrap();
    std::fs::write(cbdir.join("M.mtx"), &cb.mass).unwrap();
    std::fs::write(cbdir.join("dofs.csv"), &cb.dofs).unwrap();
    let joint = "[[joints]]\nname = \"tip\"\nbetween = [\"beam.tip\", \"ground\"]\ndirection = [0.0, 0.0, 1.0]\n\
                 law = \"mindlin\"\nmu = 0.3\nnormal_force = 10.0\nk_t0 = 1000.0\n";
    let cb_scene = write_scene(&cbdir, &scene_text(joint, "tip"));
    let cb_f = frequencies(&cb_scene);
    // scenes/beam-cb/ is this reduction as `--example beam_cb` writes it: the same text,
    // each number to 1e-9 of itself plus 1e-15 of the matrix's largest entry (ccx and the
    // eigen-solver may move the last digits between machines).
    let committed = root().join("scenes/beam-cb");
    for (name, text) in [
        ("K.mtx", &cb.stiffness),
        ("M.mtx", &cb.mass),
        ("dofs.csv", &cb.dofs),
    ] {
        let want = std::fs::read_to_string(committed.join(name)).unwrap();
        same_numbers(name, text, &want);
    }
    // The first-order forced response (k*, d* of the joint consistent with its
    // amplitude, jointlin_linearize) converges at every frequency of the sweep.
    let l = lumped::build(&cb_scene).unwrap();
    let mut a0 = vec![0.0; l.system.elements.len()];
    for f in cb_scene.frequencies() {
        let x = jointlin_harness::mhb::first_order::solve(
            &l.system,
            2.0 * std::f64::consts::PI * f,
            &a0,
        )
        .unwrap_or_else(|e| panic!("{f} Hz: {e}"));
        a0 = jointlin_harness::mhb::first_order::element_amplitudes(&l.system, &x);
        assert!(a0.iter().all(|a| a.is_finite()));
    }
    let _ = std::fs::remove_dir_all(&dir);
    eprintln!("full {:?}\ncb   {:?}", &full_f[..4], &cb_f[..4]);
    // Measured with 12 fixed-interface modes: +1.7e-5 (y bending), +1.5e-5 (z bending
    // against the tip support); the third mode +3.4e-4.
    for i in 0..2 {
        assert!(
            (cb_f[i] / full_f[i] - 1.0).abs() < 1e-4,
            "full {full_f:?}\ncb {cb_f:?}"
        );
    }
}

/// `jointlin backbone --mode 2 SCENE --out DIR --quiet`: backbone.csv's (frequency Hz,
/// damping ratio) rows.
fn backbone_rows(scene: &Path, out: &Path) -> Vec<(f64, f64)> {
    let (scene, out_dir) = (scene.to_str().unwrap(), out.to_str().unwrap());
    common::run_ok(&[
        "backbone", "--mode", "2", "--quiet", "--out", out_dir, scene,
    ]);
    common::numbers(&out.join("backbone.csv"))
        .iter()
        .map(|r| (r["frequency_Hz"], r["damping_ratio"]))
        .collect()
}

/// (iii) The unreduced matrices (180 rows) with the tip joint have the backbone of their
/// Craig–Bampton reduction (scenes/beam-cb.toml): the stuck mode of a model above the
/// dense search's size is found and traced like a reduced model's (it stopped at once,
/// "no oscillatory mode (overdamped)", when the tracking's λ jittered at round-off).
#[test]
fn unreduced_matrices_have_the_reduced_backbone() {
    if !ccx_here() {
        return;
    }
    let dir = tmp("matrices-backbone");
    let _ = full_model(&dir).unwrap();
    let imp = jointlin_harness::formats::ccx::import(&dir.join("beam_k")).unwrap();
    std::fs::write(dir.join("K.mtx"), &imp.stiffness).unwrap();
    std::fs::write(dir.join("M.mtx"), &imp.mass).unwrap();
    std::fs::write(dir.join("dofs.csv"), &imp.dofs).unwrap();
    let tip = beam::tip_node();
    let joint = format!(
        "[[joints]]\nname = \"tip\"\nbetween = [\"beam.{tip}\", \"ground\"]\ndirection = [0.0, 0.0, 1.0]\n\
         law = \"mindlin\"\nrule = \"thesis\"\nmu = 0.3\nnormal_force = 10.0\nk_t0 = 1000.0\n"
    );
    write_scene(&dir, &scene_text(&joint, &tip.to_string()));
    let full = backbone_rows(&dir.join("scene.toml"), &dir.join("bb"));
    let cb = backbone_rows(&root().join("scenes/beam-cb.toml"), &dir.join("bb-cb"));
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(full.len(), cb.len());
    let (mut df, mut dz) = (0.0f64, 0.0f64);
    for (a, b) in full.iter().zip(&cb) {
        df = df.max((b.0 / a.0 - 1.0).abs());
        dz = dz.max((b.1 - a.1).abs() / a.1.max(1e-3));
    }
    eprintln!(
        "{} amplitudes; full {:?} .. {:?}; cb differs by {df:.2e} (frequency), {dz:.2e} (damping)",
        full.len(),
        full[0],
        full[full.len() - 1]
    );
    assert!(df < 1e-4 && dz < 1e-3, "{df:e} {dz:e}");
}
