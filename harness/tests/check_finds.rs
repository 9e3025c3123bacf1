//! `jointlin check` finds what `jointlin run` finds before its first solve: geometry
//! (an interface's boxes apart, overlapping, listed the wrong way round, without a
//! common footprint, with faces whose nodes do not match; a tie between non-conforming
//! meshes or between boxes that do not touch) and physics (E = 1e308, the
//! `[time_domain]` table's ranges). Each case: `check` exits 2 naming `file:line:1` and
//! the key; `run` exits 2 with the same message and writes nothing.
//!
//! Before: each passed `check` and failed `run` without a location (E = 1e308 blamed a
//! "hex8 Jacobian determinant 12.5 <= 0").

use std::path::{Path, PathBuf};
use std::process::Command;

/// The upper box of scenes/hard/stiffness-ratio.toml (the lower one is the same at z = 0).
const UPPER: &str = "origin = [0.0, 0.0, 2.0]\nsize = [40.0, 10.0, 2.0]\ndivisions = [4, 2, 1]";
const TIE: &str = "[[ties]]\nbetween = [\"lower\", \"upper\"]\n\n";

/// scenes/hard/stiffness-ratio.toml with `edits` applied, in a fresh directory.
fn scene(name: &str, edits: &[(&str, &str)]) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/hard/stiffness-ratio.toml");
    let mut text = std::fs::read_to_string(src).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let dir = std::env::temp_dir().join(format!("jointlin-check-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// The 1-based line of the first line of `path` that starts with `start`.
fn line_of(path: &Path, start: &str) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines().position(|l| l.starts_with(start)).unwrap() + 1
}

/// `check` and `run` (with `run_args`) exit 2 with `file:line:1: key `key`: …`
/// containing `says`, the same message from both; `run` writes no results.
fn found(path: &Path, line: usize, key: &str, says: &str, run_args: &[&str]) {
    let p = path.to_str().unwrap();
    let out_dir = path.with_file_name("out");
    let mut messages = Vec::new();
    let mut run = vec!["run", p, "--out", out_dir.to_str().unwrap(), "--quiet"];
    run.extend_from_slice(run_args);
    for args in [vec!["check", p], run] {
        let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        let head = format!("error: {p}:{line}:1: key `{key}`: ");
        assert!(err.starts_with(&head), "{args:?}: want {head}, got {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        messages.push(err);
    }
    assert_eq!(messages[0], messages[1]);
    assert!(!out_dir.join("results.csv").exists());
}

#[test]
fn an_interface_with_a_gap_is_found_by_check() {
    let p = scene(
        "gap",
        &[("origin = [0.0, 0.0, 2.0]", "origin = [0.0, 0.0, 2.5]")],
    );
    found(
        &p,
        line_of(&p, "between"),
        "interfaces[0].between",
        "a gap of 0.5",
        &[],
    );
}

#[test]
fn overlapping_interface_bodies_are_found_by_check() {
    let p = scene(
        "overlap",
        &[("origin = [0.0, 0.0, 2.0]", "origin = [0.0, 0.0, 1.0]")],
    );
    found(
        &p,
        line_of(&p, "between"),
        "interfaces[0].between",
        "overlap by 1",
        &[],
    );
}

#[test]
fn a_reversed_interface_is_found_by_check() {
    let p = scene(
        "reversed",
        &[(
            "between = [\"lower\", \"upper\"]",
            "between = [\"upper\", \"lower\"]",
        )],
    );
    found(
        &p,
        line_of(&p, "between"),
        "interfaces[0].between",
        "reversed",
        &[],
    );
}

#[test]
fn interface_bodies_side_by_side_are_found_by_check() {
    let p = scene(
        "footprint",
        &[("origin = [0.0, 0.0, 2.0]", "origin = [50.0, 0.0, 2.0]")],
    );
    found(
        &p,
        line_of(&p, "between"),
        "interfaces[0].between",
        "do not overlap in x",
        &[],
    );
}

#[test]
fn interface_faces_whose_nodes_do_not_match_are_found_by_check() {
    let finer = UPPER.replace("[4, 2, 1]", "[3, 2, 1]");
    let p = scene("unmatched", &[(UPPER, &finer)]);
    found(
        &p,
        line_of(&p, "between"),
        "interfaces[0].between",
        "no coincident partner",
        &[],
    );
}

#[test]
fn a_non_conforming_tie_is_found_by_check() {
    let finer = UPPER.replace("[4, 2, 1]", "[3, 2, 1]");
    let tie = format!("{TIE}[[interfaces]]");
    let p = scene("tie", &[(UPPER, &finer), ("[[interfaces]]", &tie)]);
    found(
        &p,
        line_of(&p, "between"),
        "ties[0].between",
        "meshes must conform",
        &[],
    );
}

#[test]
fn a_tie_between_boxes_apart_is_found_by_check() {
    // The interface joins the boxes; the tie names a third box beside them.
    let third = "[[bodies]]\nname = \"third\"\nkind = \"box\"\norigin = [0.0, 20.0, 0.0]\nsize = [40.0, 10.0, 2.0]\ndivisions = [4, 2, 1]\nmaterial = \"steel\"\n\n";
    let tie = format!("{third}[[ties]]\nbetween = [\"lower\", \"third\"]\n\n[[interfaces]]");
    let p = scene("tiegap", &[("[[interfaces]]", &tie)]);
    found(
        &p,
        line_of(&p, "between"),
        "ties[0].between",
        "do not touch",
        &[],
    );
}

#[test]
fn a_modulus_of_1e308_is_found_by_check() {
    let p = scene("e308", &[("E = 210000.0", "E = 1e308")]);
    found(
        &p,
        line_of(&p, "E = "),
        "materials.steel.E",
        "would overflow",
        &[],
    );
}

#[test]
fn time_domain_steps_per_cycle_out_of_range_are_found_by_check() {
    for (n, v) in [("spc2", "2"), ("spc1e12", "1000000000000")] {
        let with = format!("[time_domain]\nsteps_per_cycle = {v}\n\n[sweep]");
        let p = scene(n, &[("[sweep]", &with)]);
        let line = line_of(&p, "steps_per_cycle");
        found(
            &p,
            line,
            "time_domain.steps_per_cycle",
            "must be in 8..=",
            &["--time-domain"],
        );
    }
}

#[test]
fn time_domain_alpha_out_of_range_is_found_by_check() {
    for (n, v) in [("alpha_pos", "0.05"), ("alpha_low", "-0.5")] {
        let with = format!("[time_domain]\nalpha = {v}\n\n[sweep]");
        let p = scene(n, &[("[sweep]", &with)]);
        let line = line_of(&p, "alpha =");
        found(
            &p,
            line,
            "time_domain.alpha",
            "HHT-α must be in [-1/3, 0]",
            &["--time-domain"],
        );
    }
}

#[test]
fn time_domain_max_cycles_below_min_cycles_is_found_by_check() {
    let with = "[time_domain]\nmin_cycles = 10\nmax_cycles = 5\n\n[sweep]";
    let p = scene("cycles", &[("[sweep]", with)]);
    let line = line_of(&p, "max_cycles");
    found(
        &p,
        line,
        "time_domain.max_cycles",
        "exceeds max_cycles = 5",
        &["--time-domain"],
    );
}

/// Unit names from a known list, the system consistent (mass = force·time²/length), and
/// a density far from any solid's in the stated units noted by `check` and `run`: a
/// density in kg/m³ in an N-mm-t scene gives a first mode near 0.001 Hz and no error.
#[test]
fn unit_names_are_known_and_consistent_and_implausible_densities_are_noted() {
    let path = scene(
        "unit-name",
        &[("length = \"mm\"", "length = \"millimetre\"")],
    );
    found(
        &path,
        line_of(&path, "length ="),
        "units.length",
        "unknown unit \"millimetre\"",
        &[],
    );
    let path = scene("unit-mass", &[("mass = \"t\"", "mass = \"kg\"")]);
    found(
        &path,
        line_of(&path, "mass ="),
        "units.mass",
        "\"kg\" is not force·time²/length: N·s²/mm = 1e3 kg (\"t\" or \"tonne\" or \"Mg\")",
        &[],
    );
    // kg/m³ in N-mm-t: a warning from check and run, naming both numbers.
    let path = scene("density", &[("rho = 7.85e-9", "rho = 7850.0")]);
    let p = path.to_str().unwrap();
    let out = path.with_file_name("out");
    for args in [
        vec!["check", p],
        vec![
            "run",
            p,
            "--out",
            out.to_str().unwrap(),
            "--quiet",
            "--no-plots",
        ],
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{args:?}: {err}");
        assert!(
            err.contains("warning: material steel: density 7.85e3 t/mm³ is 7.850e15 kg/m³")
                && err.contains("7.850e-9 t/mm³"),
            "{args:?}: {err}"
        );
    }
    // A deck's units comment the same way, at its line.
    let deck = path.with_file_name("unit.inp");
    std::fs::write(
        &deck,
        "*HEADING\n** jointlin units: length=mm force=N time=s mass=kg\n*NODE\n1, 0., 0., 0.\n",
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["check", deck.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("unit.inp:2: **: mass=: \"kg\" is not force·time²/length"),
        "{err}"
    );
}
