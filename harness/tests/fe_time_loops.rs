//! The contact points' loops of an FE scene's time domain (loops_time.csv, loops_time.svg
//! of `jointlin run --time-domain`): at the frequency of the largest response, every
//! point's tangential force against its tangential relative displacement over the last
//! period. On `scenes/three-beams-coarse.toml` near its first resonance (Newmark, 128
//! steps per period, microslip at the outer points) the loops enclose the energy the
//! library reports per point (points_time.csv): in total within 1e-3, per point that
//! dissipates within 2e-2 (a trapezoid sum over 128 samples against the library's exact
//! increments); the loops are kept for the largest response only. The harmonic balance
//! of the same scene (H = 7) writes loops.csv at the same frequency, and its loops match
//! the time domain's point by point; on `scenes/three-beams-oblique.toml` the balance's
//! loops enclose the energies the balance reports, with and without the three-direction
//! effects.

use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

mod common;
use common::{num, rows};

#[test]
fn the_loops_of_the_largest_response_enclose_each_points_energy() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/three-beams-coarse.toml");
    let out = std::env::temp_dir().join(format!("jointlin-fe-loops-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["run", "--quiet", "--time-domain", "--out"])
        .arg(&out)
        .arg(&scene)
        .args(["--set", "sweep.f_min=1150", "--set", "sweep.f_max=1169.829"])
        .args(["--set", "sweep.count=2", "--set", "sweep.refine=[]"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.join("loops_time.svg").is_file());
    let loops = rows(&out.join("loops_time.csv"));
    // Only the larger response's frequency is written.
    assert!(loops
        .iter()
        .all(|r| r["frequency_Hz"].starts_with("1.169829")));
    let samples = by_point(&loops);
    let energy: HashMap<usize, f64> = rows(&out.join("points_time.csv"))
        .iter()
        .filter(|r| r["frequency_Hz"].starts_with("1.169829"))
        .map(|r| (r["point"].parse().unwrap(), num(r, "energy_per_cycle_N_mm")))
        .collect();
    assert_eq!(samples.len(), energy.len());
    let (mut looped, mut reported, mut worst) = (0.0, 0.0, 0.0f64);
    let largest = energy.values().fold(0.0f64, |m, &e| m.max(e));
    for (point, s) in &samples {
        assert_eq!(s.len(), 128, "point {point}");
        let e = enclosed(s);
        looped += e;
        reported += energy[point];
        if energy[point] > 1e-2 * largest {
            worst = worst.max((e / energy[point] - 1.0).abs());
        }
    }
    println!("loops {looped:.6e} N·mm against {reported:.6e} N·mm; worst point {worst:.1e}");
    assert!(reported > 0.0 && (looped / reported - 1.0).abs() < 1e-3);
    assert!(worst < 2e-2);
    // The normal force is compressive at a closed, preloaded point.
    assert!(loops.iter().all(|r| num(r, "normal_force_N") >= 0.0));
    // The harmonic balance (H = 7) of the same scene at the same frequencies: its loops
    // (loops.csv, at the same larger response) against the time domain's, point by point
    // for the six that dissipate most: the slip range within 1.5e-2, the energy within
    // 4e-2 (measured 0.7 % and 2.0–2.4 %: Newmark's 128 steps against the balance).
    let hb = out.join("hb");
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["run", "--quiet", "--out"])
        .arg(&hb)
        .arg(&scene)
        .args(["--set", "sweep.f_min=1150", "--set", "sweep.f_max=1169.829"])
        .args(["--set", "sweep.count=2", "--set", "sweep.refine=[]"])
        .args(["--set", "iteration.mode=harmonic_balance"])
        .args(["--set", "iteration.harmonics=7"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(hb.join("loops.svg").is_file());
    let balance_rows = rows(&hb.join("loops.csv"));
    assert!(balance_rows
        .iter()
        .all(|r| r["frequency_Hz"].starts_with("1.169829")));
    let balance = by_point(&balance_rows);
    let mut top: Vec<(usize, f64)> = samples.iter().map(|(p, s)| (*p, enclosed(s))).collect();
    top.sort_by(|a, b| b.1.total_cmp(&a.1));
    let range = |s: &[[f64; 4]]| {
        let (lo, hi) = s
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(v[0]), h.max(v[0]))
            });
        hi - lo
    };
    let (mut de, mut dr) = (0.0f64, 0.0f64);
    for &(point, e) in &top[..6] {
        let b = &balance[&point];
        de = de.max((enclosed(b) / e - 1.0).abs());
        dr = dr.max((range(b) / range(&samples[&point]) - 1.0).abs());
    }
    println!("balance loops against the time domain's: energy {de:.1e}, slip range {dr:.1e}");
    assert!(de < 4e-2 && dr < 1.5e-2, "{de} {dr}");
    let _ = std::fs::remove_dir_all(&out);
}

/// Per point of a loops table: (u₁, u₂, f₁, f₂) per sample.
fn by_point(loops: &[HashMap<String, String>]) -> HashMap<usize, Vec<[f64; 4]>> {
    let mut samples: HashMap<usize, Vec<[f64; 4]>> = HashMap::new();
    for r in loops {
        samples
            .entry(r["point"].parse().unwrap())
            .or_default()
            .push(["u1_mm", "u2_mm", "f1_N", "f2_N"].map(|c| num(r, c)));
    }
    samples
}

/// ∮ F·du of a closed loop by the trapezoid rule (N·mm).
fn enclosed(s: &[[f64; 4]]) -> f64 {
    (0..s.len())
        .map(|k| {
            let (a, b) = (s[k], s[(k + 1) % s.len()]);
            0.5 * (a[2] + b[2]) * (b[0] - a[0]) + 0.5 * (a[3] + b[3]) * (b[1] - a[1])
        })
        .sum()
}

/// The harmonic balance's loops (loops.csv) of `scenes/three-beams-oblique.toml` near its
/// peak, with the thesis's point model and with both three-direction effects: written at
/// the largest response, each point's loop encloses the energy the balance reports for
/// it (points.csv) within 3e-3 in total and 2e-2 per point that dissipates (a trapezoid
/// sum over the balance's 64 samples against the library's exact increments); the
/// overclosure is a column where the normal follows the balance, and there the normal
/// force varies within the period.
#[test]
fn the_balance_loops_enclose_the_balances_energy() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/three-beams-oblique.toml");
    for effects in [false, true] {
        let out = std::env::temp_dir().join(format!(
            "jointlin-hb-loops-{}-{effects}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&out);
        let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args(["run", "--quiet", "--out"])
            .arg(&out)
            .arg(&scene)
            .args(["--set", "sweep.f_min=1160", "--set", "sweep.f_max=1175"])
            .args([
                "--set",
                "sweep.count=4",
                "--set",
                "effects.point_energy_output=true",
            ])
            .args(["--set", &format!("effects.normal_load_variation={effects}")])
            .args(["--set", &format!("effects.coupled_slip={effects}")])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let loops = rows(&out.join("loops.csv"));
        let results = rows(&out.join("results.csv"));
        let amp = |r: &HashMap<String, String>| num(r, "middle_tip_amp_mm");
        let peak = results
            .iter()
            .max_by(|a, b| amp(a).total_cmp(&amp(b)))
            .unwrap()["frequency_Hz"]
            .clone();
        assert!(loops.iter().all(|r| r["frequency_Hz"] == peak), "{peak}");
        assert_eq!(loops[0].contains_key("overclosure_mm"), effects);
        let samples = by_point(&loops);
        let energy: HashMap<usize, f64> = rows(&out.join("points.csv"))
            .iter()
            .filter(|r| r["frequency_Hz"] == peak)
            .map(|r| (r["point"].parse().unwrap(), num(r, "energy_per_cycle_N_mm")))
            .collect();
        let largest = energy.values().fold(0.0f64, |m, &e| m.max(e));
        let (mut looped, mut reported, mut worst) = (0.0, 0.0, 0.0f64);
        for (point, s) in &samples {
            let e = enclosed(s);
            looped += e;
            reported += energy[point];
            if energy[point] > 1e-2 * largest {
                worst = worst.max((e / energy[point] - 1.0).abs());
            }
        }
        let n: Vec<f64> = loops.iter().map(|r| num(r, "normal_force_N")).collect();
        let (lo, hi) = n
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), v| (l.min(*v), h.max(*v)));
        println!(
            "effects {effects}: loops {looped:.6e} N·mm against {reported:.6e} N·mm, worst point {worst:.1e}; normal force {lo:.4}…{hi:.4} N"
        );
        assert!(reported > 0.0 && (looped / reported - 1.0).abs() < 3e-3);
        assert!(worst < 2e-2, "{worst}");
        assert!(lo >= 0.0);
        // Per point the largest relative swing of N over the period: zero at the static
        // normal force of the thesis's model, not zero where the balance carries it.
        let mut normal: HashMap<String, Vec<f64>> = HashMap::new();
        for r in &loops {
            normal
                .entry(r["point"].clone())
                .or_default()
                .push(num(r, "normal_force_N"));
        }
        let swing = normal
            .values()
            .map(|v| {
                let (l, h) = v
                    .iter()
                    .fold((f64::INFINITY, 0.0f64), |(l, h), x| (l.min(*x), h.max(*x)));
                (h - l) / h
            })
            .fold(0.0f64, f64::max);
        println!("effects {effects}: largest swing of a point's normal force {swing:.2e}");
        assert_eq!(swing > 1e-3, effects, "{swing}");
        let _ = std::fs::remove_dir_all(&out);
    }
}
