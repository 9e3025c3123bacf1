//! SVG of the power-loss curves (the form of thesis Fig. 5.41–5.45): joint power loss
//! against the output amplitude, one line per torque, published points as crosses.

use std::path::Path;

use plotters::prelude::*;

use super::{LossStudySpec, StudyResult};
use crate::report::style::series;
use crate::report::svg::drawing_error as err;
use crate::util::ticks::linear_tick_on;

/// Draws `r` into `path`; axes in the study's reported units, torques in `torque_unit`.
pub fn curves(
    path: &Path,
    title: &str,
    torque_unit: &str,
    st: &LossStudySpec,
    r: &StudyResult,
) -> Result<(), String> {
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let a = |v: f64| v / st.amplitude_factor;
    let pw = |v: f64| v * st.power_factor;
    let mut xmax = 0.0f64;
    let mut ymax = 0.0f64;
    for (_, s) in &r.curves {
        for p in s {
            xmax = xmax.max(a(p.amplitude));
            ymax = ymax.max(pw(p.power));
        }
    }
    for p in &st.reference {
        xmax = xmax.max(a(p.amplitude));
        ymax = ymax.max(p.power);
    }
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..xmax * 1.05, 0.0..ymax.max(f64::MIN_POSITIVE) * 1.1)
        .map_err(err)?;
    let (x_end, y_end) = (xmax * 1.05, ymax.max(f64::MIN_POSITIVE) * 1.1);
    chart
        .configure_mesh()
        // One fine line between labelled ones: more draw a grey mesh.
        .x_max_light_lines(1)
        .y_max_light_lines(1)
        .x_label_formatter(&|v: &f64| linear_tick_on(*v, (0.0, x_end)))
        .y_label_formatter(&|v: &f64| linear_tick_on(*v, (0.0, y_end)))
        .x_desc(format!(
            "amplitude of {} [{}]",
            st.output, st.amplitude_unit
        ))
        .y_desc(format!("joint power loss [{}]", st.power_unit))
        .draw()
        .map_err(err)?;
    for (k, (torque, samples)) in r.curves.iter().enumerate() {
        let color = series(k);
        let mut pts: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
            .chain(samples.iter().map(|s| (a(s.amplitude), pw(s.power))))
            .collect();
        pts.sort_by(|x, y| x.0.total_cmp(&y.0));
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(err)?
            .label(format!("torque {torque} {torque_unit}"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        chart
            .draw_series(
                pts.iter()
                    .skip(1)
                    .map(|&p| Circle::new(p, 3, color.filled())),
            )
            .map_err(err)?;
        chart
            .draw_series(
                st.reference
                    .iter()
                    .filter(|p| p.torque == *torque)
                    .map(|p| Cross::new((a(p.amplitude), p.power), 7, color.stroke_width(2))),
            )
            .map_err(err)?;
    }
    // One legend entry for the reference points (their colour is their torque's).
    if !st.reference.is_empty() {
        chart
            .draw_series(std::iter::empty::<Cross<(f64, f64), i32>>())
            .map_err(err)?
            .label("reference points (× in the torque's colour)")
            .legend(|(x, y)| Cross::new((x + 10, y), 5, BLACK.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)
}
