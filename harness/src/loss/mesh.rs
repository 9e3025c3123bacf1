//! Mesh study of a loss study (thesis §5.4.2, "a finer mesh changes the loss by less
//! than 2 %"): the power at resonance at the first reference point's torque, at its
//! amplitude and a quarter of it (each at its own resonance, as [`power_at`]), for every
//! box's divisions multiplied by each factor, with the contact
//! law at the nodes (the thesis's way) and averaged over area samples
//! ([`crate::model::subgrid`]).

use std::fmt::Write as _;

use super::{power_at, LossError};
use crate::scene::Scene;

/// Samples per quarter face and direction of the area-sampled variant.
pub const STUDY_AREA_SAMPLES: usize = 4;

/// One mesh of the study.
#[derive(Debug, Clone)]
pub struct MeshRow {
    /// Divisions multiplied by this.
    pub factor: usize,
    pub free_dofs: usize,
    pub contact_points: usize,
    /// Resonance (1/time) per amplitude with the node-based law.
    pub freq: [f64; 2],
    /// Target amplitudes (scene length).
    pub amplitudes: [f64; 2],
    /// Power (reported unit) per amplitude: node-based, area-sampled.
    pub node: [f64; 2],
    pub sampled: [f64; 2],
    /// Node-based, per amplitude: share of the loss dissipated by points whose pressure
    /// is below [`LOW_PRESSURE`] × the largest pressure (the edges of the contact patch).
    pub low_pressure_share: [f64; 2],
}

/// "Low pressure" for [`MeshRow::low_pressure_share`]: below this fraction of the
/// largest contact pressure.
pub const LOW_PRESSURE: f64 = 0.2;

/// Share of the energy per cycle of `sample`'s points dissipated where the pressure is
/// below [`LOW_PRESSURE`] × the largest one.
fn low_pressure_share(pressure: &[f64], sample: &super::Sample) -> f64 {
    let p_max = pressure.iter().copied().fold(0.0, f64::max);
    let (mut low, mut all) = (0.0, 0.0);
    for (p, q) in pressure.iter().zip(&sample.points) {
        all += q.energy;
        if *p < LOW_PRESSURE * p_max {
            low += q.energy;
        }
    }
    if all > 0.0 {
        low / all
    } else {
        0.0
    }
}

/// The scene with every box's divisions multiplied by `factor`.
pub fn refined(scene: &Scene, factor: usize) -> Scene {
    let mut s = scene.clone();
    for b in &mut s.spec.bodies {
        if let Some(d) = &mut b.divisions {
            *d = d.map(|n| n * factor);
        }
    }
    s
}

/// Runs the study over `factors`; `progress(message)` before each model.
pub fn study(
    scene: &Scene,
    factors: &[usize],
    progress: &dyn Fn(&str),
) -> Result<Vec<MeshRow>, LossError> {
    let st = scene.spec.loss_study.as_ref().ok_or(LossError::NoStudy)?;
    let reference = st
        .reference
        .first()
        .ok_or_else(|| LossError::Spec("the mesh study needs a reference point".into()))?;
    let amplitudes = [0.25 * reference.amplitude, reference.amplitude];
    let mut rows = Vec::new();
    for &factor in factors {
        let mut row = MeshRow {
            factor,
            free_dofs: 0,
            contact_points: 0,
            freq: [0.0; 2],
            amplitudes,
            node: [0.0; 2],
            sampled: [0.0; 2],
            low_pressure_share: [0.0; 2],
        };
        for samples in [None, Some(STUDY_AREA_SAMPLES)] {
            progress(&format!(
                "divisions × {factor}, {}",
                samples.map_or("node-based".into(), |s| format!("{s} × {s} area samples"))
            ));
            let mut sc = refined(scene, factor);
            sc.spec
                .interfaces
                .iter_mut()
                .for_each(|i| i.area_samples = samples);
            // Each amplitude at its own resonance, as `power_at` (the trend tests') does.
            for (k, &a) in amplitudes.iter().enumerate() {
                let (got, op) = power_at(&sc, reference.torque, a)?;
                let power = got.power * st.power_factor;
                if samples.is_none() {
                    row.free_dofs = op.problem.sys.dofs.n_free();
                    row.contact_points = op.problem.contacts.len();
                    row.freq[k] = got.freq;
                    row.node[k] = power;
                    row.low_pressure_share[k] = low_pressure_share(&op.stat.pressure, &got);
                } else {
                    row.sampled[k] = power;
                }
            }
        }
        rows.push(row);
    }
    Ok(rows)
}

/// Change of `now` against `before`, percent.
fn change(before: Option<f64>, now: f64) -> String {
    before.map_or("".into(), |b| format!("{:+.1} %", 100.0 * (now - b) / b))
}

/// Markdown table of the study (power in the study's unit, change to the coarser mesh).
pub fn markdown(scene: &Scene, rows: &[MeshRow]) -> String {
    let Some(st) = scene.spec.loss_study.as_ref() else {
        return String::new();
    };
    let (pu, au, af) = (&st.power_unit, &st.amplitude_unit, st.amplitude_factor);
    let mut s = format!(
        "Mesh study, `{}` ({}): power loss at resonance, divisions of every box × factor; \
         low-p share: part of the node-based loss from points below {:.0} % of the largest \
         pressure.\n\n",
        scene.spec.title,
        scene.file,
        100.0 * LOW_PRESSURE
    );
    let Some(first) = rows.first() else {
        return s;
    };
    let [a0, a1] = first.amplitudes.map(|a| a / af);
    let _ = writeln!(
        s,
        "| × | free DOFs | points | resonance at {a1:.1} {au} | node-based {a0:.1} {au} [{pu}] | change | low-p share | node-based {a1:.1} {au} [{pu}] | change | low-p share | sampled {a0:.1} {au} [{pu}] | change | sampled {a1:.1} {au} [{pu}] | change |"
    );
    s.push_str("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (i, r) in rows.iter().enumerate() {
        let prev = i.checked_sub(1).map(|j| &rows[j]);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.1} | {:.4} | {} | {:.0} % | {:.4} | {} | {:.0} % | {:.4} | {} | {:.4} | {} |",
            r.factor,
            r.free_dofs,
            r.contact_points,
            r.freq[1],
            r.node[0],
            change(prev.map(|p| p.node[0]), r.node[0]),
            100.0 * r.low_pressure_share[0],
            r.node[1],
            change(prev.map(|p| p.node[1]), r.node[1]),
            100.0 * r.low_pressure_share[1],
            r.sampled[0],
            change(prev.map(|p| p.sampled[0]), r.sampled[0]),
            r.sampled[1],
            change(prev.map(|p| p.sampled[1]), r.sampled[1]),
        );
    }
    s
}

/// CSV of the study.
pub fn csv(rows: &[MeshRow]) -> String {
    let mut s = String::from(
        "factor,free_dofs,contact_points,frequency,amplitude,power_node_based,power_area_sampled,low_pressure_share\n",
    );
    for r in rows {
        for k in 0..2 {
            let _ = writeln!(
                s,
                "{},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}",
                r.factor,
                r.free_dofs,
                r.contact_points,
                r.freq[k],
                r.amplitudes[k],
                r.node[k],
                r.sampled[k],
                r.low_pressure_share[k]
            );
        }
    }
    s
}
