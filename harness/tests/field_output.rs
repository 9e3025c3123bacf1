//! `[field_output]`: `jointlin run` writes the displacement field and contact state at
//! the sweep's highest peaks and at named frequencies as `.vtu` files (ParaView). The
//! files are read back with an XML parser: the peaks are the results' own, the field at
//! the output's node equals the output's amplitude in results.csv, and every contact
//! node carries a regime.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-field-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// three-beams-coarse with `extra` appended, in a fresh directory.
fn scene(tag: &str, extra: &str) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/three-beams-coarse.toml");
    let text = std::fs::read_to_string(src).unwrap() + extra;
    let d = scratch(tag);
    let p = d.join("scene.toml");
    std::fs::write(&p, text).unwrap();
    p
}

fn jointlin(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A `.vtu` file's DataArrays by name (positions under "position").
fn arrays(path: &Path) -> HashMap<String, Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut out = HashMap::new();
    for part in text.split("<DataArray").skip(1) {
        let head = &part[..part.find('>').unwrap()];
        let name = head
            .split("Name=\"")
            .nth(1)
            .map(|r| r[..r.find('"').unwrap()].to_string())
            .unwrap_or_else(|| "position".into());
        let body = &part[part.find('>').unwrap() + 1..part.find("</DataArray>").unwrap()];
        let values = body
            .split_whitespace()
            .filter_map(|v| v.parse().ok())
            .collect();
        out.insert(name, values);
    }
    out
}

#[test]
fn fields_at_the_peaks_and_named_frequencies_match_the_sweep() {
    let p = scene(
        "peaks",
        "\n[field_output]\npeaks = 2\nfrequencies = [1000.0]\n",
    );
    let out = p.parent().unwrap().join("out");
    let (ok, log) = jointlin(&[
        "run",
        "--quiet",
        "--no-plots",
        "--out",
        out.to_str().unwrap(),
        p.to_str().unwrap(),
    ]);
    assert!(ok, "{log}");
    // The two highest local maxima of middle_tip (the first output) in results.csv.
    let text = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(5).map(|v| v.parse().unwrap()).collect())
        .collect();
    let mut peaks: Vec<(f64, f64)> = (1..rows.len() - 1)
        .filter(|&i| rows[i][1] > rows[i - 1][1] && rows[i][1] > rows[i + 1][1])
        .map(|i| (rows[i][1], rows[i][0]))
        .collect();
    peaks.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut want: Vec<f64> = peaks.iter().take(2).map(|p| p.1).chain([1000.0]).collect();
    want.sort_by(f64::total_cmp);
    let mut files: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("field_"))
        .collect();
    files.sort_by(|a, b| {
        let f = |n: &str| n[6..n.len() - 7].parse::<f64>().unwrap();
        f(a).total_cmp(&f(b))
    });
    assert_eq!(files.len(), 3, "{files:?}");
    for (name, f) in files.iter().zip(&want) {
        assert!(name.ends_with("_Hz.vtu"), "{name}");
        let got: f64 = name[6..name.len() - 7].parse().unwrap();
        assert!((got - f).abs() <= 1e-3 * f, "{name} against {f} Hz");
        let a = arrays(&out.join(name));
        // top_tip at (60, 5, 5), z: the field equals results.csv's amplitude there.
        let pos = &a["position"];
        let node = (0..pos.len() / 3)
            .find(|&n| {
                (pos[3 * n] - 60.0).abs() < 1e-9
                    && (pos[3 * n + 1] - 5.0).abs() < 1e-9
                    && (pos[3 * n + 2] - 5.0).abs() < 1e-9
            })
            .expect("the top_tip node");
        let uz = a["displacement_amplitude_mm"][3 * node + 2];
        let re = a["displacement_real_mm"][3 * node + 2];
        let im = a["displacement_imag_mm"][3 * node + 2];
        // The file's digits (the VTU writer's precision).
        assert!(
            (re.hypot(im) - uz).abs() <= 1e-9 * uz,
            "{name}: {re}, {im}, {uz}"
        );
        // A sweep frequency (the peaks; 1000 Hz is none): both converged to the
        // scene's tolerance (1e-3) from different starts.
        if let Some(row) = rows.iter().find(|r| (r[0] - got).abs() <= 1e-6 * got) {
            assert!(
                (uz - row[3]).abs() <= 2e-3 * row[3],
                "{name}: {uz} against {}",
                row[3]
            );
        } else {
            assert_eq!(got, 1000.0);
        }
        let regime = &a["contact_regime"];
        assert!(regime
            .iter()
            .all(|&g| [-1.0, 0.0, 1.0, 2.0, 3.0].contains(&g)));
        assert!(regime.iter().filter(|&&g| g >= 1.0).count() >= 36, "{name}");
        assert!(a["contact_amplitude_ratio"]
            .iter()
            .all(|&r| r.is_finite() && r >= 0.0));
        // The contact point data: static pressure and k* where the points are closed
        // (every one here), d* and energy ≥ 0, none elsewhere; node ids as the exported
        // deck numbers the scene's nodes.
        let contact: Vec<usize> = (0..regime.len()).filter(|&n| regime[n] >= 1.0).collect();
        for key in [
            "contact_pressure_N_per_mm2",
            "k_star_t1_N_per_mm3",
            "k_star_t2_N_per_mm3",
        ] {
            assert!(contact.iter().all(|&n| a[key][n] > 0.0), "{name}: {key}");
        }
        for key in ["d_star_t1_N_s_per_mm3", "energy_per_cycle_N_mm"] {
            assert!(
                a[key].iter().all(|&v| v.is_finite() && v >= 0.0),
                "{name}: {key}"
            );
        }
        assert!((0..regime.len())
            .filter(|&n| regime[n] < 0.0)
            .all(|n| a["contact_pressure_N_per_mm2"][n] == 0.0));
        let ids = &a["node_id"];
        assert!((0..ids.len()).all(|n| ids[n] == (n + 1) as f64));
    }
    // fields.pvd: the three files as a series over frequency (Hz).
    let pvd = std::fs::read_to_string(out.join("fields.pvd")).unwrap();
    for name in &files {
        let got: f64 = name[6..name.len() - 7].parse().unwrap();
        let line = pvd
            .lines()
            .find(|l| l.contains(&format!("file=\"{name}\"")))
            .unwrap_or_else(|| panic!("{name} not in {pvd}"));
        let t: f64 = line
            .split("timestep=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!((t - got).abs() <= 1e-3 * got, "{line}");
    }
}

#[test]
fn field_output_rules_are_checked_at_their_keys() {
    for (extra, key) in [
        ("\n[field_output]\npeaks = 21\n", "field_output.peaks"),
        (
            "\n[field_output]\nfrequencies = [-5.0]\n",
            "field_output.frequencies[0]",
        ),
    ] {
        let p = scene("rules", extra);
        let (ok, log) = jointlin(&["check", p.to_str().unwrap()]);
        assert!(
            !ok && log.contains(&format!("key `{key}`")),
            "{extra}: {log}"
        );
    }
    let p = scene("hb", "\n[field_output]\npeaks = 1\n");
    let (ok, log) = jointlin(&[
        "run",
        "--quiet",
        "--mode",
        "harmonic-balance",
        "--harmonics",
        "3",
        "--out",
        "/dev/null/x",
        p.to_str().unwrap(),
    ]);
    assert!(
        !ok && log.contains("`field_output`") && log.contains("first order"),
        "{log}"
    );
}

/// With plots, each field frequency gets its contact maps: one circle per contact point
/// in the energy map, one more ring per sliding point in the A/δ* map, axes in the
/// interface's plane with the scene's length unit.
#[test]
fn contact_maps_at_the_field_frequencies() {
    // 0.5 N at the tip: the beams' ends slide at the first resonance.
    let p = scene("maps", "\n[field_output]\npeaks = 1\n");
    let text = std::fs::read_to_string(&p).unwrap();
    let louder = text.replacen("\namplitude = 0.05 ", "\namplitude = 0.5 ", 1);
    assert_ne!(text, louder);
    std::fs::write(&p, louder).unwrap();
    let out = p.parent().unwrap().join("out");
    let (ok, log) = jointlin(&[
        "run",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        p.to_str().unwrap(),
    ]);
    assert!(ok, "{log}");
    // "…: 1234 free DOFs, 90 contact points (72 closed), mode fast"
    let points: usize = log
        .split(" contact points")
        .next()
        .and_then(|h| h.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .expect("the contact point count in the log");
    let field = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .find(|n| n.starts_with("field_"))
        .expect("a field file");
    let tag = &field["field_".len()..field.len() - ".vtu".len()];
    let energy = std::fs::read_to_string(out.join(format!("contact_energy_{tag}.svg"))).unwrap();
    let ratio = std::fs::read_to_string(out.join(format!("contact_ratio_{tag}.svg"))).unwrap();
    // A dot per point, and in the legend column two size keys and the open point's
    // dot (the ratio map's also the sliding ring).
    assert_eq!(energy.matches("<circle").count(), points + 3, "energy map");
    let rings = ratio.matches("<circle").count() - points - 4;
    let sliding = arrays(&out.join(&field))["contact_amplitude_ratio"]
        .iter()
        .filter(|&&r| r > 1.0)
        .count();
    // A ring per sliding point; the field's per-node ratio counts both nodes of each
    // (the beams share no contact node).
    assert!(
        rings > 0 && 2 * rings == sliding,
        "{rings} rings, {sliding} sliding nodes"
    );
    for svg in [&energy, &ratio] {
        assert!(svg.contains("x [mm]") && svg.contains("y [mm]"));
        assert!(
            svg.contains(&tag.replace('_', " ")),
            "the frequency in the title"
        );
    }
    assert!(
        energy.contains("E/A [N/mm]"),
        "the energy density's colour bar and unit"
    );
    assert!(
        ratio.contains("≥ 10") && ratio.contains("≤ 0.001"),
        "A/δ* on a log bar"
    );
    for svg in [&energy, &ratio] {
        assert!(svg.contains("open (no pressure)"), "open points explained");
    }
}
