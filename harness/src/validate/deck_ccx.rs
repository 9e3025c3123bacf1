//! The deck path against CalculiX on the non-conforming three-layer stack
//! ([`super::stack_deck`]): ccx's `*FREQUENCY` on the `*TIE` deck and on one layer
//! alone (the free-sliding bound: identical layers sliding freely bend as one layer
//! does), against the modes with every joint stuck (`jointlin modes`) of the same decks
//! read through the input path (`Job::load`): with `*TIE` (penalty), with `*CONTACT
//! PAIR` stuck (μ and k_T0 large) and with k_T0 → 0 (sliding).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::ccx::run_frequencies;
use super::stack_deck::{stack_deck, Joining};
use crate::model::Job;
use crate::solve::modal_stuck::{stuck_modes, ModeCount};

/// Modes compared.
pub const MODES: usize = 4;
/// Stuck contact: μ, k_T0 = k_N per area (N/mm³, about 1e4 × E / thickness), pressure (MPa).
pub const STUCK: Joining = Joining::Contact {
    mu: 1e3,
    k_t0: 1e9,
    k_n: 1e9,
    pressure: 1.0,
};
/// Sliding contact: k_T0 per area 1e-3 N/mm³ (1e-8 × E / thickness).
pub const SLIDING: Joining = Joining::Contact {
    mu: 1e3,
    k_t0: 1e-3,
    k_n: 1e9,
    pressure: 1.0,
};

/// Frequencies (Hz) of every case.
#[derive(Debug, Clone)]
pub struct Comparison {
    pub ccx_tie: Vec<f64>,
    pub ccx_single: Vec<f64>,
    pub tie: Vec<f64>,
    pub stuck: Vec<f64>,
    pub sliding: Vec<f64>,
}

/// The decks: tie, contact stuck, contact sliding, one layer (file names).
fn decks() -> [(&'static str, String); 4] {
    [
        ("stack-tie", stack_deck(Joining::Tie, MODES, None)),
        ("stack-stuck", stack_deck(STUCK, MODES, None)),
        ("stack-sliding", stack_deck(SLIDING, MODES, None)),
        ("layer", stack_deck(Joining::Single, MODES, None)),
    ]
}

/// Writes the four decks into `dir`; returns their paths.
pub fn write_decks(dir: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    decks()
        .into_iter()
        .map(|(name, text)| {
            let p = dir.join(format!("{name}.inp"));
            std::fs::write(&p, text).map_err(|e| format!("{}: {e}", p.display()))?;
            Ok(p)
        })
        .collect()
}

/// The lowest `MODES` stuck-joint frequencies (Hz) of deck `path`, as `jointlin modes`.
pub fn deck_modes(path: &Path) -> Result<Vec<f64>, String> {
    let job = Job::load(path).map_err(|e| e.to_string())?;
    let m = stuck_modes(job, ModeCount::Exactly(MODES))?;
    Ok(m.band.modes.frequencies_hz())
}

/// Runs ccx and the deck path on the decks written into `dir`.
pub fn comparison(dir: &Path) -> Result<Comparison, String> {
    let files = write_decks(dir)?;
    let [tie, stuck, sliding] = [0, 1, 2].map(|i| files[i].clone());
    let ccx = |name: &str| {
        let text =
            std::fs::read_to_string(dir.join(format!("{name}.inp"))).map_err(|e| e.to_string())?;
        run_frequencies(&text, &dir.join("ccx"), name).map_err(|e| e.to_string())
    };
    Ok(Comparison {
        ccx_tie: ccx("stack-tie")?,
        ccx_single: ccx("layer")?,
        tie: deck_modes(&tie)?,
        stuck: deck_modes(&stuck)?,
        sliding: deck_modes(&sliding)?,
    })
}

/// Relative differences below this are shown as agreement (the tests hold 1e-6).
const AGREE: f64 = 1e-6;

impl Comparison {
    /// The Markdown table: per mode the frequencies and the differences to ccx.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "| mode | ccx `*TIE` (Hz) | jointlin `*TIE` | diff | `*CONTACT PAIR` stuck | diff | ccx one layer (Hz) | `*CONTACT PAIR` sliding | diff |"
        );
        let _ = writeln!(s, "|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
        // Below 1e-6 a difference is the two eigen solvers' tolerance and ccx's printed
        // digits, and its value changes with the machine: the table says only that.
        let d = |a: f64, b: f64| match a / b - 1.0 {
            r if r.abs() < AGREE => format!("< {AGREE:.0e}"),
            r => format!("{r:+.1e}"),
        };
        for i in 0..MODES.min(self.ccx_tie.len()) {
            let slide = (i == 0).then(|| {
                (
                    format!("{:.2}", self.ccx_single[0]),
                    format!("{:.2}", self.sliding[0]),
                    d(self.sliding[0], self.ccx_single[0]),
                )
            });
            let (a, b, c) = slide.unwrap_or(("".into(), "".into(), "".into()));
            let _ = writeln!(
                s,
                "| {} | {:.2} | {:.2} | {} | {:.2} | {} | {a} | {b} | {c} |",
                i + 1,
                self.ccx_tie[i],
                self.tie[i],
                d(self.tie[i], self.ccx_tie[i]),
                self.stuck[i],
                d(self.stuck[i], self.ccx_tie[i]),
            );
        }
        s
    }
}
