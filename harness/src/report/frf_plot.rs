//! The FRF plot of a sweep (frf.svg): every output's amplitude against frequency on a
//! log axis, the reference curves (without contact damping, the sweep down) dashed in
//! the output's colour, unconverged frequencies crossed, a legend of at most
//! [`LEGEND_OUTPUTS`] outputs.

use plotters::coord::combinators::{BindKeyPoints, LogCoord, WithKeyPoints};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::svg::{drawing_error as err, freq_label};
use crate::model::Problem;
use crate::settings::units::{frequency_unit, FrequencyUnit};
use crate::solve::sweep::SweepResult;
use crate::util::number::{counted, sig};
use crate::util::ticks::{log_tick, log_ticks, plotted_log_range};

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
                grid: r.freqs.clone(),
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
    /// Every frequency the sweep ran (1/time, ascending), with or without a response:
    /// where refined bands are looked for, so that frequencies left out of `points`
    /// (failed, singular) do not pass for a coarser spacing.
    pub grid: Vec<f64>,
    pub points: Vec<(f64, Vec<f64>)>,
    /// Indices into `points` of frequencies whose iteration did not converge: marked ×.
    pub not_converged: Vec<usize>,
}

/// [`frf`] from plain data: `names` of the outputs, the curves' amplitudes. A sweep
/// with refined bands ([`refined_bands`]: ranges sampled much more finely than the
/// rest, such as a deck's second frequency range or a scene's `refine`) gets a row of
/// panels below, one per band; the bands are shaded on the whole sweep's panel.
pub fn frf_curves(
    path: &std::path::Path,
    title: &str,
    units: &crate::settings::Units,
    names: &[String],
    curves: &[FrfCurve],
) -> Res {
    let main = curves.first().ok_or("no sweep")?;
    let fu = frequency_unit(units);
    let bands = refined_bands(&main.grid);
    let size = (900, if bands.is_empty() { 560 } else { 900 });
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let (top, bottom) = root.split_vertically(560);
    let (x, y) = ranges(curves, &fu)?;
    let shades: Vec<Range> = bands
        .iter()
        .map(|&(a, b)| (fu.show(a), fu.show(b)))
        .collect();
    panel(&top, title, units, names, curves, (x, y), &shades)?;
    if curves.iter().all(|c| c.points.is_empty()) {
        let note = "no response at any frequency: each one singular or failed (results.csv)";
        top.draw(&Text::new(note, (150, 270), ("sans-serif", 18)))
            .map_err(err)?;
    }
    for (&(a, b), area) in bands
        .iter()
        .zip(bottom.split_evenly((1, bands.len().max(1))))
    {
        let inside: Vec<FrfCurve> = curves.iter().map(|c| c.within(a, b)).collect();
        let count = inside[0].points.len();
        let caption = format!(
            "{} to {} {} ({count} frequencies)",
            short(fu.show(a)),
            short(fu.show(b)),
            fu.text
        );
        let (x, y) = ranges(&inside, &fu)?;
        panel(&area, &caption, units, &[], &inside, (x, y), &[])?;
    }
    root.present().map_err(err)
}

/// `v` with at most 7 significant digits, trailing zeros dropped (139, 7539.099).
fn short(v: f64) -> String {
    let s = sig(v);
    if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

impl FrfCurve {
    /// The curve's frequencies from `a` to `b` (1/time).
    fn within(&self, a: f64, b: f64) -> FrfCurve {
        let keep: Vec<usize> = (0..self.points.len())
            .filter(|&i| (a..=b).contains(&self.points[i].0))
            .collect();
        FrfCurve {
            label: self.label.clone(),
            grid: self
                .grid
                .iter()
                .copied()
                .filter(|f| (a..=b).contains(f))
                .collect(),
            points: keep.iter().map(|&i| self.points[i].clone()).collect(),
            not_converged: (0..keep.len())
                .filter(|k| self.not_converged.contains(&keep[*k]))
                .collect(),
        }
    }
}

/// A band of at least [`BAND_POINTS`] frequencies (1/time) sampled much more finely
/// than the rest (a deck's second range, a scene's `refine`): each spacing in it under a
/// fifth of the sweep's widest, both as it is and relative to its frequency (so neither
/// an even nor a logarithmic sweep has one), narrower than a fifth of the sweep, where
/// the whole sweep's plot cannot show it. At most [`BANDS`] (the widest), ascending.
fn refined_bands(freqs: &[f64]) -> Vec<(f64, f64)> {
    let gaps: Vec<(f64, f64)> = freqs
        .windows(2)
        .map(|w| {
            (
                w[1] - w[0],
                (w[1] - w[0]) / w[1].abs().max(f64::MIN_POSITIVE),
            )
        })
        .collect();
    let widest = gaps
        .iter()
        .fold((0.0f64, 0.0f64), |m, g| (m.0.max(g.0), m.1.max(g.1)));
    let fine = |g: &(f64, f64)| g.0 >= 0.0 && g.0 < 0.2 * widest.0 && g.1 < 0.2 * widest.1;
    let span = match (freqs.first(), freqs.last()) {
        (Some(a), Some(b)) => b - a,
        _ => return Vec::new(),
    };
    let mut bands = Vec::new();
    let mut start = 0;
    for i in 0..=gaps.len() {
        if i < gaps.len() && fine(&gaps[i]) {
            continue;
        }
        // gaps[start..i] are fine: the points start ..= i.
        let width = freqs[i] - freqs[start];
        if i + 1 >= start + BAND_POINTS && width > 0.0 && width < 0.2 * span {
            bands.push((freqs[start], freqs[i]));
        }
        start = i + 1;
    }
    bands.sort_by(|p, q| (q.1 - q.0).total_cmp(&(p.1 - p.0)));
    bands.truncate(BANDS);
    bands.sort_by(|p, q| p.0.total_cmp(&q.0));
    bands
}

/// One FRF panel in `area`: its axes, the curves, the unconverged crosses, `shades`
/// (frequency ranges in display units) and, where `names` are given, the legend.
fn panel(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    caption: &str,
    units: &crate::settings::Units,
    names: &[String],
    curves: &[FrfCurve],
    (x, y): (Range, Range),
    shades: &[Range],
) -> Res {
    let fu = frequency_unit(units);
    // Enough decimals that about ten labels across the panel differ.
    let decimals = (-((x.1 - x.0) / 10.0).log10().floor()).clamp(0.0, 12.0) as usize;
    let mut chart = ChartBuilder::on(area)
        .caption(
            caption,
            ("sans-serif", if names.is_empty() { 16 } else { 20 }),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(
            x.0..x.1,
            (y.0..y.1)
                .log_scale()
                .with_key_points(log_ticks(&(y.0..y.1))),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        // Fine lines along a log axis bunch into grey bands: the ticks of
        // `util::ticks::log_ticks` only (each labelled 1, 2 or 5 × 10^k once).
        .y_max_light_lines(0)
        .x_max_light_lines(1)
        .x_desc(freq_label(units))
        .y_desc(format!("amplitude [{}]", units.length))
        .y_label_formatter(&|v: &f64| log_tick(*v))
        .x_label_formatter(&|v: &f64| format!("{v:.decimals$}"))
        .draw()
        .map_err(err)?;
    if !shades.is_empty() {
        chart
            .draw_series(
                shades
                    .iter()
                    .map(|&(a, b)| Rectangle::new([(a, y.0), (b, y.1)], BLACK.mix(0.08).filled())),
            )
            .map_err(err)?
            .label(if shades.len() == 1 {
                "finely sampled range (panel below)"
            } else {
                "finely sampled ranges (panels below)"
            })
            .legend(|(x, y)| {
                Rectangle::new([(x, y - 5), (x + 24, y + 5)], BLACK.mix(0.15).filled())
            });
    }
    let outputs = names.len().max(
        curves
            .first()
            .map_or(0, |c| c.points.first().map_or(0, |p| p.1.len())),
    );
    for k in 0..outputs {
        for (c, curve) in curves.iter().enumerate() {
            let pts: Vec<(f64, f64)> = curve
                .points
                .iter()
                .map(|(f, a)| (fu.show(*f), a[k].max(y.0)))
                .collect();
            // The legend names the first LEGEND_OUTPUTS outputs.
            let label = names
                .get(k)
                .filter(|_| k < LEGEND_OUTPUTS)
                .map(|name| format!("{name} {}", curve.label).trim_end().to_string());
            // One output compared over several curves (point models, rungs): a solid
            // line of its own colour per curve; else a colour per output, its curves
            // told apart by dashes.
            let (colour, dashed) = if outputs == 1 && curves.len() > 2 {
                (c, 0)
            } else {
                (k, c)
            };
            draw_curve(&mut chart, pts, colour, dashed, label, units, x)?;
        }
    }
    mark_not_converged(&mut chart, curves, &fu, y.0, !names.is_empty())?;
    if names.is_empty() {
        return Ok(());
    }
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
        .map_err(err)
}

/// An axis range (from, to).
type Range = (f64, f64);

/// The chart of an FRF: frequency (linear) against amplitude (log).
type FrfChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, WithKeyPoints<LogCoord<f64>>>>;

/// The frequency range (the curves' first and last frequency; markers get room at both
/// ends for themselves and their values) and the amplitude range (at least a decade,
/// ending on labelled ticks).
fn ranges(curves: &[FrfCurve], fu: &FrequencyUnit) -> Result<(Range, Range), String> {
    let main = curves.first().ok_or("no sweep")?;
    // The frequencies the sweep ran, with or without a response: a sweep whose every
    // frequency is singular still gets its (empty) chart.
    let ran = main.grid.iter().chain(main.points.iter().map(|(f, _)| f));
    let (f0, f1) = ran.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &f| {
        (a.min(f), b.max(f))
    });
    if f0 > f1 {
        return Err("no frequencies".into());
    }
    let (f0, f1) = (fu.show(f0), fu.show(f1));
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

/// Curve `c` of an output in series colour `colour`: the first curve solid and thick,
/// the others (without contact damping, the sweep down) dashed and thin; a few
/// frequencies as markers, the first curve's with their values. `label` names it in the
/// legend with a sample drawn as the curve is (solid or dashed).
fn draw_curve<'a, 'b: 'a>(
    chart: &mut FrfChart<'a, 'b>,
    pts: Vec<(f64, f64)>,
    colour: usize,
    c: usize,
    label: Option<String>,
    units: &crate::settings::Units,
    x: Range,
) -> Res {
    let color = crate::report::style::series(colour);
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
    legend: bool,
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
    let drawn = chart
        .draw_series(
            marks
                .into_iter()
                .map(|q| Cross::new(q, 5, RED.stroke_width(2))),
        )
        .map_err(err)?;
    if !legend {
        return Ok(());
    }
    drawn
        .label(if curves.len() == 1 {
            format!(
                "not converged ({}; status in results.csv)",
                counted(count, "frequency", "frequencies")
            )
        } else {
            format!(
                "not converged ({} of the curves; status in their CSVs)",
                counted(count, "frequency", "frequencies")
            )
        })
        .legend(|(x, y)| Cross::new((x + 12, y), 5, RED.stroke_width(2)));
    Ok(())
}

/// Outputs named in the legend; more are drawn and counted in one line.
const LEGEND_OUTPUTS: usize = 8;

/// Curves of at most this many frequencies are drawn as markers, not lines.
const MARKED_POINTS: usize = 3;

/// Frequencies a refined band has at least to get its own panel.
const BAND_POINTS: usize = 5;

/// Refined bands with a panel of their own, at most.
const BANDS: usize = 3;

#[cfg(test)]
mod tests {
    use super::*;

    /// The bolted lap deck's sweep: 51 frequencies over 125–150 Hz and 20 over
    /// 139.025–139.975 Hz, merged.
    fn bolted_lap_grid() -> Vec<f64> {
        let mut f: Vec<f64> = (0..51).map(|i| 125.0 + 0.5 * i as f64).collect();
        f.extend((0..20).map(|i| 139.025 + 0.05 * i as f64));
        f.sort_by(f64::total_cmp);
        f.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        f
    }

    #[test]
    fn a_refined_band_is_found_and_even_or_logarithmic_sweeps_have_none() {
        let [(a, b)] = refined_bands(&bolted_lap_grid())[..] else {
            panic!("one band")
        };
        // The band's points and the coarse ones between them: 139.0 … 140.0.
        assert!(
            (a - 139.0).abs() < 1e-9 && (b - 140.0).abs() < 1e-9,
            "{a} … {b}"
        );
        let even: Vec<f64> = (0..200).map(|i| 10.0 + 5.0 * i as f64).collect();
        let log: Vec<f64> = (0..200)
            .map(|i| 10f64.powf(1.0 + 3.0 * i as f64 / 199.0))
            .collect();
        assert!(refined_bands(&even).is_empty());
        assert!(refined_bands(&log).is_empty());
        // A band over a third of the sweep is seen well enough without a panel.
        let mut wide: Vec<f64> = (0..20).map(|i| 100.0 + 5.0 * i as f64).collect();
        wide.extend((1..100).map(|i| 130.0 + 0.3 * i as f64));
        wide.sort_by(f64::total_cmp);
        assert!(refined_bands(&wide).is_empty());
        // Two bands on a logarithmic sweep (three-beams-coarse.toml), ascending.
        let mut two = log.clone();
        two.extend((0..30).map(|i| 1100.0 + 150.0 * i as f64 / 29.0));
        two.extend((0..30).map(|i| 7000.0 + 500.0 * i as f64 / 29.0));
        two.sort_by(f64::total_cmp);
        let bands = refined_bands(&two);
        assert_eq!(bands.len(), 2, "{bands:?}");
        assert!(bands[0].0 <= 1100.0 && bands[0].1 >= 1250.0 && bands[1].0 <= 7000.0);
    }

    #[test]
    fn the_band_gets_a_panel_of_its_own_and_is_shaded_above() {
        let units = crate::settings::Units {
            length: "mm".into(),
            force: "N".into(),
            time: "s".into(),
            mass: "t".into(),
            frequency: Some("Hz".into()),
        };
        let grid = bolted_lap_grid();
        let curve = FrfCurve {
            label: "with contact damping".into(),
            grid: grid.clone(),
            not_converged: vec![],
            points: grid
                .iter()
                .map(|&f| (f, vec![1.0 / (1.0 + (f - 139.4).powi(2))]))
                .collect(),
        };
        let dir = std::env::temp_dir().join(format!("jointlin-svg-band-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("frf.svg");
        frf_curves(&path, "band", &units, &["tip".into()], &[curve]).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let has = |text: &str| svg.lines().any(|l| l.trim() == text);
        assert!(has("139 to 140 Hz (23 frequencies)"), "{svg}");
        assert!(has("finely sampled range (panel below)"));
        assert!(svg.contains("height=\"900\""));

        // An even sweep with failed frequencies (no response, left out of the points):
        // the gap they leave does not make the rest a refined band.
        let grid: Vec<f64> = (0..200).map(|i| 100.0 + i as f64).collect();
        let curve = FrfCurve {
            label: String::new(),
            grid: grid.clone(),
            not_converged: vec![],
            points: grid
                .iter()
                .filter(|f| !(120.0..125.0).contains(*f))
                .map(|&f| (f, vec![1.0 / (1.0 + (f - 150.0).powi(2))]))
                .collect(),
        };
        let path = dir.join("gap.svg");
        std::fs::create_dir_all(&dir).unwrap();
        frf_curves(&path, "gap", &units, &["tip".into()], &[curve]).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        assert!(svg.contains("height=\"560\"") && !svg.contains("finely sampled"));
    }

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
            grid: (0..50).map(|i| 100.0 + i as f64).collect(),
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
