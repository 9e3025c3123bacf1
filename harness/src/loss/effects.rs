//! `jointlin loss SCENE --effects A,…`: what the contact effects beyond the thesis
//! change in the loss study (docs/contact3d.md §6). At the first reference point's torque
//! the scene's harmonic-balance model is solved with each point model of
//! [`crate::effects::VARIANTS`] (the thesis's, coupled slip, normal load variation, both,
//! and first order with the thesis's model and with coupled slip);
//! per model and amplitude the resonance and the joint power loss there, and per model
//! the three-direction point's steps and the wall time.

use std::fmt::Write as _;

use super::{powers_at, report::torque_unit, LossError};
use crate::effects::{measured, solved_by, variants_for, with_point_model};
use crate::model::Job;
use crate::settings::units::frequency_unit;
use crate::settings::Mode;
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;

/// Point models solved for a scene in `mode` (progress steps).
pub fn variant_count(mode: Mode) -> usize {
    variants_for(mode).map_or(0, |v| v.len())
}

/// One point model at one amplitude.
#[derive(Debug, Clone)]
pub struct EffectsRow {
    pub label: &'static str,
    /// Output amplitude asked for and reached (length; the level search's tolerance
    /// apart).
    pub target: f64,
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
    job: impl Into<Job>,
    amplitudes: &[f64],
    progress: &dyn Fn(&str),
) -> Result<Vec<EffectsRow>, LossError> {
    let job: &Job = &job.into();
    let st = job.settings.loss_study.as_ref().ok_or(LossError::NoStudy)?;
    let Some(chosen) = variants_for(job.settings.iteration.mode) else {
        return Err(LossError::Spec(
            "--effects: the effects are computed by the harmonic balance, coupled slip also first order: set [iteration] mode = \"harmonic_balance\" (all point models) or \"fast\" (the first-order ones)".into(),
        ));
    };
    let torque = st
        .reference
        .first()
        .ok_or_else(|| LossError::Spec("--effects needs a reference point".into()))?
        .torque;
    let mut rows = Vec::with_capacity(chosen.len() * amplitudes.len());
    for (label, normal, coupled, first_order) in chosen {
        progress(&format!("{label} …"));
        let s = job.with_settings(with_point_model(
            &job.settings,
            normal,
            coupled,
            first_order,
        ));
        let (got, point3d_steps, seconds) = measured(|| powers_at(&s, torque, amplitudes));
        let (got, _) = got?;
        rows.extend(got.iter().zip(amplitudes).map(|(g, &target)| EffectsRow {
            label,
            target,
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
pub fn markdown(job: &Job, rows: &[EffectsRow]) -> String {
    let Some(st) = job.settings.loss_study.as_ref() else {
        return String::new();
    };
    let torque = st.reference.first().map_or(0.0, |r| r.torque);
    let fu = frequency_unit(&job.settings.units);
    let (au, af, pu) = (&st.amplitude_unit, st.amplitude_factor, &st.power_unit);
    let mut s = format!(
        "Contact effects in the loss study, `{}` ({}), {}, torque {torque} {}: \
         resonance and joint power loss per point model, changes against the thesis's model \
         at the same amplitude.\n\n",
        job.settings.title,
        job.file(),
        solved_by(job.settings.iteration.mode),
        torque_unit(job)
    );
    let _ = writeln!(
        s,
        "| amplitude [{au}] | point model | resonance [{f}] | Δ resonance [{f}] | power [{pu}] | Δ power | 3D point steps | wall time [s] |\n|---:|---|---:|---:|---:|---:|---:|---:|",
        f = fu.text
    );
    let mut targets: Vec<f64> = rows.iter().map(|r| r.target).collect();
    targets.sort_by(f64::total_cmp);
    targets.dedup();
    for a in targets {
        // In the order of the point models (the thesis's first).
        let same: Vec<&EffectsRow> = rows.iter().filter(|r| r.target == a).collect();
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
pub fn csv(job: &Job, rows: &[EffectsRow]) -> String {
    let fu = frequency_unit(&job.settings.units);
    let (au, af, pu) = job
        .settings
        .loss_study
        .as_ref()
        .map_or(("", 1.0, ""), |st| {
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
            exact(r.amplitude / af),
            exact(fu.show(r.freq)),
            exact(r.power),
            r.point3d_steps.to_string(),
            exact(r.seconds),
        ]);
    }
    t.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::VARIANTS;
    use crate::input::scene::Scene;

    #[test]
    fn each_amplitude_compares_its_models_with_the_thesis_model() {
        // Reached amplitudes differ by the level search's tolerance; rows group by the
        // amplitude asked for, in the point models' order.
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scenes/knife-coarse.toml"
        ))
        .unwrap();
        let scene = Job::from(&Scene::parse("knife-coarse.toml", &text).unwrap());
        let row = |k: usize, target: f64, power: f64| EffectsRow {
            label: VARIANTS[k].0,
            target,
            amplitude: target * (1.0 + 1e-4 * k as f64),
            freq: 31_820.0 + k as f64,
            power,
            point3d_steps: 0,
            seconds: 1.0,
        };
        let rows = vec![
            row(0, 0.012, 2.0),
            row(0, 0.015, 4.0),
            row(1, 0.012, 2.2),
            row(1, 0.015, 4.0),
        ];
        let md = markdown(&scene, &rows);
        let lines: Vec<&str> = md.lines().filter(|l| l.starts_with("| 1")).collect();
        assert_eq!(lines.len(), 4, "{md}");
        assert!(lines[0].starts_with("| 12.00 | thesis"), "{md}");
        assert!(
            lines[1].starts_with("| 12.00 | coupled slip") && lines[1].contains("| +10.0 % |"),
            "{md}"
        );
        assert!(
            lines[2].starts_with("| 15.00 | thesis") && lines[3].contains("| +0.0 % |"),
            "{md}"
        );
        assert!(
            md.contains("resonance [Hz]") && md.contains("power [W]"),
            "{md}"
        );
    }
}
