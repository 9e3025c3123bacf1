//! Reports of `jointlin backbone`: backbone.csv (one row per modal amplitude, columns
//! carrying the scene's units) and backbone.svg (frequency and damping ratio against
//! an output's first-harmonic amplitude, log amplitude axis).

use std::fmt::Write as _;

use plotters::coord::combinators::BindKeyPoints;
use plotters::prelude::*;

use super::BackbonePoint;
use crate::report::style;
use crate::report::svg::drawing_error as err;
use crate::settings::units::frequency_unit;
use crate::settings::Units;
use crate::util::number::exact;
use crate::util::ticks::{log_tick, log_ticks, plotted_log_range};

/// One row of the report: the point and its outputs' first-harmonic amplitudes.
#[derive(Debug, Clone)]
pub struct Row {
    pub point: BackbonePoint,
    /// Per output (length).
    pub outputs: Vec<f64>,
}

/// The frequency of ω (rad/time) as the scene shows it ([`frequency_unit`]).
pub fn frequency(omega: f64, units: &Units) -> f64 {
    frequency_unit(units).show(omega / (2.0 * std::f64::consts::PI))
}

/// backbone.csv: `modal_amplitude_<length>_sqrt_<mass>` (q of u = φ q with φᵀMφ = 1),
/// `frequency_<unit>`, `damping_ratio`, `<output>_amp_<length>`,
/// `energy_per_cycle_<force>_<length>` (all joints), `<element>_energy_<force>_<length>`
/// (per cycle; the 1D elements, then the three-direction points), and per point its
/// normal force range over the cycle, `<point>_normal_force_min_<force>`,
/// `<point>_normal_force_max_<force>`.
pub fn csv(
    units: &Units,
    outputs: &[String],
    (elements, points): (&[String], &[String]),
    rows: &[Row],
) -> String {
    let mut s = format!(
        "modal_amplitude_{}_sqrt_{},{},damping_ratio",
        units.length,
        units.mass,
        frequency_unit(units).column
    );
    for o in outputs {
        let _ = write!(s, ",{o}_amp_{}", units.length);
    }
    let _ = write!(s, ",energy_per_cycle_{}_{}", units.force, units.length);
    for e in elements {
        let _ = write!(s, ",{e}_energy_{}_{}", units.force, units.length);
    }
    for p in points {
        let f = &units.force;
        let _ = write!(s, ",{p}_normal_force_min_{f},{p}_normal_force_max_{f}");
    }
    s.push('\n');
    for r in rows {
        let p = &r.point;
        let _ = write!(
            s,
            "{},{},{}",
            exact(p.modal_amplitude),
            exact(frequency(p.omega, units)),
            exact(p.damping_ratio)
        );
        for a in &r.outputs {
            let _ = write!(s, ",{}", exact(*a));
        }
        let total: f64 = p.energy_per_cycle.iter().sum();
        let _ = write!(s, ",{}", exact(total));
        for e in &p.energy_per_cycle {
            let _ = write!(s, ",{}", exact(*e));
        }
        for (lo, hi) in &p.normal_range {
            let _ = write!(s, ",{},{}", exact(*lo), exact(*hi));
        }
        s.push('\n');
    }
    s
}

/// backbone.svg: frequency (top) and damping ratio (bottom) against the first output's
/// amplitude (the modal amplitude without outputs), log amplitude axis.
pub fn svg(
    path: &std::path::Path,
    title: &str,
    units: &Units,
    x_label: &str,
    rows: &[Row],
) -> Result<(), String> {
    let x = |r: &Row| {
        r.outputs
            .first()
            .copied()
            .unwrap_or(r.point.modal_amplitude)
    };
    let pts: Vec<(f64, f64, f64)> = rows
        .iter()
        .map(|r| (x(r), frequency(r.point.omega, units), r.point.damping_ratio))
        .filter(|p| p.0 > 0.0 && p.0.is_finite() && p.1.is_finite() && p.2.is_finite())
        .collect();
    if pts.is_empty() {
        return Err("no backbone points to plot".into());
    }
    let fold = |f: fn(&(f64, f64, f64)) -> f64| {
        pts.iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            })
    };
    let (x0, x1) = fold(|p| p.0);
    let (f0, f1) = fold(|p| p.1);
    let (z0, z1) = fold(|p| p.2);
    let pad = |a: f64, b: f64| {
        let m = 0.05 * (b - a).max(1e-6 * b.abs().max(1e-300));
        (a - m, b + m)
    };
    let root = SVGBackend::new(path, (900, 700)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(title, ("sans-serif", 20)).map_err(err)?;
    let panels = root.split_evenly((2, 1));
    let unit = frequency_unit(units).text;
    let (fl, fh) = pad(f0, f1);
    let (zl, zh) = pad(z0.min(0.0), z1);
    let series = [
        (fl, fh, format!("frequency [{unit}]"), 1usize),
        (zl, zh, "damping ratio [1]".to_string(), 2usize),
    ];
    // The amplitude axis out to labelled ticks at both ends, as the FRF plots.
    let x = plotted_log_range(x0 * 0.9, x1 * 1.1);
    for (area, (lo, hi, label, col)) in panels.iter().zip(series) {
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(x.clone().log_scale().with_key_points(log_ticks(&x)), lo..hi)
            .map_err(err)?;
        chart
            .configure_mesh()
            // Fine lines along a log axis bunch into grey bands: the ticks of
            // `util::ticks::log_ticks` only.
            .x_max_light_lines(1)
            .y_max_light_lines(1)
            .x_desc(x_label)
            .y_desc(label)
            .x_label_formatter(&|v: &f64| log_tick(*v))
            .draw()
            .map_err(err)?;
        let line: Vec<(f64, f64)> = pts
            .iter()
            .map(|p| (p.0, if col == 1 { p.1 } else { p.2 }))
            .collect();
        // The shared series colours: blue for frequency, vermillion for damping.
        let color = style::series(col - 1);
        chart
            .draw_series(LineSeries::new(line.clone(), color.stroke_width(2)))
            .map_err(err)?;
        chart
            .draw_series(line.iter().map(|&p| Circle::new(p, 2, color.filled())))
            .map_err(err)?;
    }
    root.present().map_err(err)
}
