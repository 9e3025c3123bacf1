//! `field_<frequency>_<unit>.vtu` of `[field_output]`: the first-order displacement
//! field of one frequency and its contact state, for ParaView. Point data per node:
//!
//! - `displacement_amplitude_<length>`: |û| per global direction (x, y, z);
//! - `displacement_real_<length>`, `displacement_imag_<length>`: û (the phase: u(t) =
//!   Re(û e^{iωt}); animate with ParaView's "Warp By Vector" on the real part);
//! - `contact_regime`: per contact node the worse of its two tangential directions,
//!   as the C API numbers it (JOINTLIN_REGIME_OPEN 0, STICK 1, MICROSLIP 2, SLIDING 3);
//!   −1 where the node is no contact point's;
//! - `contact_amplitude_ratio`: the larger A/δ* of its two directions (0 where none);
//! - `contact_pressure_<force>_per_<length>2`: the static contact pressure;
//! - `k_star_t1_…`, `k_star_t2_…`, `d_star_t1_…`, `d_star_t2_…` (per area) and
//!   `energy_per_cycle_<force>_<length>` of the contact point (0 where none);
//! - `node_id`: the node as the user knows it (a deck's node id; a scene's node number
//!   as its exported deck numbers it).
//!
//! `fields.pvd` lists the files as a series over frequency (ParaView's time axis reads
//! the frequency in the outputs' unit).
//!
//! With plots, each such frequency also gets its contact maps
//! (`contact_ratio_<frequency>_<unit>.svg`, `contact_energy_<frequency>_<unit>.svg`).

use std::path::{Path, PathBuf};

use super::contact_map::{self, MapKind};
use super::modes::cells;
use super::vtu::{unstructured_grid, PointField};
use crate::capi::JOINTLIN_REGIME_OPEN;
use crate::model::{Job, Problem};
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

/// What a field file shows besides the displacement: the static contact state and the
/// nodes' ids.
pub struct FieldContext<'a> {
    pub closed: &'a [bool],
    /// Static contact pressure per point (force/length²).
    pub pressure: &'a [f64],
    /// Per model node, its id ([`crate::model::node_ids`]).
    pub node_ids: &'a [u64],
}

/// Every kept field of `r` (the `[field_output]` sweep) as (file name, `.vtu` text),
/// then `fields.pvd`, the series of them over frequency.
pub fn files(
    p: &Problem,
    r: &SweepResult,
    ctx: &FieldContext,
    units: &Units,
) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = r
        .fields
        .iter()
        .map(|(f, x)| {
            let i = r.freqs.iter().position(|v| v == f);
            let points = i.and_then(|i| r.points.get(i)).map(Vec::as_slice);
            (
                file_name(*f, units),
                vtu(p, x, points.unwrap_or(&[]), ctx, units),
            )
        })
        .collect();
    if !out.is_empty() {
        let fu = frequency_unit(units);
        let mut pvd = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n",
        );
        for ((f, _), (name, _)) in r.fields.iter().zip(&out) {
            pvd += &format!(
                "    <DataSet timestep=\"{:e}\" part=\"0\" file=\"{name}\"/>\n",
                fu.show(*f)
            );
        }
        pvd.push_str("  </Collection>\n</VTKFile>\n");
        out.push(("fields.pvd".into(), pvd));
    }
    out
}

/// The `.vtu` text of displacement `x` (free DOFs) with the points' states.
fn vtu(p: &Problem, x: &[C64], points: &[PointFreq], ctx: &FieldContext, units: &Units) -> String {
    let full = p.sys.dofs.expand(x);
    let amp: Vec<f64> = full.iter().map(|z| z.norm()).collect();
    let re: Vec<f64> = full.iter().map(|z| z.re).collect();
    let im: Vec<f64> = full.iter().map(|z| z.im).collect();
    let nn = p.model.nodes.len();
    let mut regime = vec![-1.0; nn];
    // Per node: A/δ*, pressure, k*₁, k*₂, d*₁, d*₂, energy (the larger where a node is
    // two points').
    let mut values = vec![[0.0f64; 7]; nn];
    for (i, c) in p.contacts.iter().enumerate() {
        let closed = ctx.closed.get(i).copied().unwrap_or(false);
        let (g, v) = match points.get(i) {
            Some(pf) if closed => (
                pf.regime[0].max(pf.regime[1]),
                [
                    pf.ratio[0].max(pf.ratio[1]),
                    ctx.pressure.get(i).copied().unwrap_or(0.0),
                    pf.k_star[0],
                    pf.k_star[1],
                    pf.d_star[0],
                    pf.d_star[1],
                    pf.energy,
                ],
            ),
            _ => (JOINTLIN_REGIME_OPEN, [0.0; 7]),
        };
        for &n in &c.nodes {
            regime[n] = f64::from(g).max(regime[n]);
            for (a, b) in values[n].iter_mut().zip(v) {
                *a = a.max(b);
            }
        }
    }
    let column = |k: usize| -> Vec<f64> { values.iter().map(|v| v[k]).collect() };
    let ids: Vec<f64> = (0..nn)
        .map(|n| ctx.node_ids.get(n).map_or(0.0, |&id| id as f64))
        .collect();
    let u = ColumnUnits::new(units);
    let (len, k, d) = (&u.length, &u.stiffness_per_area, &u.damping_per_area);
    let scalars: Vec<(String, Vec<f64>)> = vec![
        ("contact_regime".into(), regime),
        ("contact_amplitude_ratio".into(), column(0)),
        (format!("contact_pressure_{}", u.pressure), column(1)),
        (format!("k_star_t1_{k}"), column(2)),
        (format!("k_star_t2_{k}"), column(3)),
        (format!("d_star_t1_{d}"), column(4)),
        (format!("d_star_t2_{d}"), column(5)),
        (format!("energy_per_cycle_{}", u.energy), column(6)),
        ("node_id".into(), ids),
    ];
    let names = [
        format!("displacement_amplitude_{len}"),
        format!("displacement_real_{len}"),
        format!("displacement_imag_{len}"),
    ];
    let mut fields: Vec<PointField> = names
        .iter()
        .zip([&amp, &re, &im])
        .map(|(name, values)| PointField {
            name,
            components: 3,
            values,
        })
        .collect();
    fields.extend(scalars.iter().map(|(name, values)| PointField {
        name,
        components: 1,
        values,
    }));
    unstructured_grid(&p.model.nodes, &cells(&p.model), &fields)
}

/// The contact maps (A/δ* and dissipated energy density per contact point, as
/// [`contact_map::svg`] draws them) of every kept field frequency of `fields`; none
/// for a model without contact points. Returns the files written.
pub fn contact_maps(
    dir: &Path,
    job: &Job,
    r: &RunResult,
    fields: &SweepResult,
) -> Result<Vec<PathBuf>, String> {
    let p = &r.problem;
    let mut out = Vec::new();
    if p.contacts.is_empty() {
        return Ok(out);
    }
    let units = &job.settings.units;
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
