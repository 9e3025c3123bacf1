//! SVG plots with plotters' SVG backend (text is written as SVG `<text>`, so no font files
//! are needed): frequencies per pass (Fig. 4.33) and the stick/slip map; the FRF is
//! [`super::frf_plot`].

use plotters::prelude::*;

use super::legend::{self, Symbol};
use super::style::series;
use crate::model::Problem;
use crate::settings::units::frequency_unit;
use crate::solve::sweep::SweepResult;
use crate::util::ticks::log_tick;

use drawing_error as err;

type Res = Result<(), String>;

pub use super::style::drawing_error;

/// `frequency [Hz]`, `frequency [1/<time>]` or `angular frequency [rad/<time>]`.
pub(crate) fn freq_label(units: &crate::settings::Units) -> String {
    let fu = frequency_unit(units);
    if fu.factor == 1.0 {
        format!("frequency [{}]", fu.text)
    } else {
        format!("angular frequency [{}]", fu.text)
    }
}

/// Frequencies run per pass (thesis: Fig. 4.33; fast: one pass).
pub fn passes(path: &std::path::Path, r: &SweepResult) -> Res {
    let root = SVGBackend::new(path, (700, 420)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let n = r.passes.len().max(1);
    let ymax = r
        .passes
        .iter()
        .map(|p| p.frequencies.len())
        .max()
        .unwrap_or(1)
        .max(1) as f64;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "frequencies per pass (outline: converged in it; green: a final pass, every frequency)",
            ("sans-serif", 16),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(0.5f64..n as f64 + 0.5, 0f64..ymax * 1.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        // Passes are categories: no fine lines between them, one between frequency labels.
        .x_max_light_lines(0)
        .y_max_light_lines(1)
        .disable_x_mesh()
        .x_desc("pass")
        .y_desc("frequencies")
        .x_label_formatter(&|v: &f64| format!("{v:.0}"))
        .y_label_formatter(&|v: &f64| format!("{v:.0}"))
        .x_labels(n.min(20))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(r.passes.iter().enumerate().map(|(i, p)| {
            let x = i as f64 + 1.0;
            let color = series(if p.kind == "final" { 2 } else { 0 });
            Rectangle::new(
                [(x - 0.35, 0.0), (x + 0.35, p.frequencies.len() as f64)],
                color.mix(0.7).filled(),
            )
        }))
        .map_err(err)?;
    chart
        .draw_series(r.passes.iter().enumerate().map(|(i, p)| {
            let x = i as f64 + 1.0;
            Rectangle::new(
                [(x - 0.35, 0.0), (x + 0.35, p.converged as f64)],
                BLACK.stroke_width(1),
            )
        }))
        .map_err(err)?;
    root.present().map_err(err)
}

/// Stick/slip map: one row per closed contact point (sorted by interface, then x, y), one
/// column per frequency, coloured by log₁₀(A/δ*) of the point's larger tangential
/// amplitude from 1e-3 (blue, deep stick) to 10 (red); sliding cells are outlined black.
pub fn stick_slip(
    path: &std::path::Path,
    units: &crate::settings::Units,
    p: &Problem,
    r: &SweepResult,
    closed: &[bool],
) -> Res {
    let root = SVGBackend::new(path, (1000, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let (map, legend) = root.split_horizontally(880);
    ratio_legend(&legend)?;
    let mut rows: Vec<usize> = (0..p.contacts.len()).filter(|&i| closed[i]).collect();
    rows.sort_by(|&a, &b| {
        let (ca, cb) = (&p.contacts[a], &p.contacts[b]);
        (ca.interface, ca.position[0], ca.position[1])
            .partial_cmp(&(cb.interface, cb.position[0], cb.position[1]))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let nf = r.freqs.len().max(1);
    let mut chart = ChartBuilder::on(&map)
        .caption(
            "stick/slip map: A/δ* per contact point (rows) and frequency (columns)",
            ("sans-serif", 16),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0f64..nf as f64, 0f64..rows.len().max(1) as f64)
        .map_err(err)?;
    let freqs = r.freqs.clone();
    chart
        .configure_mesh()
        .disable_mesh()
        // One column per swept frequency: the axis counts the sweep's points (refine
        // bands get as many columns as the rest), its labels name their frequencies.
        .x_desc(format!(
            "{} — one column per swept frequency, not to scale",
            freq_label(units)
        ))
        .y_desc("contact point (by interface, x)")
        .y_label_formatter(&|v: &f64| {
            if v.fract() == 0.0 {
                format!("{}", *v as usize)
            } else {
                String::new()
            }
        })
        .x_label_formatter(&|v: &f64| {
            let i = (*v as usize).min(freqs.len().saturating_sub(1));
            freqs.get(i).map_or(String::new(), |f| {
                format!("{:.0}", frequency_unit(units).show(*f))
            })
        })
        .draw()
        .map_err(err)?;
    for (fi, pts) in r.points.iter().enumerate() {
        chart
            .draw_series(rows.iter().enumerate().map(|(ri, &i)| {
                let q = &pts[i];
                let ratio = q.ratio[0].max(q.ratio[1]);
                Rectangle::new(
                    [(fi as f64, ri as f64), (fi as f64 + 1.0, ri as f64 + 1.0)],
                    ratio_color(ratio).filled(),
                )
            }))
            .map_err(err)?;
        chart
            .draw_series(
                rows.iter()
                    .enumerate()
                    .filter(|(_, &i)| {
                        pts[i]
                            .regime
                            .contains(&crate::capi::JOINTLIN_REGIME_SLIDING)
                    })
                    .map(|(ri, _)| {
                        Rectangle::new(
                            [(fi as f64, ri as f64), (fi as f64 + 1.0, ri as f64 + 1.0)],
                            BLACK.stroke_width(1),
                        )
                    }),
            )
            .map_err(err)?;
    }
    root.present().map_err(err)
}

/// Lowest and highest log10(A/δ*) of the stick/slip colour scale (clamped beyond).
const RATIO_SCALE: (f64, f64) = (-3.0, 1.0);

/// Colour of A/δ* on the stick/slip map: blue (≤ 1e-3, stuck) through purple to red
/// (≥ 10, beyond the slip limit A = δ*).
pub fn ratio_color(ratio: f64) -> RGBColor {
    let (lo, hi) = RATIO_SCALE;
    let t = ((ratio.max(1e-300).log10() - lo) / (hi - lo)).clamp(0.0, 1.0);
    RGBColor(
        (255.0 * t) as u8,
        (80.0 * (1.0 - (2.0 * t - 1.0).abs())) as u8,
        (255.0 * (1.0 - t)) as u8,
    )
}

/// The stick/slip map's colour bar (A/δ* on the log scale of [`ratio_color`]) and the
/// sliding frame's key.
fn ratio_legend<DB: DrawingBackend>(area: &DrawingArea<DB, plotters::coord::Shift>) -> Res {
    ratio_bar(area)?;
    legend::keys(area, true, &[(Symbol::Frame, "sliding")])
}

/// The colour bar of A/δ* on the log scale of [`ratio_color`] (also the contact maps').
pub fn ratio_bar<DB: DrawingBackend>(area: &DrawingArea<DB, plotters::coord::Shift>) -> Res {
    let (lo, hi) = RATIO_SCALE;
    let ticks: Vec<(f64, String)> = (lo as i32..=hi as i32)
        .map(|e| {
            let label = match e as f64 {
                v if v == lo => format!("≤ {}", log_tick(10f64.powi(e))),
                v if v == hi => format!("≥ {}", log_tick(10f64.powi(e))),
                _ => log_tick(10f64.powi(e)),
            };
            ((e as f64 - lo) / (hi - lo), label)
        })
        .collect();
    let colour = |t: f64| ratio_color(10f64.powf(lo + (hi - lo) * t));
    legend::colour_bar(area, "A/δ*", &colour, &ticks)
}
