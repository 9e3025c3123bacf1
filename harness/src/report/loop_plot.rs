//! Hysteresis loops (loops_time.svg): per joint the tangential force against the
//! tangential relative displacement over one period, t₁ and (where it moves) t₂, one
//! panel per joint side by side (at most [`MAX_PANELS`]).

use plotters::prelude::*;

use super::svg::drawing_error as err;
use crate::settings::Units;
use crate::util::ticks::linear_tick_on;

type Res = Result<(), String>;

/// A curve of a panel: its legend label, its points and its colour.
type Curve<'a> = (&'a str, &'a [(f64, f64)], RGBColor);

/// Panels drawn; further joints are named in the caption as left out.
pub const MAX_PANELS: usize = 4;

/// One joint's loop: per sample the displacement and force along t₁ and t₂.
pub struct JointLoop {
    pub name: String,
    /// (u₁, F₁) per sample (length, force).
    pub t1: Vec<(f64, f64)>,
    /// (u₂, F₂) per sample (length, force).
    pub t2: Vec<(f64, f64)>,
}

/// Draws the loops of `joints` into `path`; `title` names the scene and the frequency.
pub fn draw(path: &std::path::Path, title: &str, units: &Units, joints: &[JointLoop]) -> Res {
    let shown = joints.len().clamp(1, MAX_PANELS);
    let width = (460 * shown as u32 + 40).max(760);
    let root = SVGBackend::new(path, (width, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let caption = if joints.len() > MAX_PANELS {
        format!("{title} (first {MAX_PANELS} of {} joints)", joints.len())
    } else {
        title.to_string()
    };
    let root = root.titled(&caption, ("sans-serif", 18)).map_err(err)?;
    for (panel, j) in root.split_evenly((1, shown)).iter().zip(joints) {
        let moves = |pts: &[(f64, f64)]| pts.iter().any(|p| p.0 != 0.0 || p.1 != 0.0);
        let curves: Vec<Curve> = [
            ("t1", j.t1.as_slice(), RGBColor(31, 119, 180)),
            ("t2", j.t2.as_slice(), RGBColor(214, 39, 40)),
        ]
        .into_iter()
        .filter(|c| moves(c.1))
        .collect();
        let all = || curves.iter().flat_map(|c| c.1.iter());
        let span = |pick: fn(&(f64, f64)) -> f64| {
            let (lo, hi) = all().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(pick(p)), b.max(pick(p)))
            });
            if lo.is_finite() && hi > lo {
                let pad = 0.06 * (hi - lo);
                (lo - pad, hi + pad)
            } else {
                (-1.0, 1.0)
            }
        };
        let (x, y) = (span(|p| p.0), span(|p| p.1));
        let mut chart = ChartBuilder::on(panel)
            .caption(&j.name, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_max_light_lines(1)
            .y_max_light_lines(1)
            .x_labels(6)
            .x_desc(format!("tangential displacement [{}]", units.length))
            .y_desc(format!("tangential force [{}]", units.force))
            .x_label_formatter(&|v: &f64| linear_tick_on(*v, x))
            .y_label_formatter(&|v: &f64| linear_tick_on(*v, y))
            .draw()
            .map_err(err)?;
        for (label, pts, colour) in &curves {
            // Closed: the period's last sample back to its first.
            let closed = pts.iter().chain(pts.first()).copied();
            chart
                .draw_series(LineSeries::new(closed, colour.stroke_width(2)))
                .map_err(err)?
                .label(*label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        if curves.is_empty() {
            chart
                .draw_series(std::iter::once(Text::new(
                    "no tangential motion",
                    (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1)),
                    ("sans-serif", 14),
                )))
                .map_err(err)?;
        } else {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()
                .map_err(err)?;
        }
    }
    root.present().map_err(err)
}
