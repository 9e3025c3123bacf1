//! `field_<frequency>_<unit>.vtu` of `[field_output]`: the first-order displacement
//! field of one frequency and its contact state, for ParaView. Point data per node:
//!
//! - `displacement_amplitude_<length>`: |û| per global direction (x, y, z);
//! - `displacement_real_<length>`, `displacement_imag_<length>`: û (the phase: u(t) =
//!   Re(û e^{iωt}); animate with ParaView's "Warp By Vector" on the real part);
//! - `contact_regime`: per contact node the worse of its two tangential directions,
//!   as the C API numbers it (JOINTLIN_REGIME_OPEN 0, STICK 1, MICROSLIP 2, SLIDING 3);
//!   −1 where the node is no contact point's;
//! - `contact_amplitude_ratio`: the larger A/δ* of its two directions (0 where none).
//!
//! With plots, each such frequency also gets its contact maps
//! (`contact_ratio_<frequency>_<unit>.svg`, `contact_energy_<frequency>_<unit>.svg`).

use std::path::{Path, PathBuf};

use super::contact_map::{self, MapKind};
use super::modes::cells;
use super::vtu::{unstructured_grid, PointField};
use crate::capi::JOINTLIN_REGIME_OPEN;
use crate::input::scene::Scene;
use crate::model::Problem;
use crate::run::RunResult;
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::Units;
use crate::solve::sweep::{PointFreq, SweepResult, C64};
use crate::util::atomic;
use crate::util::number::sig;

/// The file name of the field at `f` (1/time): `field_1174.500_Hz.vtu`.
pub fn file_name(f: f64, units: &Units) -> String {
    let fu = frequency_unit(units);
    format!("field_{}_{}.vtu", sig(fu.show(f)), fu.suffix())
}

/// Every kept field of `r` (the `[field_output]` sweep) as (file name, `.vtu` text).
pub fn files(
    p: &Problem,
    r: &SweepResult,
    closed: &[bool],
    units: &Units,
) -> Vec<(String, String)> {
    r.fields
        .iter()
        .map(|(f, x)| {
            let i = r.freqs.iter().position(|v| v == f);
            let points = i.and_then(|i| r.points.get(i)).map(Vec::as_slice);
            (
                file_name(*f, units),
                vtu(p, x, points.unwrap_or(&[]), closed, units),
            )
        })
        .collect()
}

/// The `.vtu` text of displacement `x` (free DOFs) with the points' states.
fn vtu(p: &Problem, x: &[C64], points: &[PointFreq], closed: &[bool], units: &Units) -> String {
    let full = p.sys.dofs.expand(x);
    let amp: Vec<f64> = full.iter().map(|z| z.norm()).collect();
    let re: Vec<f64> = full.iter().map(|z| z.re).collect();
    let im: Vec<f64> = full.iter().map(|z| z.im).collect();
    let nn = p.model.nodes.len();
    let mut regime = vec![-1.0; nn];
    let mut ratio = vec![0.0; nn];
    for (i, c) in p.contacts.iter().enumerate() {
        let (g, a) = match points.get(i) {
            Some(pf) if closed.get(i).copied().unwrap_or(false) => {
                (pf.regime[0].max(pf.regime[1]), pf.ratio[0].max(pf.ratio[1]))
            }
            _ => (JOINTLIN_REGIME_OPEN, 0.0),
        };
        for &n in &c.nodes {
            regime[n] = f64::from(g).max(regime[n]);
            ratio[n] = a.max(ratio[n]);
        }
    }
    let len = ColumnUnits::new(units).length;
    let names = [
        format!("displacement_amplitude_{len}"),
        format!("displacement_real_{len}"),
        format!("displacement_imag_{len}"),
    ];
    let fields = [
        PointField {
            name: &names[0],
            components: 3,
            values: &amp,
        },
        PointField {
            name: &names[1],
            components: 3,
            values: &re,
        },
        PointField {
            name: &names[2],
            components: 3,
            values: &im,
        },
        PointField {
            name: "contact_regime",
            components: 1,
            values: &regime,
        },
        PointField {
            name: "contact_amplitude_ratio",
            components: 1,
            values: &ratio,
        },
    ];
    unstructured_grid(&p.model.nodes, &cells(&p.model), &fields)
}

/// The contact maps (A/δ* and dissipated energy density per contact point, as
/// [`contact_map::svg`] draws them) of every kept field frequency of `fields`; none
/// for a model without contact points. Returns the files written.
pub fn contact_maps(
    dir: &Path,
    scene: &Scene,
    r: &RunResult,
    fields: &SweepResult,
) -> Result<Vec<PathBuf>, String> {
    let p = &r.problem;
    let mut out = Vec::new();
    if p.contacts.is_empty() {
        return Ok(out);
    }
    let units = &scene.spec.units;
    let fu = frequency_unit(units);
    for (f, _) in &fields.fields {
        let Some(points) = fields
            .freqs
            .iter()
            .position(|v| v == f)
            .and_then(|i| fields.points.get(i))
        else {
            continue;
        };
        let vals = contact_map::values(p, &r.stat.pressure, points);
        let at = format!("{} {}", sig(fu.show(*f)), fu.text);
        let tag = format!("{}_{}", sig(fu.show(*f)), fu.suffix());
        for (name, kind, what) in [
            ("ratio", MapKind::Ratio, "stick/slip A/δ*"),
            (
                "energy",
                MapKind::EnergyDensity,
                "dissipated energy density",
            ),
        ] {
            let path = dir.join(format!("contact_{name}_{tag}.svg"));
            let title = format!("{what} at {at}");
            atomic::with_temp(&path, |t| {
                contact_map::svg(t, &title, units, p, &vals, kind)
            })?;
            out.push(path);
        }
    }
    Ok(out)
}
