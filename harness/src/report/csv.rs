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

use std::fmt::Write as _;

use crate::capi::{
    JOINTLIN_REGIME_MICROSLIP, JOINTLIN_REGIME_OPEN, JOINTLIN_REGIME_SLIDING, JOINTLIN_REGIME_STICK,
};
use crate::input::scene::units::{frequency_column, ColumnUnits};
use crate::input::scene::Units;
use crate::model::Problem;
use crate::solve::sweep::SweepResult;

/// results.csv text.
pub fn results(p: &Problem, r: &SweepResult, units: &Units) -> String {
    let u = ColumnUnits::new(units);
    let mut s = frequency_column(units);
    for o in &p.outputs {
        let _ = write!(s, ",{0}_amp_{1},{0}_phase_deg", o.name, u.length);
    }
    let _ = writeln!(s, ",dissipated_power_{},status", u.power);
    for (i, f) in r.freqs.iter().enumerate() {
        let _ = write!(s, "{f:.10e}");
        if r.is_singular(i) || r.failure(i).is_some() {
            // No response computed: empty fields, never inf or NaN.
            s.push_str(&",".repeat(2 * r.outputs[i].len() + 1));
            s.push_str(if r.is_singular(i) {
                ",singular\n"
            } else {
                ",failed\n"
            });
            continue;
        }
        for v in &r.outputs[i] {
            let _ = write!(s, ",{:.10e},{:.6}", v.norm(), v.arg().to_degrees());
        }
        let status = if r.converged[i] {
            "converged"
        } else {
            "not_converged"
        };
        let _ = writeln!(s, ",{:.10e},{status}", r.power[i]);
    }
    s
}

/// harmonics.csv text (harmonic balance): the frequency, then per output and harmonic
/// h = 0..H `<name>_h<h>_amp_<length>` (h = 0 the mean deviation from the static state).
pub fn harmonics(p: &Problem, r: &SweepResult, units: &Units) -> String {
    let length = ColumnUnits::new(units).length;
    let mut s = frequency_column(units);
    let nh = r
        .harmonics
        .first()
        .and_then(|o| o.first())
        .map_or(0, Vec::len);
    for o in &p.outputs {
        for h in 0..nh {
            let _ = write!(s, ",{}_h{h}_amp_{length}", o.name);
        }
    }
    s.push('\n');
    for (i, (f, outs)) in r.freqs.iter().zip(&r.harmonics).enumerate() {
        let _ = write!(s, "{f:.10e}");
        if r.is_singular(i) {
            // No response computed: empty fields, as in results.csv.
            s.push_str(&",".repeat(outs.len() * nh));
            s.push('\n');
            continue;
        }
        for v in outs.iter().flatten() {
            let _ = write!(s, ",{:.10e}", v.norm());
        }
        s.push('\n');
    }
    s
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
/// energy_per_cycle_N_mm, ratio_t1, ratio_t2 (A/δ*), and with the stick/slip map
/// regime_t1, regime_t2.
pub fn points(
    p: &Problem,
    r: &SweepResult,
    closed: &[bool],
    pressure: &[f64],
    regimes: bool,
    units: &Units,
) -> String {
    let u = ColumnUnits::new(units);
    let (l, k, d) = (&u.length, &u.stiffness_per_area, &u.damping_per_area);
    let mut s = format!(
        "{},point,interface,x_{l},y_{l},z_{l},closed,pressure_{},amp_t1_{l},amp_t2_{l},k_star_t1_{k},k_star_t2_{k},d_star_t1_{d},d_star_t2_{d},energy_per_cycle_{},ratio_t1,ratio_t2",
        frequency_column(units),
        u.pressure,
        u.energy,
    );
    s.push_str(if regimes {
        ",regime_t1,regime_t2\n"
    } else {
        "\n"
    });
    for (fi, f) in r.freqs.iter().enumerate() {
        for (i, c) in p.contacts.iter().enumerate() {
            let q = &r.points[fi][i];
            let x = c.position;
            let _ = write!(
                s,
                "{f:.10e},{i},{},{},{},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}",
                p.interfaces[c.interface].name,
                x[0],
                x[1],
                x[2],
                u8::from(closed[i]),
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
            );
            if regimes {
                let _ = write!(
                    s,
                    ",{},{}",
                    regime_name(q.regime[0]),
                    regime_name(q.regime[1])
                );
            }
            s.push('\n');
        }
    }
    s
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
    let mut s = frequency_column(units);
    s.push_str(",open,stick,microslip,sliding,max_ratio,median_ratio\n");
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
        let _ = writeln!(
            s,
            "{f:.10e},{},{},{},{},{max:.6e},{median:.6e}",
            c[0], c[1], c[2], c[3]
        );
    }
    s
}
