//! A lumped scene's run (mass bodies, `[[matrices]]`, springs, joints) and its files:
//! the thesis's first-order method per frequency (`mhb::first_order`: every joint's k*,
//! d* from `jointlin_linearize` consistent with its amplitude, (3.8), (3.14)), or with
//! `mode = "harmonic_balance"` the multi-harmonic balance at H harmonics (`mhb::Hb`:
//! the joints marched through `jointlin_point_step` by AFT, Newton), each frequency
//! started from the previous one's solution (harmonic balance: else from the stuck
//! linear response); swept up, down or both as `[sweep] direction` says; results.csv
//! (results_down.csv), harmonics.csv, loops.csv, frf.svg, loops.svg and run.json.

use std::path::{Path, PathBuf};

use nalgebra::Complex;
use serde_json::json;

use super::csv::{harmonic_columns, harmonic_values};
use super::frf_plot::{frf_curves, FrfCurve};
use super::loop_plot::{self, JointLoop};
use crate::capi;
use crate::mhb::default_samples;
use crate::mhb::loops::{balance_loops, LoopSample};
use crate::mhb::lumped_sweep::{Solved, Sweep};
use crate::model::lumped::Lumped;
use crate::model::Job;
use crate::settings::units::{frequency_unit, ColumnUnits};
use crate::settings::{Direction, Mode, Units};
use crate::time::lumped_tables::{joint_sample, loops_csv};
use crate::util::csv_table::CsvTable;
use crate::util::number::exact;
use crate::util::{atomic, provenance};

/// What a lumped run wrote and solved.
#[derive(Debug)]
pub struct LumpedRun {
    /// Every file written, run.json last.
    pub written: Vec<PathBuf>,
    /// Frequencies solved, over every pass.
    pub solved: usize,
    /// Of those, the ones that did not converge.
    pub failed: usize,
}

/// One sweep pass: its results.csv and (harmonic balance) harmonics.csv tables, the
/// FRF curve of the outputs and the frequencies that failed.
struct Pass {
    csv: Option<CsvTable>,
    harmonics: Option<CsvTable>,
    /// Harmonic balance: per converged frequency (ascending) every element's loop.
    loops: Vec<(f64, Vec<Vec<LoopSample>>)>,
    curve: FrfCurve,
    failed: Vec<f64>,
}

/// Runs the sweep and writes results.csv (frequency, per output amplitude and phase,
/// per element its relative amplitude, status; with `[sweep] direction = "up_down"` also
/// results_down.csv; the rows ascending in frequency whichever way the pass ran), for
/// the harmonic balance harmonics.csv (every harmonic of every output), with `plots`
/// frf.svg (the outputs' amplitudes), and run.json (last, the marker of a complete run)
/// into `out`. A file that cannot be written ends the run with its message.
pub fn run(job: &Job, l: &Lumped, out: &Path, plots: bool) -> Result<LumpedRun, String> {
    let units = &job.settings.units;
    let it = &job.settings.iteration;
    let harmonic = (it.mode == Mode::HarmonicBalance).then(|| {
        let h = it.harmonics.unwrap_or(1);
        (h, it.samples.unwrap_or_else(|| default_samples(h)))
    });
    let mut up = job.settings.frequencies();
    up.sort_by(f64::total_cmp);
    let down: Vec<f64> = up.iter().rev().copied().collect();
    // (file suffix, curve label, frequencies in solve order) per pass.
    let passes: Vec<(&str, &str, &[f64])> = match job.settings.sweep.direction {
        Direction::Up => vec![("", "", &up)],
        Direction::Down => vec![("", "", &down)],
        Direction::UpDown => vec![("", "sweep up", &up), ("_down", "sweep down", &down)],
    };
    super::clear_earlier_run(out)?;
    let mut written = Vec::new();
    let mut curves = Vec::new();
    let mut failed = Vec::new();
    let started = std::time::Instant::now();
    for (suffix, label, order) in &passes {
        let mut pass = sweep_pass(l, units, harmonic, order, label);
        let scope = Written {
            s: job,
            l,
            out,
            harmonic,
            plots,
        };
        written.extend(scope.pass_files(suffix, &mut pass)?);
        curves.push(pass.curve);
        failed.extend(pass.failed);
    }
    let sweep_seconds = started.elapsed().as_secs_f64();
    let method = match harmonic {
        None => "first order (jointlin_linearize), lumped system".to_string(),
        Some((h, n)) if l.points.is_empty() => format!(
            "harmonic balance, H = {h}, {n} samples per period (jointlin_point_step by AFT), lumped system"
        ),
        Some((h, n)) => format!(
            "harmonic balance, H = {h}, {n} samples per period (jointlin_point_step and, for the three-direction points, jointlin_point3d_step by AFT), lumped system"
        ),
    };
    let has_points = curves.iter().any(|c| !c.points.is_empty());
    if plots && has_points && !l.outputs.is_empty() {
        let names: Vec<String> = l.outputs.iter().map(|(n, _)| n.clone()).collect();
        let p = out.join("frf.svg");
        let title = match harmonic {
            None => format!("{}: first order", job.title()),
            Some((h, _)) => format!("{}: harmonic balance, H = {h}", job.title()),
        };
        atomic::with_temp(&p, |t| frf_curves(t, &title, units, &names, &curves))?;
        written.push(p);
    }
    let solved = up.len() * passes.len();
    let head = provenance::head("run", &capi::abi_version(), job.sources());
    let record = Record {
        method: &method,
        frequencies: up.len(),
        failed: &failed,
        sweep_seconds,
    };
    let run = provenance::with_head(head, body(job, l, &record));
    let text = serde_json::to_string_pretty(&run).expect("json");
    written.push(atomic::write_marker(out, &text)?);
    Ok(LumpedRun {
        written,
        solved,
        failed: failed.len(),
    })
}

/// What a lumped run's record states besides the scene and the system.
struct Record<'a> {
    /// How each frequency was solved (first order or the harmonic balance).
    method: &'a str,
    /// Frequencies of one pass.
    frequencies: usize,
    /// Frequencies that failed (1/time).
    failed: &'a [f64],
    sweep_seconds: f64,
}

/// run.json's body of a lumped run: the FE run's names where they mean the same.
fn body(s: &Job, l: &Lumped, r: &Record) -> serde_json::Value {
    let units = &s.settings.units;
    json!({
        "scene": {"file": s.file(), "spec": s.spec_json(), "text": s.text()},
        "units": units,
        "effects": s.settings.effects,
        "model": {
            "dofs": l.dofs.len(),
            "elements": l.elements.len(),
            "joints": l.joints.len(),
        },
        "mode": s.settings.iteration.mode,
        "frequency_unit": frequency_unit(units).text,
        "method": r.method,
        "dofs": l.dofs,
        "joints": l.joints.iter().map(|j| json!({
            "name": j.name,
            "static_normal_force": j.static_normal,
            "normal_force_varies": j.normal_varies,
            "three_direction_point": j.point.is_some(),
        })).collect::<Vec<_>>(),
        "frequencies": r.frequencies,
        "sweep_direction": s.settings.sweep.direction,
        "failed_frequencies": r.failed.iter().map(|&f| frequency_unit(units).show(f)).collect::<Vec<f64>>(),
        "all_converged": r.failed.is_empty(),
        "timings_s": {"sweep": r.sweep_seconds},
    })
}

/// One pass over `order` (each frequency continued from the last), its tables' rows
/// sorted ascending in frequency.
fn sweep_pass(
    l: &Lumped,
    units: &Units,
    harmonic: Option<(usize, usize)>,
    order: &[f64],
    label: &str,
) -> Pass {
    let len = ColumnUnits::new(units).length;
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    for (name, _) in &l.outputs {
        header.push(format!("{name}_amp_{len}"));
        header.push(format!("{name}_phase_deg"));
    }
    for name in &l.elements {
        header.push(format!("{name}_amplitude_{len}"));
    }
    header.extend(joint_columns(l, units));
    header.push("status".into());
    let mut hheader = vec![fu.column.clone()];
    if let Some((h, _)) = harmonic {
        for (name, _) in &l.outputs {
            hheader.extend(harmonic_columns(name, h, &len));
        }
    }
    let sys3 = l.system3();
    let mut sweep = Sweep::new(l, &sys3, harmonic);
    let mut loops = Vec::new();
    // (frequency, results row, harmonics row, output amplitudes if converged)
    let mut rows = Vec::with_capacity(order.len());
    let mut failed = Vec::new();
    for &f in order {
        let omega = 2.0 * std::f64::consts::PI * f;
        let mut row = vec![exact(fu.show(f))];
        let mut hrow = row.clone();
        let mut amps = None;
        match sweep.solve(omega) {
            Ok(solved) => {
                if let (Some((h, n)), Some(u)) = (harmonic, &solved.coefficients) {
                    match balance_loops(&sys3, u, h, n) {
                        Ok(x) => loops.push((f, x)),
                        Err(e) => eprintln!("warning: {f:e}: the loops: {e}"),
                    }
                    let m = 2 * h + 1;
                    for (_, w) in &l.outputs {
                        let c = |k: usize| -> f64 {
                            w.iter().enumerate().map(|(d, w)| w * u[d * m + k]).sum()
                        };
                        // a cos + b sin = Re((a − i b) e^{iωt}), as x̂ of results.csv.
                        let u: Vec<Complex<f64>> = (0..=h)
                            .map(|k| match k {
                                0 => Complex::new(c(0), 0.0),
                                _ => Complex::new(c(2 * k - 1), -c(2 * k)),
                            })
                            .collect();
                        hrow.extend(harmonic_values(&u).iter().map(|v| exact(*v)));
                    }
                }
                let mut a = Vec::new();
                for (_, w) in &l.outputs {
                    let v: Complex<f64> = w.iter().zip(&solved.x).map(|(w, x)| x * *w).sum();
                    row.push(exact(v.norm()));
                    row.push(exact(v.arg().to_degrees()));
                    a.push(v.norm());
                }
                amps = Some(a);
                row.extend(solved.elements.iter().map(|a| exact(*a)));
                row.extend(joint_values(l, &solved).iter().map(|v| exact(*v)));
                row.push("converged".into());
            }
            Err(e) => {
                eprintln!("warning: {f:e}: {e}");
                failed.push(f);
                row.resize(header.len() - 1, String::new());
                row.push("failed".into());
            }
        }
        // A failed frequency: empty fields, as in results.csv.
        hrow.resize(hheader.len(), String::new());
        rows.push((f, row, hrow, amps));
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut csv = CsvTable::new(&header);
    let mut harmonics = harmonic.map(|_| CsvTable::new(&hheader));
    // Only converged frequencies carry amplitudes (a failed one leaves its fields empty).
    let mut curve = FrfCurve {
        label: label.to_string(),
        grid: rows.iter().map(|r| r.0).collect(),
        points: Vec::new(),
        not_converged: Vec::new(),
    };
    for (f, row, hrow, amps) in rows {
        csv.row(&row);
        if let Some(t) = &mut harmonics {
            t.row(&hrow);
        }
        if let Some(a) = amps {
            curve.points.push((f, a));
        }
    }
    loops.sort_by(|a, b| a.0.total_cmp(&b.0));
    Pass {
        csv: Some(csv),
        harmonics,
        loops,
        curve,
        failed,
    }
}

/// Per joint: the tangential amplitudes of a three-direction point, the energy
/// dissipated per cycle and, where the normal force varies, its range.
fn joint_columns(l: &Lumped, units: &Units) -> Vec<String> {
    let cu = ColumnUnits::new(units);
    let mut h = Vec::new();
    for j in &l.joints {
        let name = &j.name;
        if j.point.is_some() {
            h.push(format!("{name}_t1_amplitude_{}", cu.length));
            h.push(format!("{name}_t2_amplitude_{}", cu.length));
        }
        h.push(format!("{name}_energy_{}", cu.energy));
        if j.normal_varies {
            h.push(format!("{name}_normal_force_min_{}", units.force));
            h.push(format!("{name}_normal_force_max_{}", units.force));
        }
    }
    h
}

/// The values of [`joint_columns`] at one solution.
fn joint_values(l: &Lumped, s: &Solved) -> Vec<f64> {
    let mut v = Vec::new();
    for j in &l.joints {
        let point = j.point.map(|p| s.points[p]);
        if let Some(p) = point {
            v.extend(p.amplitude);
        }
        let elements: f64 = j.elements.iter().map(|&e| s.element_energy[e]).sum();
        v.push(elements + point.map_or(0.0, |p| p.energy));
        if let (true, Some(p)) = (j.normal_varies, point) {
            v.extend([p.normal_range.0, p.normal_range.1]);
        }
    }
    v
}

/// The loops of the frequency with the largest first output amplitude on `curve`.
fn peak<'p>(
    loops: &'p [(f64, Vec<Vec<LoopSample>>)],
    curve: &FrfCurve,
) -> Option<(f64, &'p [Vec<LoopSample>])> {
    let amplitude = |f: f64| {
        curve
            .points
            .iter()
            .find(|p| p.0 == f)
            .and_then(|p| p.1.first().copied())
            .unwrap_or(0.0)
    };
    loops
        .iter()
        .max_by(|a, b| amplitude(a.0).total_cmp(&amplitude(b.0)))
        .map(|(f, x)| (*f, x.as_slice()))
}

/// Where a run's pass files go and what they describe.
struct Written<'a> {
    s: &'a Job,
    l: &'a Lumped,
    out: &'a Path,
    harmonic: Option<(usize, usize)>,
    plots: bool,
}

impl Written<'_> {
    /// Writes results{suffix}.csv, with the balance harmonics{suffix}.csv and
    /// loops{suffix}.csv, and (first pass, plots) loops.svg; the files written.
    fn pass_files(&self, suffix: &str, pass: &mut Pass) -> Result<Vec<PathBuf>, String> {
        let (l, units) = (self.l, &self.s.settings.units);
        let mut files = Vec::new();
        if let Some(t) = pass.csv.take() {
            files.push((format!("results{suffix}.csv"), t.finish()));
        }
        if let Some(t) = pass.harmonics.take() {
            files.push((format!("harmonics{suffix}.csv"), t.finish()));
        }
        let mut written = Vec::new();
        if !pass.loops.is_empty() && !l.joints.is_empty() {
            let loops: Vec<(f64, &[Vec<LoopSample>])> =
                pass.loops.iter().map(|(f, x)| (*f, x.as_slice())).collect();
            files.push((format!("loops{suffix}.csv"), loops_csv(l, &loops, units)));
            if let (true, true, Some(peak)) = (
                self.plots,
                suffix.is_empty(),
                peak(&pass.loops, &pass.curve),
            ) {
                let file = self.out.join("loops.svg");
                let h = self.harmonic.map_or(1, |h| h.0);
                let what = format!("harmonic balance, H = {h}");
                written.extend(plot_joint_loops(self.s, l, peak, &file, &what)?);
            }
        }
        for (name, text) in files {
            let p = self.out.join(name);
            atomic::write_text(&p, &text)?;
            written.push(p);
        }
        Ok(written)
    }
}

/// Draws every joint's loop of `samples` (per sample, per element) at `freq` into `file`
/// (nothing without joints); `what` names the method in the title.
pub fn plot_joint_loops(
    job: &Job,
    l: &Lumped,
    (freq, samples): (f64, &[Vec<LoopSample>]),
    file: &Path,
    what: &str,
) -> Result<Option<PathBuf>, String> {
    if l.joints.is_empty() || samples.is_empty() {
        return Ok(None);
    }
    let loops: Vec<JointLoop> = (0..l.joints.len())
        .map(|j| {
            let at: Vec<_> = samples.iter().map(|x| joint_sample(l, j, x)).collect();
            JointLoop {
                name: l.joints[j].name.clone(),
                t1: at.iter().map(|s| (s.displacement[0], s.force[0])).collect(),
                t2: at.iter().map(|s| (s.displacement[1], s.force[1])).collect(),
            }
        })
        .collect();
    let units = &job.settings.units;
    let fu = frequency_unit(units);
    let title = format!(
        "{}: {what}, one period at {:.4} {}",
        job.title(),
        fu.show(freq),
        fu.text
    );
    if let Some(dir) = file.parent() {
        std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    }
    atomic::with_temp(file, |t| loop_plot::draw(t, &title, units, &loops))?;
    Ok(Some(file.to_path_buf()))
}
