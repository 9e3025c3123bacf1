//! The FRF plot of a sweep (frf.svg): every output's amplitude against frequency on a
//! log axis, the reference curves (without contact damping, the sweep down) dashed in
//! the output's colour, unconverged frequencies crossed, a legend of at most
//! [`LEGEND_OUTPUTS`] outputs.

use plotters::coord::combinators::LogCoord;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::svg::{drawing_error as err, freq_label};
use crate::model::Problem;
use crate::settings::units::{frequency_unit, FrequencyUnit};
use crate::solve::sweep::SweepResult;
use crate::util::ticks::{log_tick, plotted_log_range};

type Res = Result<(), String>;

/// FRF amplitude of every output (log scale) for each (sweep, label) in `curves`: the first
/// bold (e.g. with contact damping, or sweep up), the others thinner and dashed in the
/// output's colour (e.g. the sweep down, the sweep without contact damping), so a curve that
/// coincides with the first stays visible; frequencies that did not converge are crossed. Curves of at most [`MARKED_POINTS`]
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
    curves.first().ok_or("no sweep")?;
    let fu = frequency_unit(units);
    let (x, y) = ranges(curves, &fu)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x.0..x.1, (y.0..y.1).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        // Fine lines along a log axis bunch into grey bands: the labelled ticks only;
        // over up to three decades ticks at 1, 2 and 5, else at the decades.
        .y_max_light_lines(0)
        .x_max_light_lines(1)
        .y_labels(if y.1 <= 1e3 * y.0 { 30 } else { 10 })
        .x_desc(freq_label(units))
        .y_desc(format!("amplitude [{}]", units.length))
        .y_label_formatter(&|v: &f64| log_tick(*v))
        .x_label_formatter(&|v: &f64| format!("{}", (v * 1e3).round() / 1e3))
        .draw()
        .map_err(err)?;
    for (k, name) in names.iter().enumerate() {
        for (c, curve) in curves.iter().enumerate() {
            let pts: Vec<(f64, f64)> = curve
                .points
                .iter()
                .map(|(f, a)| (fu.show(*f), a[k].max(y.0)))
                .collect();
            let label = format!("{name} {}", curve.label).trim_end().to_string();
            // The legend names the first LEGEND_OUTPUTS outputs.
            let label = (k < LEGEND_OUTPUTS).then_some(label);
            draw_curve(&mut chart, pts, k, c, label, units, x)?;
        }
    }
    mark_not_converged(&mut chart, curves, &fu, y.0)?;
    if names.len() > LEGEND_OUTPUTS {
        chart
            .draw_series(std::iter::once(EmptyElement::at((x.0, y.0))))
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

/// An axis range (from, to).
type Range = (f64, f64);

/// The chart of an FRF: frequency (linear) against amplitude (log).
type FrfChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, LogCoord<f64>>>;

/// The frequency range (the curves' first and last frequency; markers get room at both
/// ends for themselves and their values) and the amplitude range (at least a decade,
/// ending on labelled ticks).
fn ranges(curves: &[FrfCurve], fu: &FrequencyUnit) -> Result<(Range, Range), String> {
    let main = curves.first().ok_or("no sweep")?;
    let f0 = fu.show(main.points.first().ok_or("no frequencies")?.0);
    let f1 = fu.show(main.points.last().ok_or("no frequencies")?.0);
    let positive = curves
        .iter()
        .flat_map(|c| c.points.iter().flat_map(|(_, row)| row.iter().copied()))
        .filter(|&a| a > 0.0);
    let (lo, hi) = positive.fold((f64::INFINITY, 0.0f64), |(l, h), a| (l.min(a), h.max(a)));
    let (lo, hi) = if hi > 0.0 && lo.is_finite() {
        (lo, hi)
    } else {
        (1e-12, 1.0)
    };
    let x = if f1 <= f0 {
        (f0 * 0.9, f0 * 1.1)
    } else if main.points.len() <= MARKED_POINTS {
        let pad = 0.15 * (f1 - f0);
        (f0 - pad, f1 + pad)
    } else {
        (f0, f1)
    };
    let y = plotted_log_range(lo * 0.8, hi * 1.25);
    Ok((x, (y.start, y.end)))
}

/// Curve `c` of output `k`: one colour per output; its first curve solid and thick, the
/// others (without contact damping, the sweep down) dashed in the same colour; a few
/// frequencies as markers, the first curve's with their values. `label` names it in the
/// legend with a sample drawn as the curve is (solid or dashed).
fn draw_curve<'a, 'b: 'a>(
    chart: &mut FrfChart<'a, 'b>,
    pts: Vec<(f64, f64)>,
    k: usize,
    c: usize,
    label: Option<String>,
    units: &crate::settings::Units,
    x: Range,
) -> Res {
    let color = crate::report::style::series(k);
    let style = color.stroke_width(if c == 0 { 2 } else { 1 });
    let drawn = if pts.len() <= MARKED_POINTS {
        let size = 6 - 2 * c.min(1) as i32;
        if c == 0 {
            let font = ("sans-serif", 13).into_font().color(&color);
            chart
                .draw_series(pts.iter().map(|&(f, a)| {
                    EmptyElement::at((f, a))
                        + Text::new(
                            format!("{a:.4e} {}", units.length),
                            // Left of a marker in the right half, so it stays inside.
                            (if f > 0.5 * (x.0 + x.1) { -110 } else { 10 }, -18),
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
    if let Some(label) = label {
        let ends = if c > 0 {
            [(0, 6), (10, 16), (20, 24)]
        } else {
            [(0, 8), (8, 16), (16, 24)]
        };
        drawn.label(label).legend(move |(x, y)| {
            let piece = |(a, b): (i32, i32)| PathElement::new(vec![(a, 0), (b, 0)], style);
            EmptyElement::at((x, y)) + piece(ends[0]) + piece(ends[1]) + piece(ends[2])
        });
    }
    Ok(())
}

/// Frequencies that did not converge, crossed on every curve they belong to (a line
/// through them would pass them off as results), with a legend line.
fn mark_not_converged<'a, 'b: 'a>(
    chart: &mut FrfChart<'a, 'b>,
    curves: &[FrfCurve],
    fu: &FrequencyUnit,
    ymin: f64,
) -> Res {
    let count: usize = curves.iter().map(|c| c.not_converged.len()).sum();
    if count == 0 {
        return Ok(());
    }
    let marks: Vec<(f64, f64)> = curves
        .iter()
        .flat_map(|c| c.not_converged.iter().map(move |&i| &c.points[i]))
        .flat_map(|(f, a)| {
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
        .label(if curves.len() == 1 {
            format!("not converged ({count} frequencies; status in results.csv)")
        } else {
            format!("not converged ({count} frequencies of the curves; status in their CSVs)")
        })
        .legend(|(x, y)| Cross::new((x + 12, y), 5, RED.stroke_width(2)));
    Ok(())
}

/// Outputs named in the legend; more are drawn and counted in one line.
const LEGEND_OUTPUTS: usize = 8;

/// Curves of at most this many frequencies are drawn as markers, not lines.
const MARKED_POINTS: usize = 3;

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
            not_converged: if scale == 1.0 { vec![3, 7] } else { vec![5] },
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
        // Crossed on both curves: 2 + 1 frequencies, 20 outputs each.
        assert!(has(
            "not converged (3 frequencies of the curves; status in their CSVs)"
        ));
        let red_crosses = svg.matches("stroke=\"#FF0000\"").count();
        assert!(red_crosses >= 3 * 20, "{red_crosses}");
    }
}
