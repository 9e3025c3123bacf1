//! `jointlin effects SCENE`: what the contact effects beyond the thesis change and cost
//! on one scene (docs/contact3d.md §6). The scene's harmonic-balance sweep is run four
//! times: the thesis's point model (two independent tangential directions at the static
//! normal load), with `coupled_slip`, with `normal_load_variation` and with both; then
//! first order (mode fast) with the thesis's model and with `coupled_slip` (the
//! describing function of each point's ellipse). A scene in mode fast gets the two
//! first-order variants only (a balance of a large model can take hours). Per variant
//! the response peak of the
//! first output, the dissipated power there and at its largest, the three-direction
//! point's steps and the wall time.

mod report;

pub use report::{csv, markdown, write};

use std::time::Instant;

use crate::capi;
use crate::model::Job;
use crate::run::{run, Extras, RunError};
use crate::settings::{Effects, Mode, RunSettings, Units};
use crate::solve::sweep::SweepResult;

/// One variant of the point model and what it gave.
pub struct Variant {
    pub label: &'static str,
    pub normal_load_variation: bool,
    pub coupled_slip: bool,
    /// Solved first order (mode fast) instead of by the harmonic balance.
    pub first_order: bool,
    /// Frequency of the first output's largest amplitude (1/time) and that amplitude
    /// (length), from the parabola through the largest solved amplitude and its solved
    /// neighbours (the grid's point where it is at an end); `None` when none was solved.
    pub peak: Option<(f64, f64)>,
    /// Dissipated power at the peak and its largest over the sweep (force·length/time).
    pub power_at_peak: f64,
    pub power_max: f64,
    pub converged: usize,
    pub frequencies: usize,
    /// `jointlin_point3d_step` calls of the variant.
    pub point3d_steps: u64,
    pub seconds: f64,
    pub sweep: SweepResult,
}

/// The study: the scene's name, units, first output's name and the four variants.
pub struct EffectsStudy {
    pub scene: String,
    pub units: Units,
    pub output: String,
    pub variants: Vec<Variant>,
}

/// Why the study cannot run.
#[derive(Debug, thiserror::Error)]
pub enum EffectsError {
    #[error("the effects are computed by the harmonic balance, coupled slip also first order: set [iteration] mode = \"harmonic_balance\" (all variants) or \"fast\" (the first-order ones) in the scene")]
    NotHarmonicBalance,
    #[error("the model has no outputs: the peak is that of the first output")]
    NoOutput,
    #[error("{label}: {source}")]
    Run {
        label: &'static str,
        source: RunError,
    },
}

/// The variants in order: label, normal_load_variation, coupled_slip, first order.
pub const VARIANTS: [(&str, bool, bool, bool); 6] = [
    (
        "thesis: independent directions, static N",
        false,
        false,
        false,
    ),
    ("coupled slip", false, true, false),
    ("normal load variation", true, false, false),
    ("both", true, true, false),
    ("thesis, first order", false, false, true),
    ("coupled slip, first order", false, true, true),
];

/// Runs the sweep of `job` (a scene, a deck or a [`Job`]) with each variant (its own
/// `[effects]` choice of the two switches is replaced; everything else is its own).
/// `progress` gets a line per variant.
pub fn study(job: impl Into<Job>, progress: &dyn Fn(&str)) -> Result<EffectsStudy, EffectsError> {
    let job: Job = job.into();
    let chosen =
        variants_for(job.settings.iteration.mode).ok_or(EffectsError::NotHarmonicBalance)?;
    let mut output = None;
    let mut variants = Vec::with_capacity(chosen.len());
    for (label, normal, coupled, first_order) in chosen {
        progress(&format!("{label} …"));
        let s = job.with_settings(with_point_model(
            &job.settings,
            normal,
            coupled,
            first_order,
        ));
        let (r, steps, seconds) = measured(|| run(&s, Extras::default(), &|_, _, _| {}));
        let r = r.map_err(|source| EffectsError::Run { label, source })?;
        let first = r.problem.outputs.first().ok_or(EffectsError::NoOutput)?;
        output.get_or_insert_with(|| first.name.clone());
        let flags = (normal, coupled, first_order);
        variants.push(variant(label, flags, r.main, seconds, steps));
    }
    Ok(EffectsStudy {
        scene: job.file().to_string(),
        units: job.settings.units.clone(),
        output: output.unwrap_or_default(),
        variants,
    })
}

/// The variants a scene in `mode` is solved with: all of them in the harmonic balance,
/// the first-order ones in mode fast, none in mode thesis.
pub fn variants_for(mode: Mode) -> Option<Vec<(&'static str, bool, bool, bool)>> {
    match mode {
        Mode::HarmonicBalance => Some(VARIANTS.to_vec()),
        Mode::Fast => Some(VARIANTS.iter().copied().filter(|v| v.3).collect()),
        Mode::Thesis => None,
    }
}

/// How the rows were solved, for the table's caption.
pub fn solved_by(mode: Mode) -> &'static str {
    if mode == Mode::Fast {
        "first order (mode fast)"
    } else {
        "harmonic balance (first-order rows: mode fast, no balance)"
    }
}

/// `settings` with the point model (normal_load_variation, coupled_slip) in place of
/// their own, solved first order (mode fast) when `first_order`.
pub fn with_point_model(
    settings: &RunSettings,
    normal_load_variation: bool,
    coupled_slip: bool,
    first_order: bool,
) -> RunSettings {
    let mut s = settings.clone();
    if first_order {
        s.iteration.mode = Mode::Fast;
    }
    s.effects = Effects {
        normal_load_variation,
        coupled_slip,
        ..s.effects
    };
    s
}

/// `work`'s result, the three-direction point's steps it made and its wall time (s).
pub fn measured<T>(work: impl FnOnce() -> T) -> (T, u64, f64) {
    let steps0 = capi::point3d_steps();
    let t = Instant::now();
    let r = work();
    (r, capi::point3d_steps() - steps0, t.elapsed().as_secs_f64())
}

fn variant(
    label: &'static str,
    (normal_load_variation, coupled_slip, first_order): (bool, bool, bool),
    sweep: SweepResult,
    seconds: f64,
    point3d_steps: u64,
) -> Variant {
    let solved: Vec<usize> = (0..sweep.freqs.len())
        .filter(|&i| sweep.converged[i] && sweep.failure(i).is_none())
        .collect();
    let amp = |i: usize| sweep.outputs[i][0].norm();
    let at_peak = solved
        .iter()
        .copied()
        .max_by(|&a, &b| amp(a).total_cmp(&amp(b)));
    let power_max = solved
        .iter()
        .map(|&i| sweep.power[i])
        .fold(0.0f64, f64::max);
    Variant {
        label,
        normal_load_variation,
        coupled_slip,
        first_order,
        peak: at_peak.map(|i| {
            let k = solved.iter().position(|&j| j == i).unwrap_or(0);
            match (k.checked_sub(1).map(|k| solved[k]), solved.get(k + 1)) {
                (Some(a), Some(&b)) => vertex(
                    [sweep.freqs[a], sweep.freqs[i], sweep.freqs[b]],
                    [amp(a), amp(i), amp(b)],
                ),
                _ => (sweep.freqs[i], amp(i)),
            }
        }),
        power_at_peak: at_peak.map_or(0.0, |i| sweep.power[i]),
        power_max,
        converged: solved.len(),
        frequencies: sweep.freqs.len(),
        point3d_steps,
        seconds,
        sweep,
    }
}

/// Vertex (x, y) of the parabola through three points with the largest y in the middle.
fn vertex(x: [f64; 3], y: [f64; 3]) -> (f64, f64) {
    let (d1, d2) = ((y[1] - y[0]) / (x[1] - x[0]), (y[2] - y[1]) / (x[2] - x[1]));
    let c = (d2 - d1) / (x[2] - x[0]);
    if c.is_nan() || c >= 0.0 {
        return (x[1], y[1]);
    }
    // y = y₁ + b (x − x₁) + c (x − x₁)², b the slope at x₁.
    let b = d1 + c * (x[1] - x[0]);
    let dx = (-b / (2.0 * c)).clamp(x[0] - x[1], x[2] - x[1]);
    (x[1] + dx, y[1] + b * dx + c * dx * dx)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_vertex_of_a_sampled_parabola_is_exact() {
        let y = |x: f64| 3.0 - 0.5 * (x - 1.3).powi(2);
        let (x, v) = super::vertex([0.5, 1.0, 2.5], [y(0.5), y(1.0), y(2.5)]);
        assert!(
            (x - 1.3).abs() < 1e-12 && (v - 3.0).abs() < 1e-12,
            "{x} {v}"
        );
    }
}
