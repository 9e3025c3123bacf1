//! `jointlin run --mode harmonic-balance` on a lumped scene (scenes/jenkins-chain.toml):
//! the forced response at H harmonics, each frequency continued from the last. Checked
//! against the time domain through the same C function (`time::mhb_reference`, RK4 from
//! the balance's own state, settled to 1e-9 per cycle) at frequencies below, at and above
//! the resonance (measured: 1.5e-13, 3.0e-3 at the peak, 8.7e-13); harmonics.csv against
//! results.csv and the chain's symmetry; and H = 1 with 4096
//! samples per period against the first-order run (the same first harmonic of the same
//! loop, up to the AFT's sampling: 6.0e-7).

use std::path::{Path, PathBuf};
use std::process::Command;

use jointlin_harness::input::scene::Scene;
use jointlin_harness::mhb::{default_samples, state_at_zero, Hb, NewtonOptions};
use jointlin_harness::model::lumped;
use jointlin_harness::time::mhb_reference::steady;

fn scene_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/jenkins-chain.toml")
}

/// results.csv of `jointlin run` with `args`: (frequency, m3_x amplitude) per row.
fn run(tag: &str, args: &[&str]) -> Vec<(f64, f64)> {
    let out = std::env::temp_dir().join(format!("jointlin-lumped-hb-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .arg("run")
        .arg(scene_path())
        .args(["--out", out.to_str().unwrap(), "--quiet"])
        .args(args)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{log}");
    assert!(log.contains("50 of 50 frequencies converged"), "{log}");
    if let Some(h) = args.iter().position(|a| *a == "--harmonics") {
        harmonics_agree(&out, args[h + 1].parse().unwrap());
    }
    let text = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let rows = text
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].parse().unwrap(), f[1].parse().unwrap())
        })
        .collect();
    let _ = std::fs::remove_dir_all(&out);
    rows
}

/// harmonics.csv of a harmonic-balance run in `out`: m3_x's mean, then amplitude and
/// phase of h = 1…H; the first harmonic equal to results.csv's amplitude and phase, the
/// even harmonics zero (the chain and its Masing loops are odd: x(t + T/2) = −x(t)), a
/// third harmonic where the joints slip.
fn harmonics_agree(out: &Path, h: usize) {
    let text = std::fs::read_to_string(out.join("harmonics.csv")).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut want = vec!["m3_x_h0_mean_mm".to_string()];
    for k in 1..=h {
        want.push(format!("m3_x_h{k}_amp_mm"));
        want.push(format!("m3_x_h{k}_phase_deg"));
    }
    assert_eq!(head[1..], want[..], "{head:?}");
    let results = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut third = 0.0f64;
    // Column of harmonic k's amplitude (its phase follows).
    let amp_col = |k: usize| 2 * k;
    for (hl, rl) in lines.zip(results.lines().skip(1)) {
        let hv: Vec<f64> = hl.split(',').map(|v| v.parse().unwrap()).collect();
        let rv: Vec<&str> = rl.split(',').collect();
        let amp: f64 = rv[1].parse().unwrap();
        let phase: f64 = rv[2].parse().unwrap();
        assert_eq!(hv[0], rv[0].parse::<f64>().unwrap());
        assert!(
            (hv[amp_col(1)] - amp).abs() <= 1e-14 * amp,
            "{hl} against {rl}"
        );
        assert!(
            (hv[amp_col(1) + 1] - phase).abs() <= 1e-9,
            "{hl} against {rl}"
        );
        assert!(hv[1].abs() <= 1e-12 * amp, "mean: {hl}");
        for k in (2..=h).step_by(2) {
            assert!(hv[amp_col(k)] <= 1e-12 * amp, "even harmonic {k}: {hl}");
        }
        third = third.max(if h >= 3 { hv[amp_col(3)] / amp } else { 0.0 });
    }
    // Where the joints slip (near the resonance) the motion has a third harmonic; stuck,
    // the chain is linear.
    if h >= 3 {
        assert!(
            third > 1e-2,
            "largest third harmonic {third:e} of the first"
        );
    }
}

#[test]
fn harmonic_balance_sweep_matches_the_time_domain() {
    const H: usize = 7;
    let rows = run("h7", &["--mode", "harmonic-balance", "--harmonics", "7"]);
    let scene = Scene::load(&scene_path()).unwrap();
    let l = lumped::build(&scene).unwrap();
    let sys = &l.system;
    let m3 = l.dofs.iter().position(|d| d == "m3.x").unwrap();
    let peak = (0..rows.len())
        .max_by(|&a, &b| rows[a].1.total_cmp(&rows[b].1))
        .unwrap();
    for i in [5, peak, rows.len() - 5] {
        let (f, amp) = rows[i];
        let omega = 2.0 * std::f64::consts::PI * f;
        // The balance's own state at this frequency (a fresh solve from the stuck
        // response, as the run's cold start) as the time domain's initial condition.
        let mut hb = Hb::new(sys, H, default_samples(H));
        let start = hb.stuck_start(omega);
        let sol = hb.solve(&start, omega, NewtonOptions::default()).unwrap();
        let (x0, v0) = state_at_zero(&sol.u, H, omega);
        let td = steady(sys, omega, &x0, &v0, 2048, 1e-9, 20000).unwrap();
        let err = (amp - td.amplitude[m3]).abs() / td.amplitude[m3];
        println!(
            "{f:.5} Hz: harmonic balance {amp:.6e} mm, time domain {:.6e} mm ({} cycles), relative {err:.1e}",
            td.amplitude[m3], td.cycles
        );
        assert!(err <= 1e-2, "{f} Hz: {amp} against {}", td.amplitude[m3]);
    }
}

#[test]
fn one_harmonic_is_the_first_order_run() {
    let hb = run(
        "h1",
        &[
            "--mode",
            "harmonic-balance",
            "--harmonics",
            "1",
            "--samples",
            "4096",
        ],
    );
    let fo = run("fo", &[]);
    let worst = hb
        .iter()
        .zip(&fo)
        .map(|(a, b)| {
            assert_eq!(a.0, b.0);
            (a.1 - b.1).abs() / b.1
        })
        .fold(0.0f64, f64::max);
    println!("H = 1 against first order: largest relative difference {worst:.1e}");
    // Measured 6.0e-7 (2.4e-3 with the default 64 samples: the AFT's sampling of the
    // loop, which the first order integrates exactly).
    assert!(worst <= 5e-6, "{worst}");
}

/// `[sweep] direction = "up_down"` on a lumped scene: a second pass from the top
/// frequency down, written as results_down.csv and harmonics_down.csv with rows
/// ascending like the up pass's; where the response is single-valued (the first and
/// last ten frequencies) both passes agree.
#[test]
fn up_down_sweeps_write_both_passes() {
    let dir = std::env::temp_dir().join(format!("jointlin-lumped-updown-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(scene_path()).unwrap();
    let changed = text.replacen(
        "\ncount = 50\n",
        "\ncount = 50\ndirection = \"up_down\"\n",
        1,
    );
    assert_ne!(text, changed);
    let scene = dir.join("chain.toml");
    std::fs::write(&scene, changed).unwrap();
    let out = dir.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .arg("run")
        .arg(&scene)
        .args(["--out", out.to_str().unwrap(), "--quiet", "--no-plots"])
        .args(["--mode", "harmonic-balance", "--harmonics", "3"])
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{log}");
    assert!(log.contains("100 of 100 frequencies converged"), "{log}");
    let read = |name: &str| -> Vec<(f64, f64)> {
        let text = std::fs::read_to_string(out.join(name)).unwrap();
        text.lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[0].parse().unwrap(), f[1].parse().unwrap())
            })
            .collect()
    };
    let up = read("results.csv");
    let down = read("results_down.csv");
    assert_eq!(up.len(), 50);
    assert!(out.join("harmonics_down.csv").is_file());
    for (k, (u, d)) in up.iter().zip(&down).enumerate() {
        assert_eq!(u.0, d.0, "row {k}");
        if k > 0 {
            assert!(u.0 > up[k - 1].0, "rows ascending");
        }
        if !(10..40).contains(&k) {
            assert!(
                (u.1 - d.1).abs() <= 1e-8 * u.1,
                "row {k}: {u:?} against {d:?}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
