//! The bolted lap's sweep as the README states it (`jointlin run scenes/bolted-lap.toml`:
//! 21 456 DOFs, 71 frequencies, and the sweep without contact damping; about 20 min on a
//! 2-core machine, so ignored: `cargo test --release -p jointlin-harness --test
//! bolted_lap -- --ignored`). Its fast stand-ins: `deck_gmsh.rs` (the same deck's
//! reading, preload and modes against CalculiX) and `modal_ccx.rs` (its sweep's route).

use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

/// results.csv-style rows as column → field.
fn rows(path: &Path) -> Vec<HashMap<String, String>> {
    let mut r = csv::Reader::from_path(path).unwrap();
    r.deserialize().map(|x| x.unwrap()).collect()
}

/// The values of VTU point-data array `name` in `vtu` (ASCII).
fn array(vtu: &str, name: &str) -> Vec<f64> {
    let at = vtu
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no {name}"));
    let body = &vtu[at..];
    let start = body.find('>').unwrap() + 1;
    let end = body.find("</DataArray>").unwrap();
    body[start..end]
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

#[test]
#[ignore = "the bolted lap's two sweeps take about 20 minutes"]
fn the_bolted_lap_sweeps_as_the_readme_states() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::env::temp_dir().join(format!("jointlin-bolted-lap-{}", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["run", "scenes/bolted-lap.toml", "--quiet", "--out"])
        .arg(&out)
        .current_dir(&root)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // 21 456 free DOFs; the preload closes 169 of the 360 points, which carry 11 099 N.
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("run.json")).unwrap()).unwrap();
    let model = &run["model"];
    assert_eq!(model["free_dofs"], 21456);
    assert_eq!(
        (
            model["contact_points"].as_u64(),
            model["closed_points"].as_u64()
        ),
        (Some(360), Some(169))
    );
    let force = run["static_step"]["total_contact_force"].as_f64().unwrap();
    assert!((force - 11099.0).abs() < 0.5, "{force} N");
    // The tip's 12.8 mm on a 5 mm plate: linear kinematics said not to hold.
    let notes = run["notes"].as_array().unwrap();
    assert!(
        notes.len() == 1
            && notes[0]
                .as_str()
                .unwrap()
                .contains("the part it sits on (5.0")
            && notes[0]
                .as_str()
                .unwrap()
                .contains("linear kinematics may no longer hold"),
        "{notes:?}"
    );
    // 71 of 71 converged; the tip rises from 6.99 to 12.8 mm between 139.375 and
    // 139.425 Hz, the sweep's peak.
    let r = rows(&out.join("results.csv"));
    assert_eq!(r.len(), 71);
    assert!(r.iter().all(|x| x["status"] == "converged"));
    let tip = |x: &HashMap<String, String>| x["TIP_39_u3_amp_mm"].parse::<f64>().unwrap();
    let at = |f: &str| {
        r.iter()
            .find(|x| x["frequency_Hz"].parse::<f64>().unwrap() == f.parse::<f64>().unwrap())
            .map(tip)
            .unwrap()
    };
    assert!((at("139.375") - 6.99).abs() < 0.005, "{}", at("139.375"));
    assert!((at("139.425") - 12.8).abs() < 0.05, "{}", at("139.425"));
    let peak = r.iter().map(tip).fold(0.0, f64::max);
    assert_eq!(peak, at("139.425"));
    // Without contact damping: up to 20.6 mm, two frequencies not converged.
    let free = rows(&out.join("results_without_contact_damping.csv"));
    let reached = free
        .iter()
        .filter(|x| !x["TIP_39_u3_amp_mm"].is_empty())
        .map(tip)
        .fold(0.0, f64::max);
    assert!((reached - 20.6).abs() < 0.05, "{reached}");
    assert_eq!(
        free.iter()
            .filter(|x| x["status"] == "not_converged")
            .count(),
        2
    );
    // At the peak every closed point but one slides (A/δ* > 1): counted on the field's
    // nodes, both sides of each point.
    let vtu = std::fs::read_to_string(out.join("field_139.4250_Hz.vtu")).unwrap();
    let pressure = array(&vtu, "contact_pressure_N_per_mm2");
    let ratio = array(&vtu, "contact_amplitude_ratio");
    let closed: Vec<usize> = (0..pressure.len()).filter(|&i| pressure[i] > 0.0).collect();
    let sliding = closed.iter().filter(|&&i| ratio[i] > 1.0).count();
    assert_eq!((closed.len(), sliding), (2 * 169, 2 * 168));
    let _ = std::fs::remove_dir_all(&out);
}
