//! `jointlin validate`: the frequency-domain results against the time-domain reference,
//! case by case, written as validation.csv and validation.md.
//!
//! - block stick (scenes/block-stick.toml): F̂ 0.40–0.55 N at ω = 1.3 rad/s and ω
//!   0.1–20 rad/s at F̂ = 0.5 N (the thesis: errors below 5 %, Fig. 4.17, 4.18);
//! - block slip (scenes/block-slip.toml): F̂ 0.70–0.82 N; below 4μF_N/π no sliding
//!   first-harmonic solution exists (model.md §8), which the table says;
//! - the Duffing oscillator (Appendix B) swept up and down: first-order harmonic balance
//!   (closed form, the branch followed) vs RK4 (continued from frequency to frequency),
//!   with the jump frequencies of both;
//! - the softening friction oscillator (scenes/softening-friction.toml): folds of a dense
//!   first-order residual scan and of continuation (H = 1, 3), the unstable stretch, and
//!   H = 3 vs RK4 on both stable branches between the folds;
//! - three beams on a coarse mesh at frequencies around both resonances: output amplitude
//!   and joint energy per cycle, frequency domain vs Newmark.
//!
//! Both sides run the same scene through the same C API (the frequency domain LINPER = 1
//! or jointlin_linearize, the time domain UINTER LINPER = 0).

pub mod beams;
pub mod block;
pub mod c3d8i_ccx;
pub mod ccx;
pub mod deck_ccx;
pub mod duffing;
pub mod matrices_ccx;
mod mesh_cards;
pub mod softening;
pub mod stack_deck;
pub mod tied_blocks;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::model::Job;
use crate::util::atomic;
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;

/// One compared quantity.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    pub case: String,
    /// The varied parameter, e.g. "F = 0.45 N".
    pub parameter: String,
    /// What is compared, with its unit.
    pub quantity: String,
    /// Frequency-domain value (None when it has no solution).
    pub frequency_domain: Option<f64>,
    /// Time-domain value (first harmonic for amplitudes, ∮F dδ for energies).
    pub time_domain: f64,
    /// Relative error (FD − TD)/TD.
    pub error: Option<f64>,
    /// Second time-domain measure (half peak-to-peak for amplitudes), if any.
    pub time_domain_half_range: Option<f64>,
    /// Relative error against it.
    pub error_half_range: Option<f64>,
    pub note: String,
}

impl Row {
    /// A row with the relative errors filled in.
    pub fn new(
        case: &str,
        parameter: String,
        quantity: &str,
        fd: Option<f64>,
        td: f64,
        td_half: Option<f64>,
        note: String,
    ) -> Row {
        let rel = |a: f64, b: f64| if b != 0.0 { (a - b) / b } else { f64::NAN };
        Row {
            case: case.into(),
            parameter,
            quantity: quantity.into(),
            frequency_domain: fd,
            time_domain: td,
            error: fd.map(|f| rel(f, td)),
            time_domain_half_range: td_half,
            error_half_range: match (fd, td_half) {
                (Some(f), Some(h)) => Some(rel(f, h)),
                _ => None,
            },
            note,
        }
    }
}

/// Which cases to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cases {
    pub block_stick: bool,
    pub block_slip: bool,
    pub duffing: bool,
    pub softening_friction: bool,
    pub three_beams: bool,
}

impl Cases {
    pub fn all() -> Self {
        Cases {
            block_stick: true,
            block_slip: true,
            duffing: true,
            softening_friction: true,
            three_beams: true,
        }
    }

    /// From names: block-stick, block-slip, duffing, softening-friction, three-beams.
    pub fn parse(names: &[String]) -> Result<Self, String> {
        if names.is_empty() {
            return Ok(Cases::all());
        }
        let mut c = Cases {
            block_stick: false,
            block_slip: false,
            duffing: false,
            softening_friction: false,
            three_beams: false,
        };
        for n in names {
            match n.as_str() {
                "block-stick" => c.block_stick = true,
                "block-slip" => c.block_slip = true,
                "duffing" => c.duffing = true,
                "softening-friction" => c.softening_friction = true,
                "three-beams" => c.three_beams = true,
                o => {
                    return Err(format!(
                        "unknown case `{o}` (block-stick, block-slip, duffing, softening-friction, three-beams)"
                    ))
                }
            }
        }
        Ok(c)
    }
}

/// The validation report.
#[derive(Debug, Default)]
pub struct Report {
    pub rows: Vec<Row>,
    /// Extra lines per case (jumps, existence of solutions, costs).
    pub notes: Vec<(String, String)>,
}

/// The shipped scenes the cases start from, each read by the caller through the input
/// path (`Job::load`); a case whose scene is `None` is not run.
#[derive(Debug, Default)]
pub struct CaseScenes {
    /// scenes/block-stick.toml.
    pub block_stick: Option<Job>,
    /// scenes/block-slip.toml.
    pub block_slip: Option<Job>,
    /// scenes/three-beams.toml.
    pub three_beams: Option<Job>,
}

/// Runs the selected cases (those that need a scene: with it in `scenes`). `log`
/// receives progress lines.
pub fn run(scenes: &CaseScenes, cases: Cases, log: &dyn Fn(&str)) -> Result<Report, String> {
    let mut rep = Report::default();
    fn need<'a>(s: &'a Option<Job>, file: &str) -> Result<&'a Job, String> {
        s.as_ref()
            .ok_or_else(|| format!("the case needs scenes/{file}, which was not given"))
    }
    if cases.block_stick {
        block::stick(
            need(&scenes.block_stick, "block-stick.toml")?,
            &mut rep,
            log,
        )?;
    }
    if cases.block_slip {
        block::slip(need(&scenes.block_slip, "block-slip.toml")?, &mut rep, log)?;
    }
    if cases.duffing {
        duffing::sweep(&mut rep, log)?;
    }
    if cases.softening_friction {
        softening::sweep(&mut rep, log)?;
    }
    if cases.three_beams {
        beams::coarse(
            need(&scenes.three_beams, "three-beams.toml")?,
            &mut rep,
            log,
        )?;
    }
    Ok(rep)
}

fn fmt_opt(v: Option<f64>, prec: usize) -> String {
    v.map_or_else(|| "—".into(), |x| format!("{x:.prec$e}"))
}

fn pct(v: Option<f64>) -> String {
    v.map_or_else(|| "—".into(), |x| format!("{:+.2}", 100.0 * x))
}

/// validation.csv.
pub fn csv(rep: &Report) -> String {
    let mut t = CsvTable::new([
        "case",
        "parameter",
        "quantity",
        "frequency_domain",
        "time_domain",
        "error",
        "time_domain_half_range",
        "error_half_range",
        "note",
    ]);
    for r in &rep.rows {
        let o = |v: Option<f64>| v.map_or_else(String::new, exact);
        t.row([
            r.case.clone(),
            r.parameter.clone(),
            r.quantity.clone(),
            o(r.frequency_domain),
            exact(r.time_domain),
            o(r.error),
            o(r.time_domain_half_range),
            o(r.error_half_range),
            r.note.clone(),
        ]);
    }
    t.finish()
}

/// validation.md: one table per case, then its notes.
pub fn markdown(rep: &Report) -> String {
    let mut s = String::new();
    let mut cases: Vec<&str> = Vec::new();
    for r in &rep.rows {
        if !cases.contains(&r.case.as_str()) {
            cases.push(&r.case);
        }
    }
    for (c, _) in &rep.notes {
        if !cases.contains(&c.as_str()) {
            cases.push(c);
        }
    }
    for c in cases {
        let _ = writeln!(s, "### {c}\n");
        let rows: Vec<&Row> = rep.rows.iter().filter(|r| r.case == c).collect();
        if !rows.is_empty() {
            s.push_str("| parameter | quantity | frequency domain | time domain (1st harmonic / ∮F dδ) | error % | time domain (max−min)/2 | error % | note |\n|---|---|---:|---:|---:|---:|---:|---|\n");
            for r in rows {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {:.4e} | {} | {} | {} | {} |",
                    r.parameter,
                    r.quantity,
                    fmt_opt(r.frequency_domain, 4),
                    r.time_domain,
                    pct(r.error),
                    fmt_opt(r.time_domain_half_range, 4),
                    pct(r.error_half_range),
                    r.note
                );
            }
            s.push('\n');
        }
        for (_, n) in rep.notes.iter().filter(|(k, _)| k == c) {
            let _ = writeln!(s, "- {n}");
        }
        s.push('\n');
    }
    s
}

/// Writes validation.csv and validation.md, each atomically (a file is complete or
/// absent).
pub fn write(dir: &Path, rep: &Report) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let a = dir.join("validation.csv");
    let b = dir.join("validation.md");
    atomic::write_text(&a, &csv(rep))?;
    atomic::write_text(&b, &markdown(rep))?;
    Ok(vec![a, b])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_carry_relative_errors_and_missing_solutions() {
        let r = Row::new(
            "c",
            "p".into(),
            "q",
            Some(1.1),
            1.0,
            Some(2.0),
            String::new(),
        );
        assert!((r.error.unwrap() - 0.1).abs() < 1e-12);
        assert!((r.error_half_range.unwrap() + 0.45).abs() < 1e-12);
        let none = Row::new("c", "p".into(), "q", None, 1.0, Some(2.0), String::new());
        assert!(none.error.is_none() && none.error_half_range.is_none());
        let rep = Report {
            rows: vec![r, none],
            notes: vec![("c".into(), "a note".into())],
        };
        let md = markdown(&rep);
        assert!(
            md.contains("| p | q | 1.1000e0 | 1.0000e0 | +10.00 |"),
            "{md}"
        );
        assert!(md.contains("- a note"));
        assert_eq!(csv(&rep).lines().count(), 3);
    }
}
