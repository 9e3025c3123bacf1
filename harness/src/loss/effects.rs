//! `jointlin loss SCENE --effects A,…`: what the contact effects beyond the thesis
//! change in the loss study (docs/contact3d.md §6). At the first reference point's torque
//! the scene's harmonic-balance model is solved with each point model of
//! [`crate::effects::VARIANTS`] (the thesis's, coupled slip, normal load variation, both);
//! per model and amplitude the resonance and the joint power loss there, and per model
//! the three-direction point's steps and the wall time.

use std::fmt::Write as _;

use super::{powers_at, report::torque_unit, LossError};
use crate::effects::{measured, with_point_model, VARIANTS};
use crate::input::scene::units::frequency_unit;
use crate::input::scene::{Mode, Scene};
use crate::util::csv_table::CsvTable;

/// Point models solved (progress steps).
pub const VARIANT_COUNT: usize = VARIANTS.len();

/// One point model at one amplitude.
#[derive(Debug, Clone)]
pub struct EffectsRow {
    pub label: &'static str,
    /// Output amplitude (length).
    pub amplitude: f64,
    /// Resonance (1/time).
    pub freq: f64,
    /// Joint power loss (the study's power unit).
    pub power: f64,
    /// `jointlin_point3d_step` calls and wall time of the model (all its amplitudes).
    pub point3d_steps: u64,
    pub seconds: f64,
}

/// Solves every point model at `amplitudes` (length) at the first reference torque.
/// `progress` gets a line per model.
pub fn study(
    scene: &Scene,
    amplitudes: &[f64],
    progress: &dyn Fn(&str),
) -> Result<Vec<EffectsRow>, LossError> {
    let st = scene.spec.loss_study.as_ref().ok_or(LossError::NoStudy)?;
    if scene.spec.iteration.mode != Mode::HarmonicBalance {
        return Err(LossError::Spec(
            "--effects: the effects are computed by the harmonic balance: set [iteration] mode = \"harmonic_balance\"".into(),
        ));
    }
    let torque = st
        .reference
        .first()
        .ok_or_else(|| LossError::Spec("--effects needs a reference point".into()))?
        .torque;
    let mut rows = Vec::with_capacity(VARIANTS.len() * amplitudes.len());
    for (label, normal, coupled) in VARIANTS {
        progress(&format!("{label} …"));
        let s = with_point_model(scene, normal, coupled);
        let (got, point3d_steps, seconds) = measured(|| powers_at(&s, torque, amplitudes));
        let (got, _) = got?;
        rows.extend(got.iter().map(|g| EffectsRow {
            label,
            amplitude: g.amplitude,
            freq: g.freq,
            power: g.power * st.power_factor,
            point3d_steps,
            seconds,
        }));
    }
    Ok(rows)
}

/// Markdown table: per amplitude and model the resonance and the loss, each against the
/// thesis's model (the first) at that amplitude.
pub fn markdown(scene: &Scene, rows: &[EffectsRow]) -> String {
    let Some(st) = scene.spec.loss_study.as_ref() else {
        return String::new();
    };
    let torque = st.reference.first().map_or(0.0, |r| r.torque);
    let fu = frequency_unit(&scene.spec.units);
    let (au, af, pu) = (&st.amplitude_unit, st.amplitude_factor, &st.power_unit);
    let mut s = format!(
        "Contact effects in the loss study, `{}` ({}), harmonic balance, torque {torque} {}: \
         resonance and joint power loss per point model, changes against the thesis's model \
         at the same amplitude.\n\n",
        scene.spec.title,
        scene.file,
        torque_unit(scene)
    );
    let _ = writeln!(
        s,
        "| amplitude [{au}] | point model | resonance [{f}] | Δ resonance [{f}] | power [{pu}] | Δ power | 3D point steps | wall time [s] |\n|---:|---|---:|---:|---:|---:|---:|---:|",
        f = fu.text
    );
    let mut amplitudes: Vec<f64> = rows.iter().map(|r| r.amplitude).collect();
    amplitudes.sort_by(f64::total_cmp);
    amplitudes.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
    for a in amplitudes {
        let same: Vec<&EffectsRow> = rows
            .iter()
            .filter(|r| (r.amplitude - a).abs() <= 1e-9 * a.abs())
            .collect();
        let Some(base) = same.first() else { continue };
        for r in &same {
            let _ = writeln!(
                s,
                "| {:.2} | {} | {:.1} | {:+.1} | {:.4} | {:+.1} % | {} | {:.0} |",
                a / af,
                r.label,
                fu.show(r.freq),
                fu.show(r.freq) - fu.show(base.freq),
                r.power,
                100.0 * (r.power / base.power - 1.0),
                r.point3d_steps,
                r.seconds
            );
        }
    }
    s
}

/// CSV of the rows (scene units in the headers).
pub fn csv(scene: &Scene, rows: &[EffectsRow]) -> String {
    let fu = frequency_unit(&scene.spec.units);
    let (au, af, pu) = scene.spec.loss_study.as_ref().map_or(("", 1.0, ""), |st| {
        (
            st.amplitude_unit.as_str(),
            st.amplitude_factor,
            st.power_unit.as_str(),
        )
    });
    let mut t = CsvTable::new([
        "point_model".to_string(),
        format!("amplitude_{au}"),
        format!("resonance_{}", fu.column),
        format!("power_{pu}"),
        "point3d_steps".into(),
        "wall_time_s".into(),
    ]);
    for r in rows {
        t.row([
            r.label.to_string(),
            format!("{:.6e}", r.amplitude / af),
            format!("{:.10e}", fu.show(r.freq)),
            format!("{:.10e}", r.power),
            r.point3d_steps.to_string(),
            format!("{:.3}", r.seconds),
        ]);
    }
    t.finish()
}
