//! A ladder's numbers against its reference: each rung's relative errors and the speed
//! ratios of the summary.

use super::Rung;

/// Each rung's errors against the last rung, the reference: |x / x_ref − 1| for the
/// amplitude and for the energy (0 when the reference dissipates nothing).
pub(super) fn against_reference(rungs: &mut [Rung]) {
    let rf = rungs.last().expect("reference").clone();
    for r in rungs {
        r.amplitude_error = (r.amplitude / rf.amplitude - 1.0).abs();
        r.energy_error = if rf.energy > 0.0 {
            (r.energy / rf.energy - 1.0).abs()
        } else {
            0.0
        };
    }
}

/// Speed ratios: for the default frequency-domain rung, the cheapest time-domain rung
/// (not the reference) at least as accurate in both quantities, and the ratio of wall
/// times; if none is, the reference's.
pub(super) fn ratios(rungs: &[Rung]) -> Vec<String> {
    let mut out = Vec::new();
    let Some(d) = rungs.iter().find(|r| r.family == "default") else {
        return out;
    };
    let err = |r: &Rung| r.amplitude_error.max(r.energy_error);
    let target = err(d);
    let cheapest = rungs
        .iter()
        .filter(|r| r.family == "time" && r.converged && err(r) <= target)
        .min_by(|a, b| a.seconds.total_cmp(&b.seconds));
    let reference = rungs
        .iter()
        .find(|r| r.family == "reference")
        .expect("reference");
    match cheapest {
        Some(t) => out.push(format!(
            "frequency domain (default) reaches {:.2e} (max of amplitude and energy error) in {:.3e} s; the cheapest time-domain run as accurate, {}, takes {:.3e} s: {:.0}× slower",
            target,
            d.seconds,
            t.label,
            t.seconds,
            t.seconds / d.seconds
        )),
        None => out.push(format!(
            "frequency domain (default) reaches {:.2e} in {:.3e} s; no time-domain rung below the reference is as accurate; the reference takes {:.3e} s: {:.0}× slower",
            target,
            d.seconds,
            reference.seconds,
            reference.seconds / d.seconds
        )),
    }
    out.push(format!(
        "reference time-domain run vs frequency domain (default): {:.0}× the wall time",
        reference.seconds / d.seconds
    ));
    let hb: Vec<String> = rungs
        .iter()
        .filter(|r| r.family == "harmonic" || r.family == "normal_load")
        .map(|r| {
            let name = r.label.split(" (").next().unwrap_or(&r.label);
            let name = name.trim_start_matches("harmonic balance ");
            let with = if r.family == "normal_load" {
                " with N(t)"
            } else {
                ""
            };
            format!("{name}{with}: {:.2e} in {:.2e} s", err(r), r.seconds)
        })
        .collect();
    if !hb.is_empty() {
        out.push(format!(
            "harmonic balance (max of amplitude and energy error): {}",
            hb.join("; ")
        ));
    }
    out
}
