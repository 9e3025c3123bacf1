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

use super::modes::cells;
use super::vtu::{unstructured_grid, PointField};
use crate::capi::JOINTLIN_REGIME_OPEN;
use crate::input::scene::units::{frequency_unit, ColumnUnits};
use crate::input::scene::Units;
use crate::model::Problem;
use crate::solve::sweep::{PointFreq, SweepResult, C64};
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
