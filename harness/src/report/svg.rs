//! SVG plots with plotters' SVG backend (text is written as SVG `<text>`, so no font files
//! are needed): the FRF with and without contact damping, frequencies per pass (Fig.
//! 4.33), and the stick/slip map.

use plotters::prelude::*;

use crate::model::Problem;
use crate::settings::units::frequency_unit;
use crate::solve::sweep::SweepResult;
use crate::util::ticks::{labelled_log_range, log_tick};

use drawing_error as err;

type Res = Result<(), String>;

/// A plotters error as the message the plot writers return.
pub fn drawing_error<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// FRF amplitude of every output (log scale) for each (sweep, label) in `curves`: the first
/// bold (e.g. with contact damping, or sweep up), the others thinner and dashed in other
/// colours (e.g. the sweep down, the sweep without contact damping), so a curve that
/// coincides with the first stays visible. Curves of at most [`MARKED_POINTS`]
/// frequencies (a one-frequency scene) are drawn as markers.
pub fn frf(
    path: &std::path::Path,
    title: &str,
    units: &crate::settings::Units,
    p: &Problem,
    curves: &[(&SweepResult, &str)],
) -> Res {
    let names: Vec<String> = p.outputs.iter().map(|o| o.name.clone()).collect();
    let curves: Vec<FrfCurve> = curves
        .iter()
        .map(|(r, label)| {
            // Singular and failed frequencies have no response: left out of the curve.
            let solved: Vec<usize> = (0..r.freqs.len())
                .filter(|&i| !r.is_singular(i) && r.failure(i).is_none())
                .collect();
            FrfCurve {
                label: label.to_string(),
                points: solved
                    .iter()
                    .map(|&i| (r.freqs[i], r.outputs[i].iter().map(|v| v.norm()).collect()))
                    .collect(),
                not_converged: (0..solved.len())
                    .filter(|&k| !r.converged[solved[k]])
                    .collect(),
            }
        })
        .collect();
    frf_curves(path, title, units, &names, &curves)
}

/// One curve of [`frf_curves`]: its legend label and, per solved frequency (1/time), the
/// amplitude of every output (length).
pub struct FrfCurve {
    pub label: String,
    pub points: Vec<(f64, Vec<f64>)>,
    /// Indices into `points` of frequencies whose iteration did not converge: marked ×.
    pub not_converged: Vec<usize>,
}

/// [`frf`] from plain data: `names` of the outputs, the curves' amplitudes.
pub fn frf_curves(
    path: &std::path::Path,
    title: &str,
    units: &crate::settings::Units,
    names: &[String],
    curves: &[FrfCurve],
) -> Res {
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let main = curves.first().ok_or("no sweep")?;
    let fu = frequency_unit(units);
    let f0 = fu.show(main.points.first().ok_or("no frequencies")?.0);
    let f1 = fu.show(main.points.last().ok_or("no frequencies")?.0);
    let mut ymin = f64::INFINITY;
    let mut ymax = 0.0f64;
    for c in curves {
        for (_, row) in &c.points {
            for &a in row {
                if a > 0.0 {
                    ymin = ymin.min(a);
                    ymax = ymax.max(a);
                }
            }
        }
    }
    if ymax <= 0.0 || !ymin.is_finite() {
        ymin = 1e-12;
        ymax = 1.0;
    }
    // At least a decade, ending on labelled ticks.
    let (ymin, ymax) = labelled_log_range(ymin * 0.8, ymax * 1.25);
    // Markers (a few frequencies) get room at both ends for themselves and their values.
    let (x0, x1) = if f1 <= f0 {
        (f0 * 0.9, f0 * 1.1)
    } else if main.points.len() <= MARKED_POINTS {
        let pad = 0.15 * (f1 - f0);
        (f0 - pad, f1 + pad)
    } else {
        (f0, f1)
    };
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, (ymin..ymax).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        // Fine lines along a log axis bunch into grey bands: the labelled ticks only;
        // over up to three decades ticks at 1, 2 and 5, else at the decades.
        .y_max_light_lines(0)
        .x_max_light_lines(1)
        .y_labels(if ymax <= 1e3 * ymin { 30 } else { 10 })
        .x_desc(freq_label(units))
        .y_desc(format!("amplitude [{}]", units.length))
        .y_label_formatter(&|v: &f64| log_tick(*v))
        .x_label_formatter(&|v: &f64| format!("{}", (v * 1e3).round() / 1e3))
        .draw()
        .map_err(err)?;
    for (k, name) in names.iter().enumerate() {
        for (c, curve) in curves.iter().enumerate() {
            // One colour per output; its first curve solid and thick, the others
            // (without contact damping, the sweep down) dashed in the same colour.
            let color = OUTPUT_COLORS[k % OUTPUT_COLORS.len()];
            let width = if c == 0 { 2 } else { 1 };
            let pts: Vec<(f64, f64)> = curve
                .points
                .iter()
                .map(|(f, a)| (fu.show(*f), a[k].max(ymin)))
                .collect();
            let style = color.stroke_width(width);
            let drawn = if pts.len() <= MARKED_POINTS {
                // A few frequencies: markers, each with its value (the first curve's).
                let size = 6 - 2 * c.min(1) as i32;
                if c == 0 {
                    let font = ("sans-serif", 13).into_font().color(&color);
                    chart
                        .draw_series(pts.iter().map(|&(f, a)| {
                            EmptyElement::at((f, a))
                                + Text::new(
                                    format!("{a:.4e} {}", units.length),
                                    // Left of a marker in the right half, so it stays inside.
                                    (if f > 0.5 * (x0 + x1) { -110 } else { 10 }, -18),
                                    font.clone(),
                                )
                        }))
                        .map_err(err)?;
                }
                chart.draw_series(pts.into_iter().map(|q| Circle::new(q, size, style)))
            } else if c == 0 {
                chart.draw_series(LineSeries::new(pts, style))
            } else {
                chart.draw_series(DashedLineSeries::new(pts, 6, 4, style))
            }
            .map_err(err)?;
            // The legend names the first LEGEND_OUTPUTS outputs; a sample drawn as the
            // curve is (solid or dashed).
            if k < LEGEND_OUTPUTS {
                let dashed = c > 0;
                drawn
                    .label(format!("{name} {}", curve.label).trim_end().to_string())
                    .legend(move |(x, y)| {
                        let piece = |a: i32, b: i32| PathElement::new(vec![(a, 0), (b, 0)], style);
                        let ends = if dashed {
                            [(0, 6), (10, 16), (20, 24)]
                        } else {
                            [(0, 8), (8, 16), (16, 24)]
                        };
                        EmptyElement::at((x, y))
                            + piece(ends[0].0, ends[0].1)
                            + piece(ends[1].0, ends[1].1)
                            + piece(ends[2].0, ends[2].1)
                    });
            }
        }
    }
    // Frequencies that did not converge, marked on the main curve (a line through them
    // would pass them off as results).
    if !main.not_converged.is_empty() {
        let marks: Vec<(f64, f64)> = main
            .not_converged
            .iter()
            .flat_map(|&i| {
                let (f, a) = &main.points[i];
                let f = fu.show(*f);
                a.iter().map(move |&a| (f, a.max(ymin)))
            })
            .collect();
        chart
            .draw_series(
                marks
                    .into_iter()
                    .map(|q| Cross::new(q, 5, RED.stroke_width(2))),
            )
            .map_err(err)?
            .label(format!(
                "not converged ({} frequencies; status in results.csv)",
                main.not_converged.len()
            ))
            .legend(|(x, y)| Cross::new((x + 12, y), 5, RED.stroke_width(2)));
    }
    if names.len() > LEGEND_OUTPUTS {
        chart
            .draw_series(std::iter::once(EmptyElement::at((x0, ymin))))
            .map_err(err)?
            .label(format!(
                "(+{} more outputs, not in the legend)",
                names.len() - LEGEND_OUTPUTS
            ))
            .legend(|(x, y)| EmptyElement::at((x, y)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)
}

/// Colours of the outputs (Okabe and Ito's colour-blind-safe set, no yellow on white).
const OUTPUT_COLORS: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(230, 159, 0),
    RGBColor(0, 0, 0),
];

/// Outputs named in the legend; more are drawn and counted in one line.
const LEGEND_OUTPUTS: usize = 8;

/// Curves of at most this many frequencies are drawn as markers, not lines.
const MARKED_POINTS: usize = 3;

/// "frequency [Hz]", "frequency [1/<time>]" or "angular frequency [rad/<time>]".
fn freq_label(units: &crate::settings::Units) -> String {
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
            "frequencies per pass (outline: converged in it; green: final pass)",
            ("sans-serif", 16),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(0.5f64..n as f64 + 0.5, 0f64..ymax * 1.1)
        .map_err(err)?;
    chart
        .configure_mesh()
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
            let color = if p.kind == "final" { GREEN } else { BLUE };
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
        .x_desc(freq_label(units))
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
fn ratio_color(ratio: f64) -> RGBColor {
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
    let (lo, hi) = RATIO_SCALE;
    let (x, top, bottom, width) = (20, 70, 400, 22);
    let font = ("sans-serif", 13).into_font();
    area.draw(&Text::new("A/δ*", (x, top - 25), font.clone()))
        .map_err(err)?;
    let steps = 80;
    for k in 0..steps {
        let y0 = bottom - (bottom - top) * (k + 1) / steps;
        let y1 = bottom - (bottom - top) * k / steps;
        let e = lo + (hi - lo) * (k as f64 + 0.5) / steps as f64;
        area.draw(&Rectangle::new(
            [(x, y0), (x + width, y1)],
            ratio_color(10f64.powf(e)).filled(),
        ))
        .map_err(err)?;
    }
    area.draw(&Rectangle::new([(x, top), (x + width, bottom)], BLACK))
        .map_err(err)?;
    for e in lo as i32..=hi as i32 {
        let y = bottom - ((e as f64 - lo) / (hi - lo) * (bottom - top) as f64) as i32;
        let label = match e as f64 {
            v if v == lo => format!("≤ {}", log_tick(10f64.powi(e))),
            v if v == hi => format!("≥ {}", log_tick(10f64.powi(e))),
            _ => log_tick(10f64.powi(e)),
        };
        area.draw(&PathElement::new(
            vec![(x + width, y), (x + width + 5, y)],
            BLACK,
        ))
        .map_err(err)?;
        area.draw(&Text::new(label, (x + width + 8, y - 6), font.clone()))
            .map_err(err)?;
    }
    let y = bottom + 30;
    area.draw(&Rectangle::new(
        [(x, y), (x + width, y + 14)],
        BLACK.stroke_width(1),
    ))
    .map_err(err)?;
    area.draw(&Text::new("sliding", (x + width + 8, y), font))
        .map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn many_outputs_keep_the_legend_short_and_both_axis_ends_labelled() {
        // 20 outputs (a node set) with and without contact damping: 8 named in the
        // legend, the rest counted; the y axis ends on labelled ticks (0.001 … 0.01).
        let units = crate::settings::Units {
            length: "mm".into(),
            force: "N".into(),
            time: "s".into(),
            mass: "t".into(),
            frequency: None,
        };
        let names: Vec<String> = (0..20).map(|i| format!("node_{i}")).collect();
        let curve = |label: &str, scale: f64| FrfCurve {
            label: label.into(),
            not_converged: if scale == 1.0 { vec![3, 7] } else { Vec::new() },
            points: (0..50)
                .map(|i| {
                    let f = 100.0 + i as f64;
                    (
                        f,
                        (0..20)
                            .map(|k| scale * 1.3e-3 * (1.0 + 0.2 * k as f64 / 20.0))
                            .collect(),
                    )
                })
                .collect(),
        };
        let dir = std::env::temp_dir().join(format!("jointlin-svg-legend-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("frf.svg");
        frf_curves(
            &path,
            "legend",
            &units,
            &names,
            &[
                curve("with contact damping", 1.0),
                curve("without contact damping", 4.0),
            ],
        )
        .unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        // plotters writes each text on a line of its own.
        let has = |text: &str| svg.lines().any(|l| l.trim() == text);
        let named = (0..20)
            .filter(|i| has(&format!("node_{i} with contact damping")))
            .count();
        assert_eq!(named, LEGEND_OUTPUTS);
        assert!(has("(+12 more outputs, not in the legend)"));
        assert!(has("0.001") && has("0.01"), "{svg}");
        assert!(has("not converged (2 frequencies; status in results.csv)"));
    }
}
