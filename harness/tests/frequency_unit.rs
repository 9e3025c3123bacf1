//! `[units] frequency`: outputs show the angular frequency (rad per time unit) when a
//! scene declares it, with the same responses as in cycles per time unit; wrong spellings
//! are named errors. On the Duffing oscillator (scenes/duffing.toml, which declares rad/s).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const TWO_PI: f64 = 2.0 * std::f64::consts::PI;

/// scenes/duffing.toml with one text replacement (which must match), in a fresh directory.
fn duffing(dir: &str, from: &str, to: &str) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/duffing.toml");
    let text = std::fs::read_to_string(src).unwrap();
    assert!(text.contains(from), "no `{from}`");
    let d = std::env::temp_dir().join(format!("jointlin-freq-unit-{dir}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join("duffing.toml");
    std::fs::write(&p, text.replacen(from, to, 1)).unwrap();
    p
}

fn jointlin(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .args(args)
        .output()
        .unwrap()
}

/// (header, rows of numbers in the first `n` columns) of a CSV file.
fn table(path: &Path, n: usize) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let head = r.headers().unwrap().iter().map(String::from).collect();
    let rows = r
        .records()
        .map(|rec| {
            let rec = rec.unwrap();
            (0..n).map(|i| rec[i].parse().unwrap()).collect()
        })
        .collect();
    (head, rows)
}

#[test]
fn angular_outputs_are_two_pi_times_the_cycles_and_the_responses_are_the_same() {
    let rad = duffing("rad", "", "");
    let hz = duffing("hz", "frequency = \"rad/s\"\n", "");
    let mut tables = Vec::new();
    for scene in [&rad, &hz] {
        let out = scene.with_file_name("out");
        let o = jointlin(&[
            "run",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let up = table(&out.join("results.csv"), 2);
        let down = table(&out.join("results_down.csv"), 2);
        let svg = std::fs::read_to_string(out.join("frf.svg")).unwrap();
        tables.push((up, down, svg));
    }
    let ((up_rad, down_rad, svg_rad), (up_hz, down_hz, svg_hz)) = (&tables[0], &tables[1]);
    for ((rad, hz), name) in [(up_rad, up_hz), (down_rad, down_hz)]
        .iter()
        .zip(["up", "down"])
    {
        assert_eq!(rad.0[0], "angular_frequency_rad_per_s", "{name}");
        assert_eq!(hz.0[0], "frequency_Hz", "{name}");
        assert_eq!(rad.1.len(), 306, "{name}");
        for (a, b) in rad.1.iter().zip(&hz.1) {
            // Each printed with 11 significant digits.
            assert!(
                (a[0] - TWO_PI * b[0]).abs() <= 1e-10 * a[0],
                "{name}: {a:?} vs {b:?}"
            );
            assert_eq!(a[1], b[1], "{name}: the response must not change");
        }
    }
    // The sweep starts at 0.15 Hz = 0.9425 rad/s.
    assert!((up_rad.1[0][0] - TWO_PI * 0.15).abs() < 1e-10);
    assert!(svg_rad.contains("angular frequency [rad/s]"));
    assert!(svg_hz.contains("frequency [Hz]") && !svg_hz.contains("rad/s"));
}

#[test]
fn modes_print_the_angular_eigenfrequency() {
    // With the cubic spring's linear part only: ω = √(k/m) = √20 rad/s.
    let scene = duffing("modes", "", "");
    let out = scene.with_file_name("modes");
    let o = jointlin(&[
        "modes",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("frequency (rad/s)"), "{stdout}");
    let (head, rows) = table(&out.join("modes.csv"), 2);
    assert_eq!(head[1], "angular_frequency_rad_per_s");
    assert!(
        (rows[0][1] - 20f64.sqrt()).abs() < 1e-9 * 20f64.sqrt(),
        "{rows:?}"
    );
}

#[test]
fn a_frequency_unit_that_does_not_match_the_time_unit_is_named() {
    for bad in ["rad/min", "Hz ", "kHz"] {
        let scene = duffing(
            "bad",
            "frequency = \"rad/s\"",
            &format!("frequency = \"{bad}\""),
        );
        let o = jointlin(&["check", scene.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{bad}: {err}");
        assert!(
            err.contains("units.frequency") && err.contains("Hz, 1/s, rad/s"),
            "{bad}: {err}"
        );
    }
}
