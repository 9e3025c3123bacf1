//! The files of a time-domain run: results_time.csv, points_time.csv, loops_time.csv and
//! run.json (the scene's units in every column name).

use std::path::{Path, PathBuf};

use super::scene_run::{FreqResult, TimeRun};
use crate::capi;
use crate::mhb::loops::LoopSample;
use crate::model::Job;
use crate::model::Problem;
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::Units;
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;
use crate::util::provenance;

/// results_time.csv (units as in results.csv, e.g. N, mm, s): frequency_Hz; per output
/// `<name>_amp_mm`, `<name>_phase_deg` (first harmonic, u ≈ x̄ + Re(û e^{iωt})),
/// `<name>_half_range_mm` ((max − min)/2), `<name>_max_mm`, `<name>_min_mm`;
/// dissipated_power_N_mm_per_s (Σ energy per cycle × f); energy_per_cycle_N_mm;
/// energy_trapezoid_N_mm (check); integrator, steps_per_cycle, cycles, steady, distance
/// (relative), loose_steps, cut_steps (Newton acceptances at the loose tolerance, steps
/// cut in two), wall_time_s (wall clock).
pub fn results_csv(p: &Problem, r: &[FreqResult], units: &Units) -> String {
    let u = ColumnUnits::new(units);
    let l = &u.length;
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    for o in &p.outputs {
        let n = &o.name;
        header.extend([
            format!("{n}_amp_{l}"),
            format!("{n}_phase_deg"),
            format!("{n}_half_range_{l}"),
            format!("{n}_max_{l}"),
            format!("{n}_min_{l}"),
        ]);
    }
    header.extend(run_columns(&u));
    let mut t = CsvTable::new(&header);
    for x in r {
        let mut row = vec![exact(fu.show(x.freq))];
        for o in &x.last.outputs {
            row.extend([
                exact(o.amplitude),
                exact(o.phase_deg),
                exact(o.half_range()),
                exact(o.max),
                exact(o.min),
            ]);
        }
        row.extend([
            exact(x.last.energy * x.freq),
            exact(x.last.energy),
            exact(x.last.energy_trapezoid),
            x.integrator.to_string(),
            x.steps_per_cycle.to_string(),
            x.cycles.to_string(),
            x.steady.to_string(),
            exact(x.distance),
            x.loose_steps.to_string(),
            x.cut_steps.to_string(),
            exact(x.seconds),
        ]);
        t.row(&row);
    }
    t.finish()
}

/// The closing columns of every results_time.csv: dissipated_power, energy_per_cycle,
/// energy_trapezoid (in the scene's units), integrator, steps_per_cycle, cycles, steady,
/// distance, loose_steps, cut_steps, wall_time_s.
pub fn run_columns(u: &ColumnUnits) -> Vec<String> {
    let mut c = vec![
        format!("dissipated_power_{}", u.power),
        format!("energy_per_cycle_{}", u.energy),
        format!("energy_trapezoid_{}", u.energy),
    ];
    c.extend(
        [
            "integrator",
            "steps_per_cycle",
            "cycles",
            "steady",
            "distance",
            "loose_steps",
            "cut_steps",
            "wall_time_s",
        ]
        .map(String::from),
    );
    c
}

/// points_time.csv (e.g. N, mm, s): frequency_Hz, point, interface, x_mm, y_mm, z_mm,
/// energy_per_cycle_N_mm, then as points.csv the point's node (`node_ids` of its
/// upper/slave node) and its frame n_x … t2_z in global components.
pub fn points_csv(p: &Problem, r: &[FreqResult], units: &Units, node_ids: &[u64]) -> String {
    let u = ColumnUnits::new(units);
    let l = &u.length;
    let fu = frequency_unit(units);
    let mut header = vec![
        fu.column.clone(),
        "point".into(),
        "interface".into(),
        format!("x_{l}"),
        format!("y_{l}"),
        format!("z_{l}"),
        format!("energy_per_cycle_{}", u.energy),
        "node".into(),
    ];
    for axis in ["n", "t1", "t2"] {
        header.extend(["x", "y", "z"].map(|c| format!("{axis}_{c}")));
    }
    let mut t = CsvTable::new(&header);
    for x in r {
        for (i, (c, e)) in p.contacts.iter().zip(&x.last.point_energy).enumerate() {
            let mut row = vec![
                exact(fu.show(x.freq)),
                i.to_string(),
                p.interfaces[c.interface].name.clone(),
                c.position[0].to_string(),
                c.position[1].to_string(),
                c.position[2].to_string(),
                exact(*e),
                node_ids
                    .get(c.nodes[1])
                    .map_or(String::new(), u64::to_string),
            ];
            row.extend(c.frame.iter().map(|v| exact(v + 0.0)));
            t.row(&row);
        }
    }
    t.finish()
}

/// loops_time.csv (e.g. N, mm, s) at the frequency of the largest response (the one
/// whose loops [`super::scene_run::sweep`] kept), every contact point
/// ([`point_loops_csv`]); None without such a frequency.
pub fn loops_csv(p: &Problem, r: &[FreqResult], units: &Units, node_ids: &[u64]) -> Option<String> {
    let x = r.iter().find(|x| !x.loops.is_empty())?;
    let all: Vec<usize> = (0..p.contacts.len()).collect();
    let loops = PointLoops {
        freq: x.freq,
        samples: &x.loops,
        points: &all,
        overclosure: true,
    };
    Some(point_loops_csv(p, &loops, units, node_ids))
}

/// Contact points' loops over one period at one frequency.
pub struct PointLoops<'a> {
    /// Frequency (1/time).
    pub freq: f64,
    /// Per sample t_k = kT/N (k = 1..N), per contact point of the problem.
    pub samples: &'a [Vec<LoopSample>],
    /// The points written (indices into the problem's contacts).
    pub points: &'a [usize],
    /// Whether the overclosure is written (it is part of the solution).
    pub overclosure: bool,
}

/// A loops table (e.g. N, mm, s): frequency_Hz, point, interface, node, step (1..N),
/// time_s (from the period's start), u1_mm, u2_mm (tangential relative displacements),
/// overclosure_mm (−δ_n, where written), f1_N, f2_N (tangential forces on the upper
/// side), normal_force_N (compressive > 0).
pub fn point_loops_csv(p: &Problem, l: &PointLoops, units: &Units, node_ids: &[u64]) -> String {
    let u = ColumnUnits::new(units);
    let (len, force) = (&u.length, &units.force);
    let fu = frequency_unit(units);
    let mut header = vec![
        fu.column.clone(),
        "point".into(),
        "interface".into(),
        "node".into(),
        "step".into(),
        format!("time_{}", units.time),
        format!("u1_{len}"),
        format!("u2_{len}"),
    ];
    if l.overclosure {
        header.push(format!("overclosure_{len}"));
    }
    header.extend([
        format!("f1_{force}"),
        format!("f2_{force}"),
        format!("normal_force_{force}"),
    ]);
    let mut t = CsvTable::new(&header);
    let h = 1.0 / (l.freq * l.samples.len() as f64);
    for &i in l.points {
        let c = &p.contacts[i];
        for (k, at) in l.samples.iter().enumerate() {
            let mut row = vec![
                exact(fu.show(l.freq)),
                i.to_string(),
                p.interfaces[c.interface].name.clone(),
                node_ids
                    .get(c.nodes[1])
                    .map_or(String::new(), u64::to_string),
                (k + 1).to_string(),
                exact((k + 1) as f64 * h),
            ];
            let s = at[i];
            let d = &s.displacement[..if l.overclosure { 3 } else { 2 }];
            row.extend(d.iter().chain(&s.force).map(|v| exact(*v)));
            t.row(&row);
        }
    }
    t.finish()
}

/// Writes `text` to `dir/name` (atomically: a temporary name, then renamed) and records
/// its path in `files`.
pub fn put_file(
    dir: &Path,
    files: &mut Vec<PathBuf>,
    name: &str,
    text: &str,
) -> std::io::Result<()> {
    let f = dir.join(name);
    crate::util::atomic::write_text(&f, text).map_err(std::io::Error::other)?;
    files.push(f);
    Ok(())
}

/// Writes results_time.csv, points_time.csv, loops_time.csv and, last, run.json into
/// `dir`.
pub fn write(dir: &Path, job: &Job, run: &TimeRun) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut files = Vec::new();
    let mut put = |name: &str, text: String| put_file(dir, &mut files, name, &text);
    let units = &job.settings.units;
    put(
        "results_time.csv",
        results_csv(&run.problem, &run.results, units),
    )?;
    let node_ids = job.node_ids(&run.problem);
    put(
        "points_time.csv",
        points_csv(&run.problem, &run.results, units, &node_ids),
    )?;
    if let Some(text) = loops_csv(&run.problem, &run.results, units, &node_ids) {
        put("loops_time.csv", text)?;
    }
    let head = provenance::head("run --time-domain", &capi::abi_version(), job.sources());
    let json = provenance::with_head(
        head,
        serde_json::json!({
            "scene": job.file(),
            "title": job.settings.title,
            // The frequencies below are cycles per time unit.
            "frequency_unit": format!("1/{}", units.time),
            "settings": run.settings,
            "free_dofs": run.problem.sys.dofs.n_free(),
            "contact_points": run.problem.contacts.len(),
            "seconds": run.seconds,
            "frequencies": run.results,
        }),
    );
    let text = serde_json::to_string_pretty(&json).map_err(std::io::Error::other)?;
    // Last: its presence marks a complete directory, as for a frequency-domain run.
    files.push(crate::util::atomic::write_marker(dir, &text).map_err(std::io::Error::other)?);
    Ok(files)
}
