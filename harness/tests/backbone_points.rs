//! `jointlin backbone` of lumped scenes with three-direction joints (EPMC through the
//! library's point: normal load variation, lift-off, coupled slip), on the program's own
//! backbone.csv:
//!
//! - `scenes/mass-on-plane.toml`: its lowest mode slides the mass along the plane and
//!   leaves the normal force alone, so with both effects on the backbone is the thesis
//!   model's (the effects off: two 1D Jenkins directions at N₀, another code path), and
//!   the normal force range is N₀ = 100/102 N at every amplitude.
//! - `scenes/mass-on-plane-braced.toml`: a brace couples the plane's tangential and
//!   normal motion; along the backbone the normal force varies by up to 30× and the mass
//!   lifts off. Forced by 0.13 N and integrated in time (`jointlin run --time-domain`,
//!   RK4 through `jointlin_point3d_step`), its phase resonance lies where the H = 7
//!   backbone's energy balance puts it (amplitude 1e-2, frequency 7e-4); the thesis
//!   model's backbone (the effects off) misses the amplitude by 9 %.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::{numbers, scene};

fn scratch(tag: &str) -> PathBuf {
    common::scratch("bb3", tag)
}

/// backbone.csv of `jointlin backbone SCENE --harmonics 7 --amplitudes A --set …`, as
/// rows of column → value.
fn backbone(scene: &Path, tag: &str, amplitudes: &str, set: &[&str]) -> Vec<HashMap<String, f64>> {
    let out = scratch(tag);
    let mut c = Command::new(env!("CARGO_BIN_EXE_jointlin"));
    c.args([
        "backbone",
        "--quiet",
        "--harmonics",
        "7",
        "--amplitudes",
        amplitudes,
    ])
    .arg("--out")
    .arg(&out)
    .arg(scene);
    for s in set {
        c.args(["--set", s]);
    }
    let o = c.output().unwrap();
    assert!(
        o.status.success(),
        "{}: {}",
        scene.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    let rows = numbers(&out.join("backbone.csv"));
    let _ = std::fs::remove_dir_all(&out);
    rows
}

const THESIS: [&str; 2] = [
    "effects.normal_load_variation=false",
    "effects.coupled_slip=false",
];

#[test]
fn a_mode_that_leaves_the_normal_alone_is_the_thesis_models() {
    let path = scene("mass-on-plane.toml");
    let amplitudes = "1e-3,1,25";
    let with = backbone(&path, "plane-3d", amplitudes, &[]);
    let without = backbone(&path, "plane-1d", amplitudes, &THESIS);
    assert_eq!(with.len(), 25);
    assert_eq!(without.len(), 25);
    let n0 = 100.0 / 102.0;
    let (mut dw, mut dz, mut de) = (0.0f64, 0.0f64, 0.0f64);
    for (a, b) in with.iter().zip(&without) {
        dw = dw.max((a["frequency_Hz"] / b["frequency_Hz"] - 1.0).abs());
        dz = dz.max((a["damping_ratio"] / b["damping_ratio"] - 1.0).abs());
        let e = b["energy_per_cycle_N_m"];
        de = de.max((a["plane_energy_N_m"] - e).abs() / e.max(1e-300));
        for col in ["plane_normal_force_min_N", "plane_normal_force_max_N"] {
            assert!((a[col] / n0 - 1.0).abs() < 1e-9, "{col} {}", a[col]);
        }
    }
    let slid = without
        .iter()
        .filter(|r| r["energy_per_cycle_N_m"] > 0.0)
        .count();
    eprintln!("mass on plane: ω {dw:.1e}, ζ {dz:.1e}, energy {de:.1e} over {slid} sliding rows");
    assert!(slid >= 10, "{slid}");
    assert!(dw < 1e-7 && dz < 1e-6 && de < 1e-6, "{dw:e} {dz:e} {de:e}");
}

#[test]
fn extreme_amplitudes_give_the_stuck_mode_or_an_honest_stop() {
    // 1e-300 m·kg^½ is far below the slip limit: the stuck mode, as at 1e-3; 1e300 has
    // no periodic motion to trace: the path stops, says where, writes what it has and
    // exits 1.
    let path = scene("mass-on-plane-braced.toml");
    let out = scratch("extremes");
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args([
            "backbone",
            "--quiet",
            "--harmonics",
            "3",
            "--amplitudes",
            "1e-300,1e300,3",
        ])
        .arg("--out")
        .arg(&out)
        .arg(&path)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the continuation stopped at modal amplitude"),
        "{err}"
    );
    let rows = numbers(&out.join("backbone.csv"));
    assert!(!rows.is_empty() && rows.iter().all(|r| r.values().all(|v| v.is_finite())));
    let stuck = &backbone(&path, "stuck", "1e-3,1e-3,1", &[])[0];
    let tiny = &rows[0];
    assert!((tiny["modal_amplitude_m_sqrt_kg"] / 1e-300 - 1.0).abs() < 1e-12);
    assert!((tiny["frequency_Hz"] / stuck["frequency_Hz"] - 1.0).abs() < 1e-9);
    assert!((tiny["damping_ratio"] / stuck["damping_ratio"] - 1.0).abs() < 1e-6);
    let _ = std::fs::remove_dir_all(&out);
}

/// `jointlin run SCENE --time-domain --set …` (the lumped RK4 sweep): results_time.csv.
fn time_domain(scene: &Path, tag: &str, set: &[&str]) -> Vec<HashMap<String, f64>> {
    let out = scratch(tag);
    let mut c = Command::new(env!("CARGO_BIN_EXE_jointlin"));
    c.args(["run", "--quiet", "--time-domain", "--out"])
        .arg(&out)
        .arg(scene);
    for s in set {
        c.args(["--set", s]);
    }
    let o = c.output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = numbers(&out.join("results_time.csv"));
    let _ = std::fs::remove_dir_all(&out);
    rows
}

/// Where a backbone meets the force F along x at phase resonance (the force's work
/// π F a_x per cycle equals the energy the mode loses, π ξ ω q² with ξ = 2ζω and
/// ψᴴMψ = 1): the x amplitude (m) and frequency (Hz) there, interpolated between rows.
fn phase_resonance(rows: &[HashMap<String, f64>], force: f64) -> (f64, f64) {
    let balance = |r: &HashMap<String, f64>| {
        let w = std::f64::consts::TAU * r["frequency_Hz"];
        let q = r["modal_amplitude_m_sqrt_kg"];
        2.0 * r["damping_ratio"] * w * w * q * q / r["x_amp_m"] - force
    };
    rows.windows(2)
        .find_map(|p| {
            let (b0, b1) = (balance(&p[0]), balance(&p[1]));
            (b0 < 0.0 && b1 >= 0.0).then(|| {
                let s = b0 / (b0 - b1);
                let at = |c: &str| p[0][c] + s * (p[1][c] - p[0][c]);
                (at("x_amp_m"), at("frequency_Hz"))
            })
        })
        .expect("the force is met")
}

#[test]
fn a_forced_response_in_time_peaks_on_the_backbone_with_the_varying_normal_force() {
    // 0.13 N along x at 1.02…1.10 Hz, integrated in time (RK4 through
    // jointlin_point3d_step): at phase resonance (x lags the force by 90°, interpolated)
    // the amplitude and frequency are where the EPMC backbone's energy balance puts them;
    // the thesis model's backbone (both effects off) misses the amplitude by 8 %.
    let path = scene("mass-on-plane-braced.toml");
    let amplitudes = "1e-2,7e-2,25";
    let with = backbone(&path, "braced-3d", amplitudes, &[]);
    let without = backbone(&path, "braced-1d", amplitudes, &THESIS);
    let force = 0.13;
    let td = time_domain(
        &path,
        "braced-td",
        &[
            "excitation.0.amplitude=0.13",
            "sweep.f_min=1.02",
            "sweep.f_max=1.10",
            "sweep.count=21",
        ],
    );
    let (a_td, f_td) = td
        .windows(2)
        .find_map(|p| {
            let (p0, p1) = (p[0]["x_phase_deg"] + 90.0, p[1]["x_phase_deg"] + 90.0);
            (p0 > 0.0 && p1 <= 0.0).then(|| {
                let s = p0 / (p0 - p1);
                let at = |c: &str| p[0][c] + s * (p[1][c] - p[0][c]);
                (at("x_amp_m"), at("frequency_Hz"))
            })
        })
        .expect("phase resonance in the sweep");
    let (a_bb, f_bb) = phase_resonance(&with, force);
    let (a_th, f_th) = phase_resonance(&without, force);
    let lifted = with
        .iter()
        .filter(|r| r["plane_normal_force_min_N"] == 0.0)
        .count();
    let varied = with
        .iter()
        .map(|r| r["plane_normal_force_max_N"] / r["plane_normal_force_min_N"])
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    eprintln!(
        "braced mass, 0.13 N: time domain x {a_td:.5e} m at {f_td:.5} Hz; EPMC {a_bb:.5e} m at {f_bb:.5} Hz; \
         thesis model {a_th:.5e} m at {f_th:.5} Hz; {lifted} rows with lift-off, N_max/N_min up to {varied:.2}"
    );
    assert!(lifted >= 1 && varied > 4.0, "{lifted} {varied}");
    assert!((a_bb / a_td - 1.0).abs() < 2e-2, "EPMC amplitude");
    assert!((f_bb / f_td - 1.0).abs() < 2e-3, "EPMC frequency");
    assert!((a_th / a_td - 1.0).abs() > 5e-2, "thesis model amplitude");
    assert!((f_th / f_td - 1.0).abs() > 5e-3, "thesis model frequency");
}
