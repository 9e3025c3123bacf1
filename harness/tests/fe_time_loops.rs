//! The contact points' loops of an FE scene's time domain (loops_time.csv, loops_time.svg
//! of `jointlin run --time-domain`): at the frequency of the largest response, every
//! point's tangential force against its tangential relative displacement over the last
//! period. On `scenes/three-beams-coarse.toml` near its first resonance (Newmark, 128
//! steps per period, microslip at the outer points) the loops enclose the energy the
//! library reports per point (points_time.csv): in total within 1e-3, per point that
//! dissipates within 2e-2 (a trapezoid sum over 128 samples against the library's exact
//! increments); the loops are kept for the largest response only.

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
    let mut samples: HashMap<usize, Vec<[f64; 4]>> = HashMap::new();
    for r in &loops {
        samples
            .entry(r["point"].parse().unwrap())
            .or_default()
            .push(["u1_mm", "u2_mm", "f1_N", "f2_N"].map(|c| num(r, c)));
    }
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
        let mut e = 0.0;
        for k in 0..s.len() {
            let (a, b) = (s[k], s[(k + 1) % s.len()]);
            e += 0.5 * (a[2] + b[2]) * (b[0] - a[0]) + 0.5 * (a[3] + b[3]) * (b[1] - a[1]);
        }
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
}
