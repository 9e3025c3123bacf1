//! The README's and docs' long blocks — those whose commands take minutes, so that
//! `scripts/test.sh` checks only the short ones — regenerated and compared with what the
//! documents say (`scripts/readme-tables.sh --check`, which leaves out timings and lets a
//! number move by two units of its last printed digit). Each test is ignored; run one
//! with `cargo test --release -p jointlin-harness --test readme_blocks -- --ignored NAME`.
//! Their fast stand-ins in the default suite are named per test.

use std::path::Path;
use std::process::Command;

/// `bash scripts/readme-tables.sh --check BLOCKS…` succeeds.
fn check(blocks: &[&str]) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = Command::new("bash")
        .arg("scripts/readme-tables.sh")
        .arg("--check")
        .args(blocks)
        .current_dir(&root)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The knife's loss table (direct, and against the modal route: `knife_modal`), mesh
/// studies and effects (hours: `knife` alone about 70 min).
/// Stand-ins:
/// `knife.rs` (`lower_torque_dissipates_more_at_every_torque_and_amplitude`: knife-fast's
/// predictions against §5.5 at the README's digits, the torque trend) and the other
/// knife-coarse tests.
#[test]
#[ignore = "the knife studies take hours (knife.toml's loss table alone about 70 min)"]
fn knife_blocks() {
    check(&[
        "knife",
        "knife_modal",
        "knife_graded_mesh",
        "knife_effects",
        "knife_graded_effects",
        "knife_mesh",
    ]);
}

/// The accuracy ladders of the three-beams scenes (`tradeoff_beams` alone about 10 min).
/// Stand-ins:
/// `tradeoff_block` and `tradeoff_mass_on_plane`, checked by scripts/test.sh, and
/// `contact3d_fe.rs`'s ladder at the README's digits.
#[test]
#[ignore = "the three-beams ladders take tens of minutes"]
fn tradeoff_blocks() {
    check(&[
        "tradeoff_beams",
        "tradeoff_oblique",
        "tradeoff_oblique_coupled",
        "tradeoff_oblique_normal",
        "tradeoff_oblique_both",
        "contact_effects",
    ]);
}

/// The H = 7 FE backbone (about 5 min) and the backbones' cost table. Stand-ins:
/// `backbone_fe`, `backbone_braced` and `backbone_chain_h7`, checked by scripts/test.sh,
/// and `fe_backbone.rs`.
#[test]
#[ignore = "the H = 7 FE backbone and the cost table take minutes each"]
fn backbone_blocks() {
    check(&["backbone_fe_h7", "backbone_cost"]);
}

/// The benchmark tables: their sizes, iteration counts and errors (their timings are
/// left out, and their memory). Stand-ins: the tests each bench's rows come from
/// (`modes_ccx.rs`, `modal_ccx.rs`, `reduce_cli.rs`, `deck_gmsh.rs`).
#[test]
#[ignore = "the benchmarks take minutes each"]
fn bench_blocks() {
    check(&[
        "deck_bench",
        "modes_bench",
        "sweep_bench",
        "modal_deck_bench",
        "box_bench",
        "reduce_bench",
        "python_cost",
    ]);
}
