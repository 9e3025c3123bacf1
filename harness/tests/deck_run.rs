//! `jointlin run` and `jointlin modes` on Abaqus-format decks: the results of a deck
//! run, the same numbers through a scene with `model = "x.inp"`, and decks a run cannot
//! honour refused with exit code 2 and `file:line: *KEYWORD: message`.

use std::path::{Path, PathBuf};
use std::process::Command;

use jointlin_harness::validate::stack_deck::{stack_deck, Joining};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-deck-run-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn jointlin(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The stack with a Jenkins contact (μ = 0.3, k_T0 = 1e5, k_N = 1e6 N/mm³, 1 MPa),
/// swept over 3 frequencies below its first bending resonance (504 Hz stuck; the
/// deck's default FREQUENCY SCALE is logarithmic: 200, 282.8, 400 Hz), clamped by
/// ENCASTRE.
fn contact_deck() -> String {
    let joint = Joining::Contact {
        mu: 0.3,
        k_t0: 1e5,
        k_n: 1e6,
        pressure: 1.0,
    };
    stack_deck(joint, 2, Some((200.0, 400.0, 3))).replace("CLAMP, 1, 3", "CLAMP, ENCASTRE")
}

/// results.csv as (header, rows of numbers; the status column left out).
fn results(path: &Path) -> (Vec<String>, Vec<Vec<f64>>, Vec<String>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let status = header.iter().position(|h| h == "status").unwrap();
    let (mut rows, mut statuses) = (Vec::new(), Vec::new());
    for l in lines {
        let f: Vec<&str> = l.split(',').collect();
        statuses.push(f[status].to_string());
        rows.push(
            f.iter()
                .enumerate()
                .filter(|&(i, _)| i != status)
                .map(|(_, v)| v.parse().unwrap())
                .collect(),
        );
    }
    (header, rows, statuses)
}

#[test]
fn a_deck_run_and_a_scene_with_model_give_the_same_results() {
    let d = dir("run");
    let deck = d.join("stack.inp");
    std::fs::write(&deck, contact_deck()).unwrap();
    let out = d.join("deck-out");
    let (code, log) = jointlin(&[
        "run",
        deck.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--no-plots",
    ]);
    assert_eq!(code, 0, "{log}");
    let (header, rows, status) = results(&out.join("results.csv"));
    assert_eq!(rows.len(), 3);
    assert!((rows[1][0] - 200.0 * 2f64.sqrt()).abs() < 1e-6, "{rows:?}");
    assert!(status.iter().all(|s| s == "converged"), "{status:?}\n{log}");
    // The deck's *NODE PRINT, NSET=TIP, U: one column pair per component of the node.
    for c in 1..=3 {
        assert!(
            header
                .iter()
                .any(|h| h.starts_with("TIP_") && h.ends_with(&format!("_u{c}_amp_mm"))),
            "{header:?}"
        );
    }
    let scene = d.join("from-deck.toml");
    std::fs::write(
        &scene,
        "title = \"the stack deck\"\nmodel = \"stack.inp\"\n[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n",
    )
    .unwrap();
    let out2 = d.join("scene-out");
    let (code, log) = jointlin(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out2.to_str().unwrap(),
        "--quiet",
        "--no-plots",
    ]);
    assert_eq!(code, 0, "{log}");
    let (header2, rows2, _) = results(&out2.join("results.csv"));
    assert_eq!(header, header2);
    for (a, b) in rows.iter().flatten().zip(rows2.iter().flatten()) {
        assert!((a - b).abs() <= 1e-9 * a.abs().max(1e-300), "{a} vs {b}");
    }
    // The scene's own output on a deck set: the top layer's elements (set L3), the node
    // nearest its tip corner, which is TIP's node: the same numbers as TIP's z column.
    let scene3 = d.join("own-output.toml");
    std::fs::write(
        &scene3,
        "model = \"stack.inp\"\n[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n[[outputs]]\nname = \"tip_z\"\nbody = \"L3\"\nat = [100.0, 0.0, 6.0]\ndirection = [0.0, 0.0, 1.0]\n",
    )
    .unwrap();
    let out3 = d.join("own-out");
    let (code, log) = jointlin(&[
        "run",
        scene3.to_str().unwrap(),
        "--out",
        out3.to_str().unwrap(),
        "--quiet",
        "--no-plots",
    ]);
    assert_eq!(code, 0, "{log}");
    let (header3, rows3, _) = results(&out3.join("results.csv"));
    assert_eq!(header3[1], "tip_z_amp_mm");
    let z = header
        .iter()
        .position(|h| h.ends_with("_u3_amp_mm"))
        .unwrap();
    for (a, b) in rows.iter().zip(&rows3) {
        assert!((a[z] - b[1]).abs() <= 1e-9 * a[z].abs(), "{a:?} vs {b:?}");
    }
    // The modes of the same deck: its *FREQUENCY step asks for 2.
    let (code, log) = jointlin(&["modes", deck.to_str().unwrap()]);
    assert_eq!(code, 0, "{log}");
    assert!(log.contains("2 mode(s), as asked"), "{log}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn decks_a_run_cannot_honour_are_named_errors_with_their_line() {
    let d = dir("bad");
    let base = contact_deck();
    let line_of =
        |text: &str, pat: &str| text.lines().position(|l| l.starts_with(pat)).unwrap() + 1;
    let cases: Vec<(&str, String, &str, &str)> = vec![
        (
            "no-props.inp",
            base.replace(
                "PROPERTIES=7\n1.\n1, 0, 3e-1, 1e5, 0, 1e6, 0",
                "PROPERTIES=0\n1.",
            ),
            "*CONTACT PAIR",
            "needs USER, PROPERTIES >= 7",
        ),
        (
            "law-code.inp",
            base.replace("1, 0, 3e-1, 1e5, 0, 1e6, 0", "2, 0, 3e-1, 1e5, 0, 1e6, 0"),
            "*CONTACT PAIR",
            "PROPS(1) = 2.0 is not a tangential law code",
        ),
        (
            "moving.inp",
            base.replace("CLAMP, ENCASTRE", "CLAMP, 1, 3, 0.1"),
            "*BOUNDARY",
            "prescribed displacement 0.1",
        ),
        (
            "freq-load.inp",
            base.replace("*FREQUENCY\n2\n", "*FREQUENCY\n2\n*CLOAD\nTIP, 3, 1.\n"),
            "*FREQUENCY",
            "loads in a frequency step",
        ),
        (
            "static-imaginary.inp",
            base.replace("*STATIC\n*DSLOAD\n", "*STATIC\n*DSLOAD, IMAGINARY\n"),
            "*STATIC",
            "an IMAGINARY load in a static step",
        ),
        (
            "amplitude.inp",
            base.replace("*CLOAD\nTIP, 3, 1.", "*CLOAD, AMPLITUDE=RAMP\nTIP, 3, 1."),
            "*CLOAD",
            "AMPLITUDE=RAMP: a frequency-dependent load amplitude is not read",
        ),
    ];
    for (name, text, keyword, msg) in cases {
        assert_ne!(text, base, "{name}: the case did not change the deck");
        let path = d.join(name);
        std::fs::write(&path, &text).unwrap();
        let (code, log) = jointlin(&[
            "run",
            path.to_str().unwrap(),
            "--out",
            d.join("out").to_str().unwrap(),
            "--quiet",
        ]);
        assert_eq!(code, 2, "{name}: {log}");
        let card = match keyword {
            "*FREQUENCY" => "*CLOAD",
            "*STATIC" => "*DSLOAD",
            "*CONTACT PAIR" => "*CONTACT PAIR",
            k => k,
        };
        // A contact pair is named at its data line (slave, master), after the card.
        let line = line_of(&text, card) + usize::from(keyword == "*CONTACT PAIR");
        let want = format!("{name}:{line}: {keyword}: ");
        assert!(
            log.contains(&want) && log.contains(msg),
            "{name}: want `{want}…{msg}` in\n{log}"
        );
        assert!(!d.join("out").join("results.csv").exists());
        let (code, log) = jointlin(&["modes", path.to_str().unwrap()]);
        assert!(code == 2 && log.contains(&want), "{name}: modes: {log}");
        // `check` finds what `run` finds, at the same file:line.
        let (code, log) = jointlin(&["check", path.to_str().unwrap()]);
        assert!(code == 2 && log.contains(&want), "{name}: check: {log}");
    }
    // Nodes without elements: no mesh to run.
    let bare = d.join("bare.inp");
    std::fs::write(&bare, "*HEADING\nnodes only\n*NODE\n1, 0., 0., 0.\n").unwrap();
    let bare_out = d.join("bare-out");
    let bare_arg = bare.to_str().unwrap();
    for args in [
        vec!["check", bare_arg],
        vec!["modes", bare_arg],
        vec!["run", bare_arg, "--out", bare_out.to_str().unwrap()],
    ] {
        let (code, log) = jointlin(&args);
        assert!(
            code == 2 && log.contains("bare.inp:0: *ELEMENT: the deck has no elements"),
            "{args:?}: {log}"
        );
    }
    assert!(!bare_out.join("results.csv").exists());
    // A deck a run can take passes `check` with the run's own numbers.
    std::fs::write(d.join("good.inp"), &base).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(["check", d.join("good.inp").to_str().unwrap()])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && out.contains("run checks: ok") && out.contains("contact points"),
        "{out}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // A scene with `model` may not have its own bodies.
    std::fs::write(d.join("stack.inp"), &base).unwrap();
    let scene = d.join("bodies.toml");
    std::fs::write(
        &scene,
        "model = \"stack.inp\"\n[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n[[bodies]]\nname = \"b\"\nkind = \"mass\"\nposition = [0.0, 0.0, 0.0]\nmass = 1.0\n",
    )
    .unwrap();
    let (code, log) = jointlin(&["check", scene.to_str().unwrap()]);
    assert_eq!(code, 2, "{log}");
    assert!(
        log.contains("bodies.toml:7:") && log.contains("not allowed with `model`"),
        "{log}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A scene with `model` and `[field_output]`: the peak of the deck's output gets its
/// field and, with plots, its contact maps in the interface's plane; without any output
/// (no `[[outputs]]`, no `*NODE PRINT`) `peaks` is an error at its key.
#[test]
fn field_output_of_a_scene_with_model_uses_the_deck_outputs() {
    let d = dir("field");
    std::fs::write(d.join("stack.inp"), contact_deck()).unwrap();
    let units = "[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n";
    let scene = d.join("fields.toml");
    std::fs::write(
        &scene,
        format!("model = \"stack.inp\"\n{units}[field_output]\npeaks = 1\n"),
    )
    .unwrap();
    let out = d.join("out");
    let (code, log) = jointlin(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{log}");
    // Below the resonance the amplitude rises: the peak is the top end, 400 Hz.
    for name in [
        "field_400.0000_Hz.vtu",
        "contact_ratio_400.0000_Hz.svg",
        "contact_energy_400.0000_Hz.svg",
    ] {
        assert!(out.join(name).is_file(), "{name}: {log}");
    }
    let map = std::fs::read_to_string(out.join("contact_ratio_400.0000_Hz.svg")).unwrap();
    assert!(
        map.contains("x [mm]") && map.contains("y [mm]"),
        "the plates' plane"
    );
    // Two interfaces of the three-layer stack: a panel each.
    assert_eq!(
        map.matches("A/δ* (colour) and slip amplitude (area)")
            .count(),
        2
    );
    let bare = d.join("bare.inp");
    std::fs::write(
        &bare,
        contact_deck().replace("*NODE PRINT, NSET=TIP\nU\n", ""),
    )
    .unwrap();
    let scene = d.join("no-output.toml");
    std::fs::write(
        &scene,
        format!("model = \"bare.inp\"\n{units}[field_output]\npeaks = 1\n"),
    )
    .unwrap();
    let (code, log) = jointlin(&["check", scene.to_str().unwrap()]);
    assert_eq!(code, 2, "{log}");
    assert!(
        log.contains("field_output.peaks") && log.contains("*NODE OUTPUT/*NODE PRINT"),
        "{log}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// points.csv names each point by the deck's own slave node id (not the model's index:
/// an orphan node listed first shifts every index by one) and gives its frame n, t1, t2
/// in global components, orthonormal.
#[test]
fn points_carry_the_decks_node_ids_and_their_frames() {
    let d = dir("points");
    let deck = contact_deck().replacen("*NODE\n", "*NODE\n999999, -50., -50., -50.\n", 1);
    std::fs::write(d.join("stack.inp"), &deck).unwrap();
    std::fs::write(
        d.join("points.toml"),
        "model = \"stack.inp\"\n[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n[effects]\npoint_energy_output = true\n",
    )
    .unwrap();
    let out = d.join("out");
    let (code, log) = jointlin(&[
        "run",
        d.join("points.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--no-plots",
    ]);
    assert_eq!(code, 0, "{log}");
    // The deck's node coordinates by id, read from its *NODE lines.
    let mut coords = std::collections::HashMap::new();
    let mut in_nodes = false;
    for l in deck.lines() {
        if l.starts_with('*') {
            in_nodes = l.starts_with("*NODE") && !l.starts_with("*NODE PRINT");
            continue;
        }
        if in_nodes {
            let f: Vec<f64> = l.split(',').map(|v| v.trim().parse().unwrap()).collect();
            coords.insert(f[0] as u64, [f[1], f[2], f[3]]);
        }
    }
    let text = std::fs::read_to_string(out.join("points.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let first = lines.next().unwrap().split(',').next().unwrap().to_string();
    let mut rows = 0;
    for l in text.lines().skip(1).filter(|l| l.starts_with(&first)) {
        let v: Vec<&str> = l.split(',').collect();
        let id: u64 = v[col("node")].parse().unwrap();
        let at = coords[&id];
        for (k, axis) in ["x_mm", "y_mm", "z_mm"].iter().enumerate() {
            let x: f64 = v[col(axis)].parse().unwrap();
            assert!((x - at[k]).abs() < 1e-9, "node {id}: {x} vs {}", at[k]);
        }
        let vec3 = |a: &str| -> [f64; 3] {
            ["x", "y", "z"].map(|c| v[col(&format!("{a}_{c}"))].parse().unwrap())
        };
        let (n, t1, t2) = (vec3("n"), vec3("t1"), vec3("t2"));
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        for (a, b, want) in [
            (n, n, 1.0),
            (t1, t1, 1.0),
            (t2, t2, 1.0),
            (n, t1, 0.0),
            (n, t2, 0.0),
            (t1, t2, 0.0),
        ] {
            assert!(
                (dot(a, b) - want).abs() < 1e-12,
                "node {id}: frame {n:?} {t1:?} {t2:?}"
            );
        }
        rows += 1;
    }
    assert!(rows > 0, "{text}");
    let _ = std::fs::remove_dir_all(&d);
}
