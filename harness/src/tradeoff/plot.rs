//! The Pareto plot: error vs wall time (log–log), amplitude error left, energy error
//! right, one marker colour per family of rungs. Errors below 1e-12 (the reference
//! itself) are left out.

use plotters::prelude::*;

use super::Tradeoff;
use crate::report::svg::drawing_error as err;

const FAMILIES: [(&str, &str); 8] = [
    ("linear", "linear stick"),
    ("simpson", "Simpson (thesis)"),
    ("default", "default method"),
    ("tolerance", "iteration tolerances"),
    ("harmonic", "harmonic balance H = 1, 3, 7, 15"),
    ("time", "time domain"),
    ("reference", "reference"),
    ("normal_load", "harmonic balance with N(t), H = 1, 3, 7"),
];

/// Writes the SVG.
pub fn pareto(path: &std::path::Path, t: &Tradeoff) -> Result<(), String> {
    let root = SVGBackend::new(path, (1200, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let panels = root.split_evenly((1, 2));
    let (t0, t1) = t.rungs.iter().fold((f64::INFINITY, 0.0f64), |(a, b), r| {
        (a.min(r.seconds), b.max(r.seconds))
    });
    for (k, panel) in panels.iter().enumerate() {
        let value = |r: &super::Rung| {
            if k == 0 {
                r.amplitude_error
            } else {
                r.energy_error
            }
        };
        let pts: Vec<f64> = t.rungs.iter().map(value).filter(|&e| e > 1e-12).collect();
        let (e0, e1) = pts
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &e| (a.min(e), b.max(e)));
        let (e0, e1) = if e1 > 0.0 {
            (e0 / 3.0, e1 * 3.0)
        } else {
            (1e-6, 1.0)
        };
        let mut chart = ChartBuilder::on(panel)
            .caption(
                if k == 0 {
                    format!("amplitude error ({}) vs wall time", t.output)
                } else {
                    "joint energy per cycle error vs wall time".to_string()
                },
                ("sans-serif", 18),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d((t0 / 2.0..t1 * 2.0).log_scale(), (e0..e1).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("wall time [s]")
            .y_desc("relative error vs reference")
            .y_label_formatter(&|v| crate::util::ticks::log_tick(*v))
            .x_label_formatter(&|v| crate::util::ticks::log_tick(*v))
            .draw()
            .map_err(err)?;
        for (i, (fam, name)) in FAMILIES.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let series: Vec<(f64, f64)> = t
                .rungs
                .iter()
                .filter(|r| r.family == *fam && value(r) > 1e-12)
                .map(|r| (r.seconds, value(r)))
                .collect();
            if series.is_empty() {
                continue;
            }
            chart
                .draw_series(series.iter().map(|&p| Circle::new(p, 5, color.filled())))
                .map_err(err)?
                .label(*name)
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)
}
