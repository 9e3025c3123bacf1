//! Switched-off effects cost nothing: C-API calls counted per effect, on the block
//! scene (fast and thesis modes). And the CLI writes nothing for a bad scene.

use jointlin_harness::capi::CallCounts;
use jointlin_harness::input::scene::{Mode, Scene};
use jointlin_harness::run::{run, Extras, RunResult};

fn block() -> Scene {
    let p = format!("{}/../scenes/block-stick.toml", env!("CARGO_MANIFEST_DIR"));
    Scene::load(std::path::Path::new(&p)).unwrap()
}

fn go(s: &Scene) -> (RunResult, CallCounts) {
    let r = run(s, Extras::default(), &|_, _, _| {}).unwrap();
    let c = r.calls;
    (r, c)
}

#[test]
fn switched_off_effects_make_no_calls() {
    for mode in [Mode::Fast, Mode::Thesis] {
        let mut s = block();
        s.spec.iteration.mode = mode;
        s.spec.effects.point_energy_output = false;
        s.spec.effects.stick_slip_map = false;
        let (all, c) = go(&s);
        assert!(c.uinter_general > 0, "{mode:?}: static step uses UINTER");
        assert_eq!(
            c.linearize_cubic, 0,
            "{mode:?}: no cubic springs, no cubic calls"
        );
        match mode {
            Mode::Fast => assert!(c.linearize > 0 && c.uinter_linear == 0),
            // Thesis mode: k*, d* only through UINTER; no per-point output, no linearize.
            Mode::Thesis => assert!(c.uinter_linear > 0 && c.linearize == 0 && c.uexternaldb > 0),
            Mode::HarmonicBalance => unreachable!("this loop runs the linearization modes"),
        }
        assert!(all.main.power[0] > 0.0);

        // No normal nonlinearity: no static Newton, no LINPER = 0 call.
        let mut t = s.clone();
        t.spec.effects.normal_contact_nonlinearity = false;
        let (_, c) = go(&t);
        assert_eq!(c.uinter_general, 0, "{mode:?}");

        // No microslip: constant k_T0, no linearization of any kind, no store.
        let mut t = s.clone();
        t.spec.effects.tangential_microslip = false;
        let (r, c) = go(&t);
        assert_eq!(
            (c.linearize, c.uinter_linear, c.uexternaldb, c.store),
            (0, 0, 0, 0),
            "{mode:?}"
        );
        // Stuck block: |k_T0 − mω² + …| A = F̂ → A = 0.5 / (1282.7 − 0.002·1.69) mm.
        let a = r.main.outputs[0][0].norm();
        assert!(
            (a / (0.5 / (1282.7 - 0.002 * 1.69)) - 1.0).abs() < 1e-9,
            "{a}"
        );

        // No contact damping: no d* in the model, no dissipated power reported.
        let mut t = s.clone();
        t.spec.effects.contact_damping = false;
        let (r, _) = go(&t);
        assert_eq!(r.main.power[0], 0.0);

        // Per-point output asked for: thesis mode then pays 2 linearize calls per point
        // and run frequency (A/δ* is not in the UINTER report); fast mode pays nothing.
        let mut t = s.clone();
        t.spec.effects.point_energy_output = true;
        let (r, c) = go(&t);
        let runs: usize = r.main.passes.iter().map(|p| p.frequencies.len()).sum();
        match mode {
            Mode::Fast => assert_eq!(c.linearize, all.calls.linearize),
            Mode::Thesis => assert_eq!(c.linearize as usize, 2 * runs),
            Mode::HarmonicBalance => unreachable!("this loop runs the linearization modes"),
        }
        assert_eq!(r.main.points.len(), 1);
    }
}

#[test]
fn harmonic_balance_marches_points_and_linearizes_nothing() {
    let mut s = block();
    s.spec.iteration.mode = Mode::HarmonicBalance;
    s.spec.iteration.harmonics = Some(3);
    s.spec.effects.point_energy_output = false;
    s.spec.effects.stick_slip_map = false;
    let steps0 = jointlin_harness::capi::point_steps();
    let (r, c) = go(&s);
    let steps = jointlin_harness::capi::point_steps() - steps0;
    // Only the static step's UINTER and the AFT marches (jointlin_point_step).
    assert!(c.uinter_general > 0 && steps > 0, "{steps}");
    assert_eq!((c.linearize, c.uinter_linear, c.uexternaldb), (0, 0, 0));
    assert!(r.main.power[0] > 0.0);
    assert_eq!(r.main.harmonics[0][0].len(), 4);
    // Newton stopped early: the frequency is flagged, its last iterate finite.
    let mut t = s.clone();
    (t.spec.iteration.tolerance, t.spec.iteration.max_passes) = (1e-15, 1);
    let (early, _) = go(&t);
    assert!(!early.main.converged[0]);
    let a = early.main.outputs[0][0].norm();
    assert!(
        a.is_finite() && (a / r.main.outputs[0][0].norm() - 1.0).abs() < 0.1,
        "{a}"
    );
    // Point outputs: one linearize call per direction and frequency (A/δ*, regime).
    s.spec.effects.point_energy_output = true;
    let (r, c) = go(&s);
    assert_eq!(c.linearize, 2);
    assert!(r.main.points[0][0].energy > 0.0);
}

#[test]
fn cli_bad_scene_names_file_line_key_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("jointlin-bad-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let scene = dir.with_extension("toml");
    let text = std::fs::read_to_string(format!(
        "{}/../scenes/block-stick.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .replace("mu = 0.3", "mu = -0.3");
    std::fs::write(&scene, &text).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args([
            "run",
            scene.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
            "--quiet",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    let line = text.lines().position(|l| l.contains("mu = -0.3")).unwrap() + 1;
    assert!(!out.status.success());
    assert!(
        err.contains(&format!("{}:{line}:", scene.display())),
        "{err}"
    );
    assert!(err.contains("interfaces[0].mu"), "{err}");
    assert!(!dir.exists(), "nothing may be written for a bad scene");
    std::fs::remove_file(&scene).unwrap();
}

#[test]
fn cli_run_writes_the_documented_files() {
    let dir = std::env::temp_dir().join(format!("jointlin-run-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let scene = format!("{}/../scenes/block-stick.toml", env!("CARGO_MANIFEST_DIR"));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["run", &scene, "--out", dir.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{log}");
    // The run log lists every effect with on/off and its cost.
    for e in [
        "normal_contact_nonlinearity",
        "tangential_microslip",
        "contact_damping",
        "point_energy_output",
    ] {
        assert!(log.contains(e), "{log}");
    }
    let results = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    let mut lines = results.lines();
    assert_eq!(
        lines.next().unwrap(),
        "frequency_Hz,block_x_amp_mm,block_x_phase_deg,dissipated_power_N_mm_per_s,status"
    );
    let row: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .take(4)
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(results.lines().nth(1).unwrap().ends_with(",converged"));
    // Amplitude as in block_stick_amplitude_matches_the_thesis_in_both_modes; the power
    // is the loop energy × f > 0; the phase lags the force (−180° < φ < 0°).
    assert!(
        (row[1] / 4.267e-4 - 1.0).abs() < 0.01 && row[3] > 0.0 && row[2] < 0.0 && row[2] > -180.0
    );
    let points = std::fs::read_to_string(dir.join("points.csv")).unwrap();
    assert!(points.starts_with(
        "frequency_Hz,point,interface,x_mm,y_mm,z_mm,closed,pressure_N_per_mm2,amp_t1_mm"
    ));
    assert_eq!(points.lines().count(), 2);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("run.json")).unwrap()).unwrap();
    for k in ["scene", "effects", "passes", "timings_s", "c_api_calls"] {
        assert!(json.get(k).is_some(), "run.json lacks {k}");
    }
    assert_eq!(json["scene"]["spec"]["interfaces"][0]["mu"], 0.3);
    for f in [
        "frf.svg",
        "stick_slip.svg",
        "stick_slip.csv",
        "results_without_contact_damping.csv",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    // One pass (fast mode): no passes.svg of a single bar.
    assert!(!dir.join("passes.svg").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn cli_output_into_a_closed_pipe_ends_quietly() {
    // `jointlin modes SCENE | head -1`: the reader is gone before the modes are printed.
    // Rust ignores SIGPIPE, so println! used to panic (exit 101, "failed printing to
    // stdout"); the CLI restores the default action and ends by the signal, silently.
    use std::os::unix::process::ExitStatusExt;
    let scene = format!("{}/../scenes/block-stick.toml", env!("CARGO_MANIFEST_DIR"));
    // A pipe whose reading end is closed before the child starts: its first write
    // meets no reader, whatever else the test threads are spawning.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["modes", &scene])
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.signal(), Some(13), "{:?}", out.status);
}

#[test]
fn cli_harmonic_balance_override_writes_harmonics_and_is_validated() {
    let dir = std::env::temp_dir().join(format!("jointlin-hb-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let scene = format!("{}/../scenes/block-stick.toml", env!("CARGO_MANIFEST_DIR"));
    let jl = |extra: &[&str]| {
        let mut args = vec!["run", &scene, "--out", dir.to_str().unwrap(), "--quiet"];
        args.extend_from_slice(extra);
        std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args(&args)
            .output()
            .unwrap()
    };
    // The mode without H: refused by the scene's rule, nothing written.
    let out = jl(&["--mode", "harmonic-balance"]);
    let log = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{log}");
    assert!(log.contains("iteration.harmonics"), "{log}");
    assert!(!dir.exists());
    let out = jl(&[
        "--mode",
        "harmonic-balance",
        "--harmonics",
        "3",
        "--samples",
        "7",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("iteration.samples"));
    // H = 3: harmonics.csv with h = 0..3 per output, first harmonic in results.csv.
    let out = jl(&[
        "--mode",
        "harmonic-balance",
        "--harmonics",
        "3",
        "--no-plots",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let h = std::fs::read_to_string(dir.join("harmonics.csv")).unwrap();
    assert!(
        h.starts_with("frequency_Hz,block_x_h0_mean_mm,block_x_h1_amp_mm,block_x_h1_phase_deg,block_x_h2_amp_mm,block_x_h2_phase_deg,block_x_h3_amp_mm,block_x_h3_phase_deg\n"),
        "{h}"
    );
    let field = |text: &str, k: usize| -> f64 {
        text.lines()
            .nth(1)
            .unwrap()
            .split(',')
            .nth(k)
            .unwrap()
            .parse()
            .unwrap()
    };
    let (h1, phase1) = (field(&h, 2), field(&h, 3));
    let results = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    let (a1, phase) = (field(&results, 1), field(&results, 2));
    // Same numbers in both files (10 significant digits printed): amplitude and phase of
    // the first harmonic; H = 3 moves the block's amplitude by ~0.5 % from the
    // linearized 4.279e-4 mm (docs/accuracy.md: 4.300e-4).
    assert!(
        (h1 / a1 - 1.0).abs() < 1e-9 && (a1 / 4.30e-4 - 1.0).abs() < 2e-3,
        "{h1} {a1}"
    );
    assert!((phase1 - phase).abs() < 1e-6, "{phase1} {phase}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cli_set_changes_the_scene_before_it_is_read() {
    let dir = std::env::temp_dir().join(format!("jointlin-set-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let scene = format!("{}/../scenes/block-stick.toml", env!("CARGO_MANIFEST_DIR"));
    let run = |sets: &[&str]| {
        let mut args = vec!["run", &scene, "--out", dir.to_str().unwrap(), "--quiet"];
        for s in sets {
            args.extend(["--set", s]);
        }
        std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args(&args)
            .output()
            .unwrap()
    };
    let out = run(&["sweep.count=3", "sweep.f_max=0.3"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let results = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert_eq!(results.lines().count(), 1 + 3, "{results}");
    std::fs::remove_dir_all(&dir).unwrap();

    // A key the scene does not have is named, and nothing is written.
    let out = run(&["interfaces.7.mu=0.2"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("interfaces.7.mu") && err.contains("not an index"),
        "{err}"
    );
    assert!(!dir.exists(), "nothing may be written for a bad override");
}

/// `--set` on every command that reads a scene, and a value it gives that the scene
/// refuses named on the command line, not at a line of the file.
#[test]
fn cli_set_is_taken_by_every_scene_command_and_its_errors_name_the_command_line() {
    let dir = std::env::temp_dir().join(format!("jointlin-set-all-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let scene = format!("{}/../scenes/block-stick.toml", env!("CARGO_MANIFEST_DIR"));
    let beams = format!(
        "{}/../scenes/three-beams-coarse.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let out = dir.join("out");
    let inp = dir.join("job/block.inp");
    let jl = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args(args)
            .output()
            .unwrap()
    };
    let commands: [Vec<&str>; 4] = [
        vec!["check", &scene],
        vec!["modes", &scene],
        vec!["backbone", &beams, "--out", out.to_str().unwrap()],
        vec!["export", &beams, "--inp", inp.to_str().unwrap()],
    ];
    for c in &commands {
        let mut args = c.clone();
        args.extend(["--set", "interfaces.*.mu=-1"]);
        let o = jl(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{c:?}: {err}");
        assert!(
            err.contains("error: --set interfaces.*.mu=-1: key `interfaces[0].mu`: must be >= 0"),
            "{c:?}: {err}"
        );
        // A good override is taken.
        let mut args = c.clone();
        args.extend(["--set", "interfaces.*.mu=0.25"]);
        let o = jl(&args);
        assert!(
            o.status.success(),
            "{c:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    // A table the override creates, incomplete: named on the command line too.
    let o = jl(&["check", &scene, "--set", "loss_study.output=block_x"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains(
            "error: --set loss_study.output=block_x: key `loss_study.amplitudes`: missing"
        ),
        "{err}"
    );
    // The exported deck carries the overridden μ.
    let deck = std::fs::read_to_string(&inp).unwrap();
    // (PROPS 1–3: law, rule, μ; the scene's own μ is 0.2.)
    assert!(
        deck.contains("\n0.0, 0.0, 0.25, ") && !deck.contains("\n0.0, 0.0, 0.2, "),
        "{deck}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// An amplitude beyond half the thickness of the part the output sits on is said to break
/// linear kinematics (on the log and in run.json's notes); the scene's own load is not.
#[test]
fn a_deflection_beyond_half_the_parts_thickness_is_named() {
    let dir = std::env::temp_dir().join(format!("jointlin-kinematics-{}", std::process::id()));
    let scene = format!(
        "{}/../scenes/three-beams-coarse.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    for (amplitude, large) in [("0.05", false), ("2000.0", true)] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args([
                "run",
                &scene,
                "--out",
                dir.to_str().unwrap(),
                "--quiet",
                "--no-plots",
            ])
            .args(["--set", &format!("excitation.0.amplitude={amplitude}")])
            .output()
            .unwrap();
        let log = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{log}");
        assert_eq!(
            log.contains("linear kinematics may no longer hold"),
            large,
            "{log}"
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("run.json")).unwrap()).unwrap();
        // The middle beam (1 mm) of the 5 mm stack: its tip moves 56 mm at the first
        // resonance under 2000 N, judged against its own thickness.
        assert_eq!(json["notes"].as_array().unwrap().len(), usize::from(large));
        if large {
            assert!(
                log.contains("output middle_tip moves 5.633e1 mm")
                    && log.contains("the part it sits on (1.000e0 mm"),
                "{log}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
