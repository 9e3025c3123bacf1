//! The files of a lumped scene's time-domain run: results_time.csv, loops_time.csv and
//! run.json (the scene's units in every column name).

use std::path::{Path, PathBuf};

use super::lumped::{LoopSample, Settled};
use super::lumped_sweep::{LumpedFreq, LumpedTimeRun};
use super::tables::{put_file, run_columns};
use crate::capi;
use crate::model::lumped::Lumped;
use crate::model::Job;
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::Units;
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;
use crate::util::provenance;

/// results_time.csv (e.g. N, m, s): frequency_Hz; per output `<name>_amp_m`,
/// `<name>_phase_deg` (first harmonic, u ≈ x̄ + Re(û e^{iωt})), `<name>_half_range_m`, _max_m,
/// _min_m; per joint `<joint>_energy_N_m` (dissipated per cycle) and, where its normal
/// force varies, `<joint>_normal_force_min_N` and _max_N; dissipated_power_N_m_per_s,
/// energy_per_cycle_N_m (all elements), energy_trapezoid_N_m (Σ ½(F + F₊)·Δδ over the
/// tangential components, a check); integrator, steps_per_cycle, cycles, steady,
/// distance, loose_steps and cut_steps (0: RK4), wall_time_s; status ("converged",
/// "not periodic" or why the integration stopped, its fields empty).
pub fn results_csv(l: &Lumped, r: &[LumpedFreq], units: &Units) -> String {
    let u = ColumnUnits::new(units);
    let len = &u.length;
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    for (name, _) in &l.outputs {
        header.extend(
            ["amp", "phase", "half_range", "max", "min"].map(|q| match q {
                "phase" => format!("{name}_phase_deg"),
                _ => format!("{name}_{q}_{len}"),
            }),
        );
    }
    for j in &l.joints {
        header.push(format!("{}_energy_{}", j.name, u.energy));
        if j.normal_varies && j.point.is_some() {
            header.push(format!("{}_normal_force_min_{}", j.name, units.force));
            header.push(format!("{}_normal_force_max_{}", j.name, units.force));
        }
    }
    header.extend(run_columns(&u));
    header.push("status".into());
    let mut t = CsvTable::new(&header);
    for x in r {
        let mut row = vec![exact(fu.show(x.freq))];
        match &x.result {
            Ok(s) => {
                let n = l.dofs.len();
                for o in &s.last.outputs[n..] {
                    row.extend([o.amplitude, o.phase_deg, o.half_range(), o.max, o.min].map(exact));
                }
                row.extend(joint_values(l, s).into_iter().map(exact));
                row.extend(
                    [
                        s.last.energy * x.freq,
                        s.last.energy,
                        s.last.energy_trapezoid,
                    ]
                    .map(exact),
                );
                row.extend([
                    "rk4".to_string(),
                    x.steps_per_cycle.to_string(),
                    s.cycles.to_string(),
                    s.steady.to_string(),
                    exact(s.distance),
                    // RK4 has no Newton iteration to loosen and no step control.
                    "0".into(),
                    "0".into(),
                    exact(s.seconds),
                    if s.steady {
                        "converged"
                    } else {
                        "not periodic"
                    }
                    .to_string(),
                ]);
            }
            Err(e) => {
                row.resize(header.len() - 1, String::new());
                row.push(format!("failed: {e}"));
            }
        }
        t.row(&row);
    }
    t.finish()
}

/// Per joint: the energy its elements and point dissipated in the last cycle and, where
/// its normal force varies, the point's normal force range (the columns of
/// [`results_csv`]).
fn joint_values(l: &Lumped, s: &Settled) -> Vec<f64> {
    let one_d = l.system.elements.len();
    let mut v = Vec::new();
    for j in &l.joints {
        let elements: f64 = j.elements.iter().map(|&e| s.last.point_energy[e]).sum();
        let point = j.point.map_or(0.0, |p| s.last.point_energy[one_d + p]);
        v.push(elements + point);
        if let (true, Some(p)) = (j.normal_varies, j.point) {
            v.extend([s.normal_range[p].0, s.normal_range[p].1]);
        }
    }
    v
}

/// A joint's sample: its point's, or its one-direction elements' along t₁ and t₂ with the
/// static normal force.
pub fn joint_sample(l: &Lumped, joint: usize, samples: &[LoopSample]) -> LoopSample {
    let j = &l.joints[joint];
    if let Some(p) = j.point {
        return samples[l.system.elements.len() + p];
    }
    let mut s = LoopSample {
        displacement: [0.0; 3],
        force: [0.0, 0.0, j.static_normal.unwrap_or(0.0)],
    };
    for (a, &e) in j.elements.iter().take(2).enumerate() {
        s.displacement[a] = samples[e].displacement[0];
        s.force[a] = samples[e].force[0];
    }
    s
}

/// A loops table (loops_time.csv of the time domain, loops.csv of the balance; e.g. N,
/// m, s): per frequency, joint and sample of one period frequency_Hz, joint, step (1..N),
/// time_s (from the period's start), u1_m, u2_m (the tangential relative displacements),
/// overclosure_m (a point's h; 0 for a joint at a fixed normal force), f1_N, f2_N (the
/// tangential forces), normal_force_N. `loops`: per frequency (1/time) the samples of
/// every element at t_k = kT/N, k = 1..N.
pub fn loops_csv(l: &Lumped, loops: &[(f64, &[Vec<LoopSample>])], units: &Units) -> String {
    let u = ColumnUnits::new(units);
    let (len, force) = (&u.length, &units.force);
    let fu = frequency_unit(units);
    let mut header = vec![
        fu.column.clone(),
        "joint".into(),
        "step".into(),
        format!("time_{}", units.time),
    ];
    header.extend([
        format!("u1_{len}"),
        format!("u2_{len}"),
        format!("overclosure_{len}"),
        format!("f1_{force}"),
        format!("f2_{force}"),
        format!("normal_force_{force}"),
    ]);
    let mut t = CsvTable::new(&header);
    for &(freq, samples) in loops {
        let h = 1.0 / (freq * samples.len() as f64);
        for (j, joint) in l.joints.iter().enumerate() {
            for (k, at) in samples.iter().enumerate() {
                let js = joint_sample(l, j, at);
                let mut row = vec![
                    exact(fu.show(freq)),
                    joint.name.clone(),
                    (k + 1).to_string(),
                    exact((k + 1) as f64 * h),
                ];
                row.extend(js.displacement.iter().chain(&js.force).map(|v| exact(*v)));
                t.row(&row);
            }
        }
    }
    t.finish()
}

/// Writes results_time.csv, loops_time.csv and, last, run.json into `dir`.
pub fn write(dir: &Path, job: &Job, run: &LumpedTimeRun) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut files = Vec::new();
    let mut put = |name: &str, text: String| put_file(dir, &mut files, name, &text);
    let units = &job.settings.units;
    let l = &run.lumped;
    put("results_time.csv", results_csv(l, &run.results, units))?;
    if !l.joints.is_empty() {
        let loops: Vec<(f64, &[Vec<LoopSample>])> = run
            .results
            .iter()
            .filter_map(|x| x.result.as_ref().ok().map(|s| (x.freq, s.loops.as_slice())))
            .collect();
        put("loops_time.csv", loops_csv(l, &loops, units))?;
    }
    let fu = frequency_unit(units);
    let frequencies: Vec<serde_json::Value> = run
        .results
        .iter()
        .map(|x| match &x.result {
            Ok(s) => serde_json::json!({
                "frequency": fu.show(x.freq),
                "steps_per_cycle": x.steps_per_cycle,
                "cycles": s.cycles,
                "steady": s.steady,
                "distance": s.distance,
                "energy_per_cycle": s.last.energy,
                "energy_trapezoid": s.last.energy_trapezoid,
                "seconds": s.seconds,
            }),
            Err(e) => serde_json::json!({
                "frequency": fu.show(x.freq),
                "steps_per_cycle": x.steps_per_cycle,
                "error": e,
            }),
        })
        .collect();
    let head = provenance::head("run --time-domain", &capi::abi_version(), job.sources());
    let json = provenance::with_head(
        head,
        serde_json::json!({
            "scene": job.file(),
            "title": job.settings.title,
            "units": units,
            "frequency_unit": fu.text,
            "method": "time domain, RK4 (the library's points through jointlin_point_step and jointlin_point3d_step), lumped system",
            "settings": run.settings,
            "dofs": l.dofs,
            "static_displacement": run.static_x,
            "highest_stuck_frequency": fu.show(run.highest_frequency),
            "seconds": run.seconds,
            "frequencies": frequencies,
        }),
    );
    let text = serde_json::to_string_pretty(&json).map_err(std::io::Error::other)?;
    // Last: its presence marks a complete directory, as for a frequency-domain run.
    files.push(crate::util::atomic::write_marker(dir, &text).map_err(std::io::Error::other)?);
    Ok(files)
}

/// The integrated frequency with the largest first output amplitude (the first DOF's
/// without outputs).
pub fn peak<'r>(l: &Lumped, r: &'r [LumpedFreq]) -> Option<(f64, &'r Settled)> {
    let at = if l.outputs.is_empty() {
        0
    } else {
        l.dofs.len()
    };
    r.iter()
        .filter_map(|x| x.result.as_ref().ok().map(|s| (x.freq, s)))
        .max_by(|a, b| {
            a.1.last.outputs[at]
                .amplitude
                .total_cmp(&b.1.last.outputs[at].amplitude)
        })
}
