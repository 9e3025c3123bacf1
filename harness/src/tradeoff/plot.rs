//! The Pareto plot: error vs wall time (log–log), amplitude error left, energy error
//! right, one colour per family of rungs, each rung a ring (rungs that coincide stay
//! visible). Errors below 1e-12 (the reference itself) are left out. Both axes end at
//! labelled ticks; the error axis reaches up far enough that the legend, top right,
//! covers no rung.

use plotters::prelude::*;

use super::Tradeoff;
use crate::report::style::series;
use crate::report::svg::drawing_error as err;
use crate::util::ticks::{log_tick, log_ticks, plotted_log_range};
use plotters::coord::combinators::BindKeyPoints;

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
        let (e0, e1) = if e1 > 0.0 { (e0, e1) } else { (1e-6, 1.0) };
        // The legend's rows take about a third of the panel's height.
        let rows = FAMILIES.len() as f64;
        let room = (e1 / e0).max(10.0).powf(0.06 * rows);
        let y = plotted_log_range(e0 / 1.5, e1 * 1.5 * room);
        let x = plotted_log_range(t0 / 1.5, t1 * 1.5);
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
            .build_cartesian_2d(
                x.clone().log_scale().with_key_points(log_ticks(&x)),
                y.clone().log_scale().with_key_points(log_ticks(&y)),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            // Fine lines along log axes bunch into grey bands: the ticks of
            // `util::ticks::log_ticks` only.
            .x_max_light_lines(0)
            .y_max_light_lines(0)
            .x_desc("wall time [s]")
            .y_desc("relative error vs reference")
            .y_label_formatter(&|v| log_tick(*v))
            .x_label_formatter(&|v| log_tick(*v))
            .draw()
            .map_err(err)?;
        for (i, (fam, name)) in FAMILIES.iter().enumerate() {
            let color = series(i);
            let rungs: Vec<(f64, f64)> = t
                .rungs
                .iter()
                .filter(|r| r.family == *fam && value(r) > 1e-12)
                .map(|r| (r.seconds, value(r)))
                .collect();
            if rungs.is_empty() {
                continue;
            }
            chart
                .draw_series(
                    rungs
                        .iter()
                        .map(|&p| Circle::new(p, 6, color.stroke_width(2))),
                )
                .map_err(err)?
                .label(*name)
                .legend(move |(x, y)| Circle::new((x + 10, y), 6, color.stroke_width(2)));
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
