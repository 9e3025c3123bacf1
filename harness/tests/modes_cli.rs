//! `jointlin modes`: the default count covers the sweep's band, the outputs carry the
//! scene's units, and modes.vtu reads back (Python's XML parser) with the mesh's node
//! count and the CSV's modes.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A steel cantilever 100 × 4 × 6 mm, clamped at x = 0, in N, mm and `time`
/// (`mass` = N·time²/mm: t for s, g for ms; ρ = 7.85e-9 t/mm³ = 7.85e-3 g/mm³), swept up
/// to `f_max` (1/time).
fn beam_scene(time: &str, mass: &str, rho: f64, f_max: f64) -> String {
    format!(
        r#"
title = "cantilever"
[units]
length = "mm"
force = "N"
time = "{time}"
mass = "{mass}"
[materials.steel]
E = 210000.0
nu = 0.3
rho = {rho:e}
[[bodies]]
name = "beam"
kind = "box"
origin = [0.0, 0.0, 0.0]
size = [100.0, 4.0, 6.0]
divisions = [20, 2, 2]
material = "steel"
[[clamp]]
body = "beam"
face = "x_min"
[[excitation]]
kind = "point"
body = "beam"
at = [100.0, 2.0, 3.0]
direction = [0.0, 1.0, 0.0]
amplitude = 1.0
[sweep]
f_min = {f_min:e}
f_max = {f_max:e}
count = 2
[[outputs]]
name = "tip"
body = "beam"
at = [100.0, 2.0, 3.0]
direction = [0.0, 1.0, 0.0]
"#,
        f_min = 0.5 * f_max
    )
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-modes-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `jointlin modes` with `args`; returns stdout, panics on failure.
fn modes(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .arg("modes")
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn csv_rows(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], rows: &[Vec<String>], name: &str) -> Vec<String> {
    let i = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
    rows.iter().map(|r| r[i].clone()).collect()
}

fn floats(v: &[String]) -> Vec<f64> {
    v.iter().map(|s| s.parse().unwrap()).collect()
}

/// The same beam in seconds and in milliseconds: headers in each scene's units, the
/// frequencies 1000 times apart, the effective masses 1e6 times (t vs g).
#[test]
fn outputs_follow_the_scene_units() {
    let dir = tmp("units");
    // Band top 3 kHz: 1.5 × 3 kHz covers the first bending pairs only.
    let s_scene = dir.join("beam_s.toml");
    let ms_scene = dir.join("beam_ms.toml");
    std::fs::write(&s_scene, beam_scene("s", "t", 7.85e-9, 3000.0)).unwrap();
    std::fs::write(&ms_scene, beam_scene("ms", "g", 7.85e-3, 3.0)).unwrap();
    let (out_s, out_ms) = (dir.join("s"), dir.join("ms"));
    let table_s = modes(&[s_scene.to_str().unwrap(), "--out", out_s.to_str().unwrap()]);
    let table_ms = modes(&[
        ms_scene.to_str().unwrap(),
        "--out",
        out_ms.to_str().unwrap(),
    ]);
    assert!(table_s.contains("| frequency (Hz) |"), "{table_s}");
    assert!(table_s.contains("| m_eff,x (t) |"), "{table_s}");
    assert!(table_ms.contains("| frequency (1/ms) |"), "{table_ms}");
    assert!(table_ms.contains("| m_eff,x (g) |"), "{table_ms}");

    let (hs, rs) = csv_rows(&out_s.join("modes.csv"));
    let (hm, rm) = csv_rows(&out_ms.join("modes.csv"));
    assert_eq!(hs[1], "frequency_Hz");
    assert_eq!(hm[1], "frequency_per_ms");
    assert!(hs.contains(&"effective_mass_z_t".to_string()), "{hs:?}");
    assert!(hm.contains(&"effective_mass_z_g".to_string()), "{hm:?}");
    assert!(
        hm.contains(&"effective_inertia_x_g_mm2".to_string()),
        "{hm:?}"
    );
    // At least 6 modes, all below 4.5 kHz but the ones the minimum adds.
    assert!(
        rs.len() >= 6 && rs.len() == rm.len(),
        "{} vs {}",
        rs.len(),
        rm.len()
    );
    let fs = floats(&column(&hs, &rs, "frequency_Hz"));
    let fm = floats(&column(&hm, &rm, "frequency_per_ms"));
    for (a, b) in fs.iter().zip(&fm) {
        approx::assert_relative_eq!(*a, 1000.0 * b, max_relative = 1e-5);
    }
    let ms = floats(&column(&hs, &rs, "effective_mass_y_t"));
    let mm = floats(&column(&hm, &rm, "effective_mass_y_g"));
    // The first mode bends in the thin direction y and carries most of the y mass.
    assert_eq!(column(&hs, &rs, "label")[0], "bending_xy");
    approx::assert_relative_eq!(1e6 * ms[0], mm[0], max_relative = 1e-5);

    check_vtu(&out_s.join("modes.vtu"), 21 * 3 * 3, &fs, "Hz");
    check_vtu(&out_ms.join("modes.vtu"), 21 * 3 * 3, &fm, "per_ms");
}

/// Reads `path` with Python's XML parser: the point count, one vector per mode named
/// with its frequency and unit, each scaled to a largest nodal magnitude of 1, zero on
/// the clamped face x = 0.
fn check_vtu(path: &Path, n_points: usize, freqs: &[f64], unit: &str) {
    let script = r#"
import sys, xml.etree.ElementTree as ET
piece = ET.parse(sys.argv[1]).getroot().find("UnstructuredGrid/Piece")
n = int(piece.get("NumberOfPoints"))
pts = [float(v) for v in piece.find("Points/DataArray").text.split()]
assert len(pts) == 3 * n
for a in piece.find("PointData").findall("DataArray"):
    v = [float(x) for x in a.text.split()]
    assert a.get("NumberOfComponents") == "3" and len(v) == 3 * n
    mags = [sum(c * c for c in v[3 * i:3 * i + 3]) ** 0.5 for i in range(n)]
    clamped = max(mags[i] for i in range(n) if pts[3 * i] == 0.0)
    print(a.get("Name"), n, max(mags), clamped)
"#;
    let out = Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(path)
        .output()
        .expect("python3 reads the VTU");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), freqs.len(), "{text}");
    for (i, (line, f)) in lines.iter().zip(freqs).enumerate() {
        let w: Vec<&str> = line.split(' ').collect();
        let name: Vec<&str> = w[0].split('_').collect();
        assert_eq!(name[0], "mode");
        assert_eq!(name[1], (i + 1).to_string());
        approx::assert_relative_eq!(name[2].parse::<f64>().unwrap(), *f, max_relative = 1e-6);
        assert_eq!(name[3..].join("_"), unit);
        assert_eq!(w[1].parse::<usize>().unwrap(), n_points);
        approx::assert_relative_eq!(w[2].parse::<f64>().unwrap(), 1.0, max_relative = 1e-8);
        assert_eq!(w[3].parse::<f64>().unwrap(), 0.0);
    }
}

/// The knife's sweep is 30–34 kHz; its 31.7 kHz longitudinal mode is the 9th, beyond
/// the 6 of a fixed count. The default (every mode below 1.5 × 34 kHz) reaches it.
#[test]
fn default_count_covers_the_knife_band() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
    let dir = tmp("knife");
    modes(&[scene.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    let (h, rows) = csv_rows(&dir.join("modes.csv"));
    let f = floats(&column(&h, &rows, "frequency_Hz"));
    let labels = column(&h, &rows, "label");
    for (fi, l) in f.iter().zip(&labels) {
        eprintln!("{fi} Hz {l}");
    }
    assert!(f.len() > 6 && *f.last().unwrap() < 51_000.0, "{f:?}");
    let i = f
        .iter()
        .position(|&v| (30_000.0..34_000.0).contains(&v))
        .expect("a mode in the sweep band");
    assert!(i >= 6, "the band's mode is mode {}", i + 1);
    assert_eq!(labels[i], "longitudinal_x");
}

/// `check --modes` lists the stuck modes below the sweep's top as `jointlin modes`
/// computes them (knife-coarse: 8 modes below 34 kHz, the 9th being beyond it).
#[test]
fn check_lists_the_modes_below_the_sweeps_top() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
    let dir = tmp("knife-check");
    modes(&[scene.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    let (h, rows) = csv_rows(&dir.join("modes.csv"));
    let below: Vec<f64> = floats(&column(&h, &rows, "frequency_Hz"))
        .into_iter()
        .filter(|&f| f <= 34_000.0)
        .collect();
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["check", "--modes", scene.to_str().unwrap()])
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(out.status.success(), "{said}");
    assert!(
        said.contains("model: 824 free DOFs, 30 contact points"),
        "{said}"
    );
    let line = said
        .lines()
        .find(|l| l.starts_with("stuck modes below the sweep's top 34000.00 Hz: "))
        .unwrap_or_else(|| panic!("{said}"));
    let (count, list) = line.rsplit_once(": ").unwrap().1.split_once(" — ").unwrap();
    assert_eq!(count.parse::<usize>().unwrap(), below.len(), "{line}");
    let listed: Vec<f64> = list.split(", ").map(|v| v.parse().unwrap()).collect();
    for (a, b) in listed.iter().zip(&below) {
        // Five significant digits.
        assert!((a - b).abs() <= 5e-5 * b, "{a} against {b}");
    }
}

/// three-beams-coarse held nowhere (its clamps removed): six rigid-body modes at
/// round-off (below 0.02 Hz, labelled `rigid_body`), then the flexible ones; the
/// shift-invert about 0 stopped with "projected mass matrix not positive definite".
#[test]
fn a_structure_held_nowhere_has_six_rigid_body_modes() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/three-beams-coarse.toml");
    let mut text = std::fs::read_to_string(src).unwrap();
    while let Some(i) = text.find("[[clamp]]") {
        let j = text[i + 1..]
            .find("\n[")
            .map_or(text.len(), |j| i + 1 + j + 1);
        text.replace_range(i..j, "");
    }
    let dir = tmp("free");
    let scene = dir.join("free.toml");
    std::fs::write(&scene, text).unwrap();
    modes(&[scene.to_str().unwrap(), "--out", dir.to_str().unwrap()]);
    let (h, rows) = csv_rows(&dir.join("modes.csv"));
    let f = floats(&column(&h, &rows, "frequency_Hz"));
    let labels = column(&h, &rows, "label");
    assert!(f.len() > 6, "{f:?}");
    for i in 0..6 {
        assert!(
            f[i] < 0.02 && labels[i] == "rigid_body",
            "{i}: {} {}",
            f[i],
            labels[i]
        );
    }
    assert!(
        f[6] > 1000.0 && labels[6] != "rigid_body",
        "{} {}",
        f[6],
        labels[6]
    );
}
