//! Mesh study of a loss study (thesis §5.4.2, "a finer mesh changes the loss by less
//! than 2 %"): the power at the first reference point's torque, at its amplitude and a
//! quarter of it, for every box's divisions multiplied by each factor, with the contact
//! law at the nodes (the thesis's way) and averaged over area samples
//! ([`crate::model::subgrid`]).

use std::fmt::Write as _;

use super::{curve, with_torque, LossError, Operating};
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
    /// Resonance (1/time) with the node-based law.
    pub freq: f64,
    /// Target amplitudes (scene length).
    pub amplitudes: [f64; 2],
    /// Power (reported unit) per amplitude: node-based, area-sampled.
    pub node: [f64; 2],
    pub sampled: [f64; 2],
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
    let grid = scene.frequencies();
    let mut rows = Vec::new();
    for &factor in factors {
        let mut row = MeshRow {
            factor,
            free_dofs: 0,
            contact_points: 0,
            freq: 0.0,
            amplitudes,
            node: [0.0; 2],
            sampled: [0.0; 2],
        };
        for samples in [None, Some(STUDY_AREA_SAMPLES)] {
            progress(&format!(
                "divisions × {factor}, {}",
                samples.map_or("node-based".into(), |s| format!("{s} × {s} area samples"))
            ));
            let mut sc = with_torque(&refined(scene, factor), &st.screw, reference.torque)?;
            sc.spec
                .interfaces
                .iter_mut()
                .for_each(|i| i.area_samples = samples);
            let mut op = Operating::new(&sc, &st.output, st.model_share)?;
            let got = curve(&mut op, &grid, &amplitudes)?;
            let power = [0, 1].map(|k| got[k].power * st.power_factor);
            if samples.is_none() {
                row.free_dofs = op.problem.sys.dofs.n_free();
                row.contact_points = op.problem.contacts.len();
                row.freq = got[1].freq;
                row.node = power;
            } else {
                row.sampled = power;
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
        "Mesh study, `{}` ({}): power loss at resonance, divisions of every box × factor.\n\n",
        scene.spec.title, scene.file
    );
    let Some(first) = rows.first() else {
        return s;
    };
    let [a0, a1] = first.amplitudes.map(|a| a / af);
    let _ = writeln!(
        s,
        "| × | free DOFs | points | resonance | node-based {a0:.1} {au} [{pu}] | change | node-based {a1:.1} {au} [{pu}] | change | sampled {a0:.1} {au} [{pu}] | change | sampled {a1:.1} {au} [{pu}] | change |"
    );
    s.push_str("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (i, r) in rows.iter().enumerate() {
        let prev = i.checked_sub(1).map(|j| &rows[j]);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.1} | {:.4} | {} | {:.4} | {} | {:.4} | {} | {:.4} | {} |",
            r.factor,
            r.free_dofs,
            r.contact_points,
            r.freq,
            r.node[0],
            change(prev.map(|p| p.node[0]), r.node[0]),
            r.node[1],
            change(prev.map(|p| p.node[1]), r.node[1]),
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
        "factor,free_dofs,contact_points,frequency,amplitude,power_node_based,power_area_sampled\n",
    );
    for r in rows {
        for k in 0..2 {
            let _ = writeln!(
                s,
                "{},{},{},{:.6e},{:.6e},{:.6e},{:.6e}",
                r.factor,
                r.free_dofs,
                r.contact_points,
                r.freq,
                r.amplitudes[k],
                r.node[k],
                r.sampled[k]
            );
        }
    }
    s
}
