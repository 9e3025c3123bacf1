//! Every number in the CSV files keeps its digits (docs/outputs.md, "Numbers in the CSV
//! files"): each numeric field is the shortest decimal of the double it reads back to,
//! and the fields carry the digits that form needs (most of them 15 to 17 significant
//! digits), not a fixed rounding. Checked on the files of an FE run, a lumped run with
//! harmonic balance, a backbone and the modes.

use std::path::{Path, PathBuf};
use std::process::Command;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jointlin-csv-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn jointlin(args: &[&str]) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = Command::new(env!("CARGO_BIN_EXE_jointlin"))
        .current_dir(root)
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Significant digits of a decimal in scientific or plain form.
fn significant_digits(text: &str) -> usize {
    let mantissa = text.split(['e', 'E']).next().unwrap_or("");
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    digits
        .trim_start_matches('0')
        .trim_end_matches('0')
        .len()
        .max(1)
}

/// Checks every numeric field of every CSV in `out`; returns (fields, fields with at
/// least 15 significant digits).
fn check_dir(out: &Path) -> (usize, usize) {
    let (mut fields, mut long) = (0, 0);
    let mut csvs = 0;
    for entry in std::fs::read_dir(out).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "csv") {
            continue;
        }
        csvs += 1;
        let text = std::fs::read_to_string(&path).unwrap();
        for line in text.lines().skip(1) {
            for field in line.split(',') {
                let Ok(v) = field.parse::<f64>() else {
                    continue;
                };
                if field.contains(['e', 'E']) {
                    assert_eq!(
                        format!("{:e}", v + 0.0),
                        field,
                        "{}: {field} is not the shortest form of its double",
                        path.display()
                    );
                } else {
                    // Plain integers and coordinates: Display's shortest form.
                    assert_eq!(format!("{}", v + 0.0), field, "{}", path.display());
                }
                fields += 1;
                long += usize::from(significant_digits(field) >= 15);
            }
        }
    }
    assert!(csvs > 0, "no CSV in {}", out.display());
    (fields, long)
}

#[test]
fn csv_numbers_read_back_to_the_computed_doubles() {
    let runs: [(&str, Vec<&str>); 4] = [
        (
            "fe",
            vec!["run", "scenes/three-beams.toml", "--no-plots", "--quiet"],
        ),
        (
            "lumped-hb",
            vec![
                "run",
                "scenes/jenkins-chain.toml",
                "--mode",
                "harmonic-balance",
                "--harmonics",
                "3",
                "--no-plots",
                "--quiet",
            ],
        ),
        ("backbone", vec!["backbone", "scenes/jenkins-chain.toml"]),
        (
            "modes",
            vec!["modes", "scenes/three-beams.toml", "--count", "4"],
        ),
    ];
    for (name, mut args) in runs {
        let out = dir(name);
        let out_text = out.to_str().unwrap().to_string();
        args.extend(["--out", &out_text]);
        jointlin(&args);
        let (fields, long) = check_dir(&out);
        // A fixed rounding (11 digits before) would leave no field with 15 or more.
        assert!(
            long * 4 >= fields,
            "{name}: only {long} of {fields} numbers carry 15+ digits"
        );
        let _ = std::fs::remove_dir_all(&out);
    }
}
