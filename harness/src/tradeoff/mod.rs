//! `jointlin tradeoff SCENE`: one scene at one frequency, run at a ladder of fidelities;
//! each rung's wall time and its error against the most accurate time-domain run, for two
//! quantities: the first-harmonic amplitude at the first output point and the total joint
//! energy per cycle. Written as tradeoff.csv, tradeoff.md and tradeoff.svg (Pareto plot of
//! error vs wall time).
//!
//! The scene's `[effects]` choose the point model of the harmonic-balance rungs and of the
//! time domain (the three-direction point with `coupled_slip` or `normal_load_variation`,
//! else UINTER); the first-order rungs compute the thesis's model (they have no other).
//!
//! Rungs (frequency domain, fast mode, through the C API):
//! - linear stick: k_T0, no contact damping (no linearization at all);
//! - the thesis's Simpson rule for k* and the loop area at several interval counts
//!   (`jointlin_method`), default iteration tolerance;
//! - the default quadrature at several amplitude-iteration tolerances (the scene's own is
//!   "default");
//! - the multi-harmonic balance (`mode = "harmonic_balance"`) with H = 1, 3, 7, 15 and the
//!   default samples per period, Newton to 1e-6;
//! - for the thesis's point model, where the scene's interfaces allow it (Masing's rule, a
//!   linear normal law), the
//!   harmonic balance with `[effects] normal_load_variation` at H = 1, 3, 7: the normal
//!   load follows the normal law within the cycle, as it does in the time domain (UINTER
//!   at LINPER = 0: the friction limit follows the current pressure), where the thesis's
//!   model holds it at the static value;
//!
//! and the time domain (UINTER LINPER = 0): Newmark at several steps per period (settled
//! to a tolerance), fixed settling lengths, RK4 for small models, and the reference: the
//! finest step (4 × the finest rung's), settled to 1e-6 (FE models, Newmark) or 1e-8
//! (small models, RK4).
//!
//! Wall time: the whole computation at that frequency (model build, static step, solve);
//! frequency-domain rungs are repeated until 0.2 s have passed and averaged.

mod compare;
mod frequency_rungs;
pub mod lumped;
mod plot;
mod report;
mod time_rungs;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::model::Job;
use crate::run::{run, Extras};
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::Units;
use crate::solve::sweep::harmonic_fe_point3d::PointModel;
use crate::util::atomic;
use crate::util::csv_table::CsvTable;

use compare::{against_reference, ratios};
pub use report::{csv, markdown, write};

/// The harmonic-balance rungs.
pub const HARMONICS: [usize; 4] = [1, 3, 7, 15];
/// The harmonic-balance rungs with the normal load varying within the cycle.
pub const HARMONICS_NORMAL_LOAD: [usize; 3] = [1, 3, 7];
/// Their Newton tolerance (‖R‖ relative to the stuck response; far below the rungs'
/// differences).
const HB_TOLERANCE: f64 = 1e-6;

/// One rung of the ladder.
#[derive(Debug, Clone, Serialize)]
pub struct Rung {
    /// "linear", "simpson", "default", "tolerance", "harmonic", "normal_load", "time",
    /// "reference".
    pub family: &'static str,
    pub label: String,
    pub seconds: f64,
    /// First-harmonic amplitude at the first output (length).
    pub amplitude: f64,
    /// Total joint energy per cycle (force·length).
    pub energy: f64,
    /// |amplitude / reference − 1|.
    pub amplitude_error: f64,
    /// |energy / reference − 1| (1 when the rung has no joint dissipation).
    pub energy_error: f64,
    /// Converged (frequency domain) or periodic (time domain).
    pub converged: bool,
    pub frequency_domain: bool,
}

/// The study.
#[derive(Debug, Clone, Serialize)]
pub struct Tradeoff {
    pub scene: String,
    /// Frequency (1/time).
    pub freq: f64,
    pub output: String,
    /// The scene's units (column headers and table headings).
    pub units: Units,
    pub rungs: Vec<Rung>,
    /// Summary lines (speed ratios).
    pub summary: Vec<String>,
}

/// The job at one frequency.
pub fn at_frequency(job: &Job, f: f64) -> Job {
    let mut s = job.settings.clone();
    s.sweep.f_min = f;
    s.sweep.f_max = f;
    s.sweep.count = 1;
    s.sweep.refine.clear();
    job.with_settings(s)
}

/// The frequency of the largest response at the first output in the job's own sweep.
pub fn peak_frequency(job: &Job) -> Result<f64, String> {
    let r = run(job, Extras::default(), &|_, _, _| {}).map_err(|e| e.to_string())?;
    (0..r.main.freqs.len())
        .max_by(|&a, &b| {
            r.main.outputs[a][0]
                .norm()
                .total_cmp(&r.main.outputs[b][0].norm())
        })
        .map(|i| r.main.freqs[i])
        .ok_or_else(|| "the scene has no frequencies".into())
}

/// The ladder's frequency (1/time) and the job at it: `freq`, else the sweep's only
/// one, else the peak of the first output that `peak` finds in the sweep.
pub fn ladder_base(
    job: &Job,
    freq: Option<f64>,
    log: &dyn Fn(&str),
    peak: fn(&Job) -> Result<f64, String>,
) -> Result<(f64, Job), String> {
    let freqs = job.settings.frequencies();
    let f = match freq {
        Some(f) => f,
        None if freqs.len() == 1 => freqs[0],
        None => {
            log("finding the response peak of the scene's sweep");
            peak(job)?
        }
    };
    Ok((f, at_frequency(job, f)))
}

/// Runs the ladder of an FE scene or deck, or a [`Job`] of one ([`lumped::study`] for
/// lumped scenes). `freq`: the frequency (default: the sweep's only one, else its peak).
pub fn study(
    job: impl Into<Job>,
    freq: Option<f64>,
    log: &dyn Fn(&str),
) -> Result<Tradeoff, String> {
    let job: Job = job.into();
    let (f, base) = ladder_base(&job, freq, log, peak_frequency)?;
    let problem = base.build().map_err(|e| e.to_string())?;
    let n_free = problem.sys.dofs.n_free();
    let scene_model = PointModel::from_effects(&base.settings.effects);
    let mut rungs = frequency_rungs::run(&base, &problem, scene_model, log)?;
    let stopped = time_rungs::run(&base, time_rungs::ladder(n_free), log, &mut rungs)?;
    against_reference(&mut rungs);
    let mut summary = ratios(&rungs);
    summary.extend(stopped);
    Ok(Tradeoff {
        scene: job.file().to_string(),
        freq: f,
        output: base.settings.outputs[0].name.clone(),
        units: base.settings.units.clone(),
        rungs,
        summary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rung(family: &'static str, seconds: f64, a: f64, e: f64, converged: bool) -> Rung {
        Rung {
            family,
            label: format!("{family} {seconds}"),
            seconds,
            amplitude: 0.0,
            energy: 0.0,
            amplitude_error: a,
            energy_error: e,
            converged,
            frequency_domain: family != "time" && family != "reference",
        }
    }

    #[test]
    fn speed_ratio_picks_the_cheapest_time_run_as_accurate_as_the_default() {
        let r = vec![
            rung("default", 0.01, 1e-3, 2e-2, true),
            // Too inaccurate in energy, cheapest: skipped.
            rung("time", 0.5, 1e-4, 5e-2, true),
            // As accurate but not periodic: skipped.
            rung("time", 1.0, 1e-4, 1e-3, false),
            rung("time", 2.0, 1e-4, 1e-2, true),
            rung("time", 3.0, 1e-5, 1e-3, true),
            rung("reference", 10.0, 0.0, 0.0, true),
        ];
        let s = ratios(&r);
        assert!(s[0].contains("200× slower"), "{}", s[0]);
        assert!(s[1].contains("1000×"), "{}", s[1]);
    }

    /// tradeoff.csv and tradeoff.md carry the scene's units (here m, kN, ms, angular).
    #[test]
    fn tables_carry_the_scene_units() {
        let t = Tradeoff {
            scene: "s.toml".into(),
            freq: 1.0,
            output: "tip".into(),
            units: Units {
                length: "m".into(),
                force: "kN".into(),
                time: "ms".into(),
                mass: "t".into(),
                frequency: Some("rad/ms".into()),
            },
            rungs: vec![rung("default", 0.01, 1e-3, 2e-2, true)],
            summary: Vec::new(),
        };
        let head = csv(&t).lines().next().unwrap().to_string();
        assert_eq!(
            head,
            "family,label,frequency_domain,wall_time_s,amplitude_m,amplitude_error,energy_per_cycle_kN_m,energy_error,converged"
        );
        let md = markdown(&t);
        assert!(md.contains("at 6.283185 rad/ms"), "{md}");
        assert!(
            md.contains("amplitude [m]") && md.contains("energy per cycle [kN·m]"),
            "{md}"
        );
    }
}
