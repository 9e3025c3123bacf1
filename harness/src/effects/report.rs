//! The study's files: effects.csv, effects.md (headings in the scene's units) and
//! effects.svg (the first output's FRF of every variant), each written atomically.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::EffectsStudy;
use crate::report::frf_plot::{frf_curves, FrfCurve};
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::Mode;
use crate::util::atomic;
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;

/// effects.csv: one row per variant.
pub fn csv(t: &EffectsStudy) -> String {
    let u = ColumnUnits::new(&t.units);
    let fu = frequency_unit(&t.units);
    let mut table = CsvTable::new([
        "variant".to_string(),
        "normal_load_variation".into(),
        "coupled_slip".into(),
        "first_order".into(),
        format!("peak_{}", fu.column),
        format!("peak_{}_amp_{}", t.output, u.length),
        format!("power_at_peak_{}", u.power),
        format!("power_max_{}", u.power),
        "converged".into(),
        "frequencies".into(),
        "point3d_steps".into(),
        "wall_time_s".into(),
    ]);
    for v in &t.variants {
        let (f, a) = v.peak.map_or((String::new(), String::new()), |(f, a)| {
            (exact(fu.show(f)), exact(a))
        });
        table.row([
            v.label.to_string(),
            v.normal_load_variation.to_string(),
            v.coupled_slip.to_string(),
            v.first_order.to_string(),
            f,
            a,
            exact(v.power_at_peak),
            exact(v.power_max),
            v.converged.to_string(),
            v.frequencies.to_string(),
            v.point3d_steps.to_string(),
            exact(v.seconds),
        ]);
    }
    table.finish()
}

/// effects.md: the table, changes relative to the thesis's model (first row).
pub fn markdown(t: &EffectsStudy) -> String {
    let fu = frequency_unit(&t.units);
    let length = &t.units.length;
    let power = format!("{}·{}/{}", t.units.force, length, t.units.time);
    let mut s = format!(
        "`{}`, {}; peak of `{}`, changes against the thesis's point model (first row).\n\n",
        t.scene,
        if t.variants.iter().all(|v| v.first_order) {
            super::solved_by(Mode::Fast)
        } else {
            super::solved_by(Mode::HarmonicBalance)
        },
        t.output
    );
    let _ = writeln!(
        s,
        "| point model | peak [{f}] | Δ peak [{f}] | amplitude [{length}] | Δ amplitude | power at peak [{power}] | Δ power | largest power [{power}] | converged | 3D point steps | wall time [s] |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        f = fu.text
    );
    let base = t
        .variants
        .first()
        .and_then(|v| v.peak.map(|p| (p, v.power_at_peak)));
    for v in &t.variants {
        let rel = |a: f64, b: f64| {
            if b != 0.0 {
                format!("{:+.2} %", 100.0 * (a / b - 1.0))
            } else {
                "–".to_string()
            }
        };
        let (peak, dpeak, amp, damp, dpow) = match (v.peak, base) {
            (Some((f, a)), Some(((f0, a0), p0))) => (
                format!("{:.2}", fu.show(f)),
                format!("{:+.2}", fu.show(f) - fu.show(f0)),
                format!("{a:.4e}"),
                rel(a, a0),
                rel(v.power_at_peak, p0),
            ),
            (Some((f, a)), None) => (
                format!("{:.2}", fu.show(f)),
                "–".into(),
                format!("{a:.4e}"),
                "–".into(),
                "–".into(),
            ),
            (None, _) => ("–".into(), "–".into(), "–".into(), "–".into(), "–".into()),
        };
        let _ = writeln!(
            s,
            "| {} | {peak} | {dpeak} | {amp} | {damp} | {:.4e} | {dpow} | {:.4e} | {}/{} | {} | {:.1} |",
            v.label,
            v.power_at_peak,
            v.power_max,
            v.converged,
            v.frequencies,
            v.point3d_steps,
            v.seconds
        );
    }
    s
}

/// Writes effects.csv, effects.md and effects.svg into `dir`.
pub fn write(dir: &Path, t: &EffectsStudy) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    let (a, b, c) = (
        dir.join("effects.csv"),
        dir.join("effects.md"),
        dir.join("effects.svg"),
    );
    atomic::write_text(&a, &csv(t))?;
    atomic::write_text(&b, &markdown(t))?;
    let curves: Vec<FrfCurve> = t
        .variants
        .iter()
        .map(|v| FrfCurve {
            label: v.label.to_string(),
            grid: v.sweep.freqs.clone(),
            points: (0..v.sweep.freqs.len())
                .filter(|&i| v.sweep.converged[i] && v.sweep.failure(i).is_none())
                .map(|i| (v.sweep.freqs[i], vec![v.sweep.outputs[i][0].norm()]))
                .collect(),
            not_converged: Vec::new(),
        })
        .collect();
    let title = format!("{}: point models of the contact", t.scene);
    atomic::with_temp(&c, |tmp| {
        frf_curves(
            tmp,
            &title,
            &t.units,
            std::slice::from_ref(&t.output),
            &curves,
        )
    })?;
    Ok(vec![a, b, c])
}
