//! Per-point contact maps of one operating point (the form of thesis Fig. 5.28/5.29):
//! A/δ* (stick/microslip/sliding) and dissipated energy density E/A (energy per cycle
//! of a point over its tributary area) on every contact face, as SVG and as ParaView
//! `.vtu` files (VTK XML UnstructuredGrid, ASCII, one quad cell per element face).

use std::collections::HashMap;
use std::path::Path;

use plotters::prelude::*;

use super::legend::{colour_bar, keys, Symbol};
use super::svg::{drawing_error as err, ratio_bar, ratio_color};
use super::vtu::{unstructured_grid, CellType, PointField};
use crate::fe::mesh::Face;
use crate::model::Problem;
use crate::settings::Units;
use crate::solve::sweep::PointFreq;

/// What a map shows of one contact point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointValues {
    /// Contact pressure after the preload step (force/length²).
    pub pressure: f64,
    /// Tangential relative displacement amplitude √(a₁² + a₂²) (length).
    pub amplitude: f64,
    /// Larger A/δ* of the two tangential directions (< 1 microslip, > 1 sliding; 0 open).
    pub ratio: f64,
    /// Energy dissipated per cycle per area (force/length).
    pub energy_density: f64,
}

/// Values per contact point of `p` from a sample's per-point results.
pub fn values(p: &Problem, pressure: &[f64], points: &[PointFreq]) -> Vec<PointValues> {
    p.contacts
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let q = points.get(i).copied().unwrap_or_default();
            PointValues {
                pressure: pressure[i],
                amplitude: q.amplitude[0].hypot(q.amplitude[1]),
                ratio: q.ratio[0].max(q.ratio[1]),
                energy_density: q.energy / c.area,
            }
        })
        .collect()
}

/// One interface's face as a quad mesh: its contact points and the element faces of the
/// lower body whose four corners are all contact points.
struct FaceMesh {
    /// Contact point indices (into `Problem::contacts`), in point order of the file.
    points: Vec<usize>,
    /// Quads as indices into `points`.
    quads: Vec<[usize; 4]>,
}

fn face_mesh(p: &Problem, interface: usize) -> FaceMesh {
    let points: Vec<usize> = (0..p.contacts.len())
        .filter(|&i| p.contacts[i].interface == interface)
        .collect();
    let index: HashMap<usize, usize> = points
        .iter()
        .enumerate()
        .map(|(k, &i)| (p.contacts[i].nodes[0], k))
        .collect();
    let mut quads = Vec::new();
    for body in &p.model.bodies {
        for q in body.face_quads(Face::ZMax, &p.model.elements) {
            if let (Some(a), Some(b), Some(c), Some(d)) = (
                index.get(&q[0]),
                index.get(&q[1]),
                index.get(&q[2]),
                index.get(&q[3]),
            ) {
                quads.push([*a, *b, *c, *d]);
            }
        }
    }
    FaceMesh { points, quads }
}

/// The `.vtu` text of one interface's contact face with point data `amplitude_ratio`
/// (A/δ*, the active scalar), `pressure`, `amplitude` and `energy_density`.
pub fn vtu(p: &Problem, interface: usize, vals: &[PointValues]) -> String {
    let fm = face_mesh(p, interface);
    let points: Vec<[f64; 3]> = fm.points.iter().map(|&i| p.contacts[i].position).collect();
    let cells: Vec<(CellType, Vec<usize>)> = fm
        .quads
        .iter()
        .map(|q| (CellType::Quad, q.to_vec()))
        .collect();
    let field = |f: fn(&PointValues) -> f64| -> Vec<f64> {
        fm.points.iter().map(|&i| f(&vals[i])).collect()
    };
    let columns = [
        ("amplitude_ratio", field(|v| v.ratio)),
        ("pressure", field(|v| v.pressure)),
        ("amplitude", field(|v| v.amplitude)),
        ("energy_density", field(|v| v.energy_density)),
    ];
    let fields: Vec<PointField> = columns
        .iter()
        .map(|(name, values)| PointField {
            name,
            components: 1,
            values,
        })
        .collect();
    unstructured_grid(&points, &cells, &fields)
}

/// Which value a map shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapKind {
    /// Colour A/δ* (0 blue … 1 red; sliding points outlined black), circle area ∝ the
    /// relative displacement amplitude (Fig. 5.28).
    Ratio,
    /// Colour and circle area ∝ the dissipated energy density (Fig. 5.29).
    EnergyDensity,
}

/// The two global axes a panel of interface `interface` is drawn in: the pair left when
/// the axis closest to the interface's mean normal is dropped (z-normal: x across, y up).
fn panel_axes(p: &Problem, interface: usize) -> (usize, usize) {
    let mut n = [0.0f64; 3];
    for c in p.contacts.iter().filter(|c| c.interface == interface) {
        for (k, v) in n.iter_mut().enumerate() {
            *v += c.frame[(k, 0)];
        }
    }
    let drop = (0..3)
        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(2);
    match drop {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

/// The panels of a map: interfaces that lie in one plane share a panel (a face split
/// into slabs of interfaces is drawn whole), in the order of their first interface.
/// Per panel its interfaces and the two global axes across it.
fn panel_groups(p: &Problem) -> Vec<(Vec<usize>, (usize, usize))> {
    let extent = p
        .contacts
        .iter()
        .flat_map(|c| c.position)
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let mut groups: Vec<(Vec<usize>, (usize, usize), f64)> = Vec::new();
    for k in 0..p.interfaces.len().max(1) {
        let axes = panel_axes(p, k);
        // The coordinate along the dropped axis (the face's plane), mean over its points.
        let d = 3 - axes.0 - axes.1;
        let (sum, n) = p
            .contacts
            .iter()
            .filter(|c| c.interface == k)
            .fold((0.0, 0usize), |(s, n), c| (s + c.position[d], n + 1));
        let plane = if n > 0 { sum / n as f64 } else { f64::NAN };
        match groups
            .iter_mut()
            .find(|(_, ax, pl)| *ax == axes && (pl - plane).abs() <= 1e-9 * extent)
        {
            Some(g) => g.0.push(k),
            None => groups.push((vec![k], axes, plane)),
        }
    }
    groups.into_iter().map(|(ks, ax, _)| (ks, ax)).collect()
}

/// A panel's name: its interface's, or for several the first and last names and their
/// count.
fn panel_name(p: &Problem, ks: &[usize]) -> String {
    let name = |k: usize| p.interfaces.get(k).map_or("", |i| i.name.as_str());
    match ks {
        [k] => name(*k).to_string(),
        [first, .., last] => format!(
            "{} … {} ({} interfaces in one plane)",
            name(*first),
            name(*last),
            ks.len()
        ),
        [] => String::new(),
    }
}

/// Each panel's plane axes (a, b) and bounds (x0, x1, y0, y1, length) around its
/// contact points, padded by 5 %; a panel without points spans the unit square.
fn panel_bounds(
    p: &Problem,
    groups: &[(Vec<usize>, (usize, usize))],
) -> Vec<(usize, usize, f64, f64, f64, f64)> {
    groups
        .iter()
        .map(|(ks, (a, b))| {
            let (a, b) = (*a, *b);
            let (mut x0, mut x1, mut y0, mut y1) = (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            );
            for c in p.contacts.iter().filter(|c| ks.contains(&c.interface)) {
                x0 = x0.min(c.position[a]);
                x1 = x1.max(c.position[a]);
                y0 = y0.min(c.position[b]);
                y1 = y1.max(c.position[b]);
            }
            if x0 > x1 {
                (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
            }
            let pad = 0.05 * (x1 - x0).max(y1 - y0).max(1e-9);
            (a, b, x0 - pad, x1 + pad, y0 - pad, y1 + pad)
        })
        .collect()
}

/// A point's dot radius (px) for its share `size` (0 … 1) of the panel's largest value:
/// its area grows with the value.
fn radius(size: f64) -> i32 {
    (3.0 + 11.0 * size.clamp(0.0, 1.0).sqrt()) as i32
}

/// The energy map's colour for share `t` (0 … 1) of the largest energy density: blue to
/// red.
fn energy_colour(t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    RGBColor((255.0 * t) as u8, 40, (255.0 * (1.0 - t)) as u8)
}

/// The maps' legend column: the colour bar (A/δ* on the stick/slip map's log scale, or
/// the energy density from 0 to its largest value `emax`), what the dot sizes mean
/// (the largest slip amplitude `vmax` or `emax`), the sliding ring and the open points.
fn legend(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    kind: MapKind,
    units: &Units,
    vmax: f64,
    emax: f64,
) -> Result<(), String> {
    let l = units.length.as_str();
    let grey = RGBColor(190, 190, 190);
    let mid = RGBColor(120, 40, 140);
    match kind {
        MapKind::Ratio => {
            ratio_bar(area)?;
            let largest = format!("slip {vmax:.2e} {l}");
            let quarter = format!("slip {:.2e} {l}", vmax / 4.0);
            keys(
                area,
                true,
                &[
                    (Symbol::Dot(radius(1.0), mid), largest.as_str()),
                    (Symbol::Dot(radius(0.25), mid), quarter.as_str()),
                    (Symbol::Ring(radius(0.25) + 1), "sliding (A/δ* > 1)"),
                    (Symbol::Dot(2, grey), "open (no pressure)"),
                ],
            )
        }
        MapKind::EnergyDensity => {
            let unit = format!("[{}/{l}]", units.force);
            let ticks: Vec<(f64, String)> = [0.0, 0.25, 0.5, 0.75, 1.0]
                .iter()
                .map(|&t| (t, format!("{:.2e}", t * emax)))
                .collect();
            colour_bar(area, &format!("E/A {unit}"), &energy_colour, &ticks)?;
            let largest = format!("{emax:.2e}");
            let quarter = format!("{:.2e}", emax / 4.0);
            keys(
                area,
                true,
                &[
                    (
                        Symbol::Dot(radius(1.0), energy_colour(1.0)),
                        largest.as_str(),
                    ),
                    (
                        Symbol::Dot(radius(0.25), energy_colour(0.25)),
                        quarter.as_str(),
                    ),
                    (Symbol::Dot(2, grey), "open (no pressure)"),
                ],
            )
        }
    }
}

/// SVG map: one panel per plane of interfaces ([`panel_groups`]; the two global axes
/// across it), a circle per contact point (grey dots: open points), and a legend column
/// ([`legend`]).
pub fn svg(
    path: &Path,
    title: &str,
    units: &Units,
    p: &Problem,
    vals: &[PointValues],
    kind: MapKind,
) -> Result<(), String> {
    let length_unit = units.length.as_str();
    let groups = panel_groups(p);
    let n = groups.len();
    let panels = panel_bounds(p, &groups);
    // Panel height from the flattest face's aspect, so a square face stays square.
    let aspect = panels
        .iter()
        .map(|&(_, _, x0, x1, y0, y1)| (y1 - y0) / (x1 - x0))
        .fold(0.0, f64::max);
    let panel_h = (760.0 * aspect + 90.0).clamp(220.0, 800.0) as u32;
    let height = (40 + panel_h * n as u32).max(560);
    let root = SVGBackend::new(path, (1060, height)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(title, ("sans-serif", 18)).map_err(err)?;
    let (maps, legend_area) = root.split_horizontally(880);
    let areas = maps.split_evenly((n, 1));
    let vmax = vals
        .iter()
        .map(|v| match kind {
            MapKind::Ratio => v.amplitude,
            MapKind::EnergyDensity => v.energy_density,
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let emax = vals
        .iter()
        .map(|v| v.energy_density)
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    legend(&legend_area, kind, units, vmax, emax)?;
    for (k, area) in areas.iter().enumerate() {
        let (a, b, x0, x1, y0, y1) = panels[k];
        let ks = &groups[k].0;
        let name = panel_name(p, ks);
        let caption = match kind {
            MapKind::Ratio => format!("{name}: A/δ* (colour) and slip amplitude (area)"),
            MapKind::EnergyDensity => {
                format!("{name}: energy dissipated per cycle and area (colour and area)")
            }
        };
        let mut chart = ChartBuilder::on(area)
            .caption(caption, ("sans-serif", 13))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(45)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("{} [{length_unit}]", AXIS_NAMES[a]))
            .y_desc(format!("{} [{length_unit}]", AXIS_NAMES[b]))
            .draw()
            .map_err(err)?;
        let at = |i: usize| (p.contacts[i].position[a], p.contacts[i].position[b]);
        let pts: Vec<(usize, &PointValues)> = p
            .contacts
            .iter()
            .enumerate()
            .filter(|(_, c)| ks.contains(&c.interface))
            .map(|(i, _)| (i, &vals[i]))
            .collect();
        chart
            .draw_series(
                pts.iter()
                    .filter(|(_, v)| v.pressure <= 0.0)
                    .map(|(i, _)| Circle::new(at(*i), 2, RGBColor(190, 190, 190).filled())),
            )
            .map_err(err)?;
        chart
            .draw_series(pts.iter().filter(|(_, v)| v.pressure > 0.0).map(|(i, v)| {
                let (color, size) = match kind {
                    MapKind::Ratio => (ratio_color(v.ratio), v.amplitude / vmax),
                    MapKind::EnergyDensity => {
                        let t = v.energy_density / emax;
                        (energy_colour(t), t)
                    }
                };
                Circle::new(at(*i), radius(size), color.mix(0.85).filled())
            }))
            .map_err(err)?;
        if kind == MapKind::Ratio {
            chart
                .draw_series(pts.iter().filter(|(_, v)| v.ratio > 1.0).map(|(i, v)| {
                    Circle::new(
                        at(*i),
                        radius(v.amplitude / vmax) + 1,
                        BLACK.stroke_width(2),
                    )
                }))
                .map_err(err)?;
        }
    }
    root.present().map_err(err)
}
