//! Files of a loss study: loss.csv, loss.md (with the comparison against published
//! points), loss.svg, and the contact maps of the scene's own torque at the largest
//! amplitude (contact_ratio.svg, contact_energy.svg, `contact_<interface>.vtu`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::{plot, LossStudySpec, Sample, StudyResult};
use crate::model::Job;
use crate::report::contact_map::{self as maps, MapKind};
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;

/// Power (reported unit) of a curve at `amplitude`: a sample's own (reached within the
/// level search's tolerance), or by linear interpolation between its samples; `None`
/// outside them.
pub fn interpolate(samples: &[Sample], amplitude: f64, power_factor: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = samples
        .iter()
        .map(|s| (s.amplitude, s.power * power_factor))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // A sample reached its target to the level's tolerance, not exactly.
    let at = |a: f64| (amplitude - a).abs() <= 2.0 * super::LEVEL_TOL * a.abs();
    if let Some(&(_, p)) = pts.iter().find(|(a, _)| at(*a)) {
        return Some(p);
    }
    pts.windows(2).find_map(|w| {
        let ((a0, p0), (a1, p1)) = (w[0], w[1]);
        (amplitude >= a0 * (1.0 - 1e-9) && amplitude <= a1 * (1.0 + 1e-9))
            .then(|| p0 + (p1 - p0) * (amplitude - a0) / (a1 - a0))
    })
}

/// Unit of a torque in the scene's units (force·length, e.g. N·mm).
pub fn torque_unit(job: &Job) -> String {
    format!("{}·{}", job.settings.units.force, job.settings.units.length)
}

/// loss.csv text: torque (force·length), amplitude of the output at resonance (length),
/// resonance frequency, power (the study's power unit), excitation scale, max A/δ*.
pub fn csv(job: &Job, st: &LossStudySpec, r: &StudyResult) -> String {
    let u = ColumnUnits::new(&job.settings.units);
    let fu = frequency_unit(&job.settings.units);
    let mut t = CsvTable::new([
        format!("torque_{}", u.energy),
        format!("amplitude_{}", u.length),
        fu.column.clone(),
        format!("power_{}", st.power_unit),
        "excitation_scale".into(),
        "max_amplitude_ratio".into(),
    ]);
    for (torque, samples) in &r.curves {
        for x in samples {
            t.row(
                [
                    *torque,
                    x.amplitude,
                    fu.show(x.freq),
                    x.power * st.power_factor,
                    x.scale,
                    x.max_ratio(),
                ]
                .map(exact),
            );
        }
    }
    t.finish()
}

/// loss.md text: the curves and the comparison with the reference points.
pub fn markdown(job: &Job, st: &LossStudySpec, r: &StudyResult) -> String {
    let au = &st.amplitude_unit;
    let pu = &st.power_unit;
    let tu = torque_unit(job);
    let fu = frequency_unit(&job.settings.units);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Joint power loss at resonance, `{}` ({}); output `{}`.\n",
        job.settings.title,
        job.file(),
        st.output
    );
    let _ = writeln!(
        s,
        "| torque [{tu}] | resonance [{}] | amplitude [{au}] | power [{pu}] | max A/δ* |\n|---:|---:|---:|---:|---:|",
        fu.text
    );
    for (t, samples) in &r.curves {
        for x in samples {
            let _ = writeln!(
                s,
                "| {t} | {:.1} | {:.2} | {:.4} | {:.3} |",
                fu.show(x.freq),
                x.amplitude / st.amplitude_factor,
                x.power * st.power_factor,
                x.max_ratio()
            );
        }
    }
    if !st.reference.is_empty() {
        let _ = writeln!(
            s,
            "\n| torque [{tu}] | amplitude [{au}] | reference [{pu}] | this model [{pu}] | deviation | source's own deviation | reference from |\n|---:|---:|---:|---:|---:|---:|---|"
        );
        for p in &st.reference {
            let ours = r
                .curves
                .iter()
                .find(|(t, _)| *t == p.torque)
                .and_then(|(_, c)| interpolate(c, p.amplitude, st.power_factor));
            let (o, d) = match ours {
                Some(o) => (
                    format!("{o:.3}"),
                    format!("{:+.1} %", 100.0 * (o - p.power) / p.power),
                ),
                None => ("–".into(), "–".into()),
            };
            let src = p
                .source_deviation_percent
                .map_or("–".into(), |v| format!("{v} %"));
            let _ = writeln!(
                s,
                "| {} | {:.1} | {:.3} | {o} | {d} | {src} | {} |",
                p.torque,
                p.amplitude / st.amplitude_factor,
                p.power,
                p.note
            );
        }
    }
    let _ = writeln!(s, "\n{} steady-state solves.", r.solves);
    s
}

/// Writes every file into `dir`; returns the paths.
pub fn write(dir: &Path, job: &Job, r: &StudyResult) -> Result<Vec<PathBuf>, String> {
    let st = job
        .settings
        .loss_study
        .as_ref()
        .ok_or("the scene has no [loss_study]")?;
    let io = |e: std::io::Error| format!("{}: {e}", dir.display());
    std::fs::create_dir_all(dir).map_err(io)?;
    let mut out = Vec::new();
    let mut put = |name: &str, text: String| -> Result<(), String> {
        let p = dir.join(name);
        crate::util::atomic::write_text(&p, &text)?;
        out.push(p);
        Ok(())
    };
    put("loss.csv", csv(job, st, r))?;
    put("loss.md", markdown(job, st, r))?;
    let p = dir.join("loss.svg");
    crate::util::atomic::with_temp(&p, |t| {
        plot::curves(t, job.title(), &torque_unit(job), st, r)
    })?;
    out.push(p);
    if let Some((op, sample)) = &r.maps {
        let vals = maps::values(&op.problem, &op.stat.pressure, &sample.points);
        for (k, i) in op.problem.interfaces.iter().enumerate() {
            let p = dir.join(format!("contact_{}.vtu", i.name));
            crate::util::atomic::write_text(&p, &maps::vtu(&op.problem, k, &vals))?;
            out.push(p);
        }
        let what = format!(
            "{} at {:.2} {} and {:.1} Hz",
            st.output,
            sample.amplitude / st.amplitude_factor,
            st.amplitude_unit,
            sample.freq
        );
        for (name, kind, title) in [
            ("contact_ratio.svg", MapKind::Ratio, "stick/slip A/δ*"),
            (
                "contact_energy.svg",
                MapKind::EnergyDensity,
                "dissipated energy density",
            ),
        ] {
            let p = dir.join(name);
            crate::util::atomic::with_temp(&p, |t| {
                maps::svg(
                    t,
                    &format!("{title}, {what}"),
                    &job.settings.units,
                    &op.problem,
                    &vals,
                    kind,
                )
            })?;
            out.push(p);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::scene::Scene;

    /// loss.csv and loss.md carry the scene's units (knife-coarse: N, mm, s; W, µm).
    #[test]
    fn tables_carry_the_scene_units() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
        let scene = Job::from(&Scene::load(&path).unwrap());
        let st = scene.settings.loss_study.clone().unwrap();
        let sample = Sample {
            freq: 31700.0,
            scale: 1.0,
            amplitude: 2e-3,
            power: 1.0,
            points: Vec::new(),
        };
        let r = StudyResult {
            curves: vec![(1500.0, vec![sample])],
            solves: 1,
            maps: None,
        };
        let head = csv(&scene, &st, &r).lines().next().unwrap().to_string();
        assert_eq!(
            head,
            "torque_N_mm,amplitude_mm,frequency_Hz,power_W,excitation_scale,max_amplitude_ratio"
        );
        let md = markdown(&scene, &st, &r);
        assert!(
            md.contains("| torque [N·mm] | resonance [Hz] | amplitude [µm] | power [W] |"),
            "{md}"
        );
    }

    fn sample(amplitude: f64, power: f64) -> Sample {
        Sample {
            freq: 1.0,
            scale: 1.0,
            amplitude,
            power,
            points: Vec::new(),
        }
    }

    #[test]
    fn a_reference_at_a_sampled_amplitude_needs_no_neighbour() {
        // One amplitude in the study, and the reference exactly there.
        assert_eq!(
            interpolate(&[sample(0.012, 3.0)], 0.012, 1e-3),
            Some(3.0e-3)
        );
        // As reached by the level search: within its tolerance of the target.
        let reached = 0.012 * (1.0 + 0.9 * super::super::LEVEL_TOL);
        assert_eq!(
            interpolate(&[sample(reached, 3.0)], 0.012, 1e-3),
            Some(3.0e-3)
        );
        let two = [sample(0.01, 1.0), sample(0.02, 3.0)];
        assert!((interpolate(&two, 0.015, 1.0).unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(interpolate(&two, 0.02, 1.0), Some(3.0));
        assert_eq!(interpolate(&two, 0.03, 1.0), None);
        assert_eq!(interpolate(&[sample(0.012, 3.0)], 0.013, 1.0), None);
    }
}
