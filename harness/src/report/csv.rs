//! results.csv, harmonics.csv, points.csv and stick_slip.csv.
//!
//! Every column carries the scene's units ([`ColumnUnits`]); below for N, mm, s.
//!
//! results.csv: `frequency_Hz` (`frequency_per_<time>` for other time units), then per
//! named output `<name>_amp_mm` and `<name>_phase_deg` (degrees, of u = Re(û e^{iωt})),
//! then `dissipated_power_N_mm_per_s` (power dissipated in the joints: mW) and `status`
//! (`converged`, `not_converged`, `singular`: the dynamic stiffness was singular
//! there, see [`crate::solve::sweep::SINGULAR_RCOND`], or `failed`: a library call or a
//! solve failed at that frequency, its message in run.json `failed_frequencies`; the
//! other fields of a singular or failed row are empty).

use crate::capi::{
    JOINTLIN_REGIME_MICROSLIP, JOINTLIN_REGIME_OPEN, JOINTLIN_REGIME_SLIDING, JOINTLIN_REGIME_STICK,
};
use crate::model::Problem;
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::Units;
use crate::solve::sweep::SweepResult;
use crate::util::number::exact;

use crate::util::csv_table::CsvTable;

/// results.csv text.
pub fn results(p: &Problem, r: &SweepResult, units: &Units) -> String {
    let u = ColumnUnits::new(units);
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    for o in &p.outputs {
        header.push(format!("{}_amp_{}", o.name, u.length));
        header.push(format!("{}_phase_deg", o.name));
    }
    header.push(format!("dissipated_power_{}", u.power));
    header.push("status".into());
    let mut t = CsvTable::new(&header);
    for (i, f) in r.freqs.iter().enumerate() {
        let mut row = vec![exact(fu.show(*f))];
        let status = r.status(i);
        if status.has_response() {
            for v in &r.outputs[i] {
                row.push(exact(v.norm()));
                row.push(exact(v.arg().to_degrees()));
            }
            row.push(exact(r.power[i]));
        } else {
            // No response computed: empty fields, never inf or NaN.
            row.resize(header.len() - 1, String::new());
        }
        row.push(status.name().into());
        t.row(&row);
    }
    t.finish()
}

/// The harmonics.csv columns of output `name` at harmonics 0..=`h`:
/// `<name>_h0_mean_<length>` (signed mean deviation from the static state), then per
/// h ≥ 1 `<name>_h<h>_amp_<length>` and `<name>_h<h>_phase_deg`, so that the output over
/// a period is u(t) = mean + Σ_h amp_h cos(h ω t + phase_h) — results.csv's amplitude
/// and phase are those of h = 1.
pub fn harmonic_columns(name: &str, h: usize, length: &str) -> Vec<String> {
    let mut c = vec![format!("{name}_h0_mean_{length}")];
    for k in 1..=h {
        c.push(format!("{name}_h{k}_amp_{length}"));
        c.push(format!("{name}_h{k}_phase_deg"));
    }
    c
}

/// The values of [`harmonic_columns`] for the complex amplitudes û_h, h = 0..=H
/// (u(t) = Re Σ û_h e^{ihωt}; û_0 real).
pub fn harmonic_values(u: &[nalgebra::Complex<f64>]) -> Vec<f64> {
    let mut v = Vec::with_capacity(2 * u.len());
    for (k, c) in u.iter().enumerate() {
        if k == 0 {
            v.push(c.re);
        } else {
            v.push(c.norm());
            v.push(c.arg().to_degrees());
        }
    }
    v
}

/// harmonics.csv text (harmonic balance): the frequency, then per output its
/// [`harmonic_columns`].
pub fn harmonics(p: &Problem, r: &SweepResult, units: &Units) -> String {
    let length = ColumnUnits::new(units).length;
    let nh = r
        .harmonics
        .first()
        .and_then(|o| o.first())
        .map_or(0, Vec::len);
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    for o in &p.outputs {
        header.extend(harmonic_columns(&o.name, nh.saturating_sub(1), &length));
    }
    let mut t = CsvTable::new(&header);
    for (i, (f, outs)) in r.freqs.iter().zip(&r.harmonics).enumerate() {
        let mut row = vec![exact(fu.show(*f))];
        if !r.status(i).has_response() {
            // No response computed (singular or failed): empty fields, as in results.csv.
            row.resize(header.len(), String::new());
        } else {
            for o in outs {
                row.extend(harmonic_values(o).iter().map(|v| exact(*v)));
            }
        }
        t.row(&row);
    }
    t.finish()
}

/// Regime name.
pub fn regime_name(code: i32) -> &'static str {
    match code {
        JOINTLIN_REGIME_OPEN => "open",
        JOINTLIN_REGIME_STICK => "stick",
        JOINTLIN_REGIME_MICROSLIP => "microslip",
        JOINTLIN_REGIME_SLIDING => "sliding",
        _ => "unknown",
    }
}

/// points.csv text: per contact point and frequency. Open points have all zeros.
/// Columns (N, mm, s): frequency_Hz, point, interface, x_mm, y_mm, z_mm, closed,
/// pressure_N_per_mm2, amp_t1_mm, amp_t2_mm, k_star_t1_N_per_mm3, k_star_t2_N_per_mm3
/// (per area), d_star_t1_N_s_per_mm3, d_star_t2_N_s_per_mm3 (per area),
/// energy_per_cycle_N_mm, ratio_t1, ratio_t2 (A/δ*), with the stick/slip map
/// regime_t1, regime_t2, then node (`node_ids` of the upper/slave node) and the frame
/// n_x … t2_z.
pub fn points(
    p: &Problem,
    r: &SweepResult,
    closed: &[bool],
    pressure: &[f64],
    regimes: bool,
    units: &Units,
    node_ids: &[u64],
) -> String {
    let u = ColumnUnits::new(units);
    let (l, k, d) = (&u.length, &u.stiffness_per_area, &u.damping_per_area);
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    header.extend([
        "point".to_string(),
        "interface".into(),
        format!("x_{l}"),
        format!("y_{l}"),
        format!("z_{l}"),
        "closed".into(),
        format!("pressure_{}", u.pressure),
        format!("amp_t1_{l}"),
        format!("amp_t2_{l}"),
        format!("k_star_t1_{k}"),
        format!("k_star_t2_{k}"),
        format!("d_star_t1_{d}"),
        format!("d_star_t2_{d}"),
        format!("energy_per_cycle_{}", u.energy),
        "ratio_t1".into(),
        "ratio_t2".into(),
    ]);
    if regimes {
        header.push("regime_t1".into());
        header.push("regime_t2".into());
    }
    // The point's node (the deck's slave node id; a scene's node number as its exported
    // deck numbers it) and its frame: normal n and the tangential t1, t2 of the
    // amplitude, k* and d* columns, each in global components.
    header.push("node".into());
    for axis in ["n", "t1", "t2"] {
        header.extend(["x", "y", "z"].map(|c| format!("{axis}_{c}")));
    }
    let mut t = CsvTable::new(&header);
    for (fi, f) in r.freqs.iter().enumerate() {
        for (i, c) in p.contacts.iter().enumerate() {
            let q = &r.points[fi][i];
            let x = c.position;
            let mut row = vec![
                exact(fu.show(*f)),
                i.to_string(),
                p.interfaces[c.interface].name.clone(),
                x[0].to_string(),
                x[1].to_string(),
                x[2].to_string(),
                u8::from(closed[i]).to_string(),
            ];
            row.extend(
                [
                    pressure[i],
                    q.amplitude[0],
                    q.amplitude[1],
                    q.k_star[0],
                    q.k_star[1],
                    q.d_star[0],
                    q.d_star[1],
                    q.energy,
                    q.ratio[0],
                    q.ratio[1],
                ]
                .iter()
                .map(|v| exact(*v)),
            );
            if regimes {
                row.push(regime_name(q.regime[0]).into());
                row.push(regime_name(q.regime[1]).into());
            }
            row.push(
                node_ids
                    .get(c.nodes[1])
                    .map_or(String::new(), u64::to_string),
            );
            row.extend(c.frame.iter().map(|v| exact(v + 0.0)));
            t.row(&row);
        }
    }
    t.finish()
}

/// Points per regime (worst of the two directions) per frequency.
pub fn regime_counts(r: &SweepResult, closed: &[bool]) -> Vec<[usize; 4]> {
    r.points
        .iter()
        .map(|pts| {
            let mut c = [0usize; 4];
            for (i, q) in pts.iter().enumerate() {
                let g = if closed[i] {
                    q.regime[0].max(q.regime[1])
                } else {
                    JOINTLIN_REGIME_OPEN
                };
                c[g.clamp(0, 3) as usize] += 1;
            }
            c
        })
        .collect()
}

/// stick_slip.csv: the frequency, open, stick, microslip, sliding (point counts, worst
/// direction), then max and median A/δ* over the closed points.
pub fn stick_slip(r: &SweepResult, closed: &[bool], units: &Units) -> String {
    let fu = frequency_unit(units);
    let mut t = CsvTable::new([
        fu.column.as_str(),
        "open",
        "stick",
        "microslip",
        "sliding",
        "max_ratio",
        "median_ratio",
    ]);
    for ((f, c), pts) in r.freqs.iter().zip(regime_counts(r, closed)).zip(&r.points) {
        let mut ratios: Vec<f64> = pts
            .iter()
            .zip(closed)
            .filter(|(_, &c)| c)
            .map(|(q, _)| q.ratio[0].max(q.ratio[1]))
            .collect();
        ratios.sort_by(f64::total_cmp);
        let max = ratios.last().copied().unwrap_or(0.0);
        let median = ratios.get(ratios.len() / 2).copied().unwrap_or(0.0);
        let mut row = vec![exact(fu.show(*f))];
        row.extend(c.iter().map(usize::to_string));
        row.push(exact(max));
        row.push(exact(median));
        t.row(&row);
    }
    t.finish()
}
