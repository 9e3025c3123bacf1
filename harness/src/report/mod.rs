//! Reports of a run: CSV tables, run.json and SVG plots. Reports read results only.

pub mod contact_map;
pub mod csv;
pub mod field;
pub mod frf_plot;
pub mod kinematics;
pub mod legend;
pub mod loop_plot;
pub mod lumped_run;
pub mod modes;
pub mod point_loops;
pub mod style;
pub mod svg;
pub mod vtu;

use std::path::{Path, PathBuf};

use serde_json::json;

use crate::model::Job;
use crate::run::RunResult;
use crate::settings::units::frequency_unit;
use crate::util::{atomic, provenance};

/// Which plots to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReportOptions {
    pub plots: bool,
}

fn write(dir: &Path, name: &str, text: &str, out: &mut Vec<PathBuf>) -> Result<(), String> {
    let p = dir.join(name);
    atomic::write_text(&p, text)?;
    out.push(p);
    Ok(())
}

/// run.json: the provenance head ([`provenance::head`]), scene echo, effects (with
/// costs), passes, timings, calls, static step.
pub fn run_json(job: &Job, r: &RunResult) -> serde_json::Value {
    let head = provenance::head("run", &crate::capi::abi_version(), job.sources());
    provenance::with_head(head, run_body(job, r))
}

fn run_body(job: &Job, r: &RunResult) -> serde_json::Value {
    let m = &r.main;
    // Every frequency as the outputs show it ([units] frequency: cycles or angular).
    let fu = frequency_unit(&job.settings.units);
    let shown = |f: f64| fu.show(f);
    let closed = r.stat.closed.iter().filter(|&&c| c).count();
    json!({
        "scene": {
            "file": job.file(),
            "spec": job.spec_json(),
            "text": job.text(),
        },
        "units": job.settings.units,
        "effects": r.effects,
        "model": {
            "nodes": r.problem.model.nodes.len(),
            "elements": r.problem.model.elements.len(),
            "free_dofs": r.problem.sys.dofs.n_free(),
            "contact_points": r.problem.contacts.len(),
            "closed_points": closed,
        },
        "static_step": {
            "newton_iterations": r.stat.newton_iterations,
            "relative_residual": r.stat.residual,
            "backward_error": r.stat.backward_error,
            "stopped_by": r.stat.stopped_by,
            "total_contact_force": r.problem.contacts.iter().zip(&r.stat.pressure).map(|(c, p)| c.area * p).sum::<f64>(),
        },
        "mode": job.settings.iteration.mode,
        // The unit of every frequency below (frequencies, checks, field output).
        "frequency_unit": fu.text,
        "passes": m.passes,
        "iterations_per_frequency": m.iterations,
        "converged": m.converged,
        "all_converged": m.converged.iter().all(|&c| c),
        "singular_frequencies": m.freqs.iter().enumerate().filter(|(i, _)| m.is_singular(*i)).map(|(_, f)| shown(*f)).collect::<Vec<f64>>(),
        "failed_frequencies": m.freqs.iter().enumerate().filter_map(|(i, f)| m.failure(i).map(|e| json!({"frequency": shown(*f), "error": e}))).collect::<Vec<_>>(),
        "a_posteriori_checks": checks_at(&m.freqs.iter().map(|&f| shown(f)).collect::<Vec<_>>(), &m.checks),
        "singular_rcond_threshold": crate::solve::sweep::SINGULAR_RCOND,
        "singular_rcond_estimate_threshold": crate::solve::sweep::SINGULAR_RCOND_ESTIMATE,
        "factorizations": m.factorizations,
        // The modal route's basis (null for the direct route); its a-posteriori checks'
        // relative_residual is then the truncation error in the full equations.
        "modal_route": m.modal,
        "gmres_solves": m.gmres_solves,
        "macroslip_caps": m.macroslip_caps,
        "sweep_direction": job.settings.sweep.direction,
        // [field_output]: each asked frequency, its file, or why there is none.
        "field_output": r.fields.as_ref().map(|f| f.freqs.iter().enumerate().map(|(i, &fr)| {
            let kept = f.fields.iter().any(|(k, _)| *k == fr);
            json!({
                "frequency": shown(fr),
                "file": kept.then(|| field::file_name(fr, &job.settings.units)),
                "converged": f.converged.get(i).copied().unwrap_or(false),
            })
        }).collect::<Vec<_>>()),
        "down_sweep": r.down.as_ref().map(|d| json!({
            "passes": d.passes,
            "iterations_per_frequency": d.iterations,
            "converged": d.converged,
            "all_converged": d.converged.iter().all(|&c| c),
            "factorizations": d.factorizations,
        })),
        "timings_s": {
            "build": r.seconds[0],
            "static_step": r.seconds[1],
            "sweep": r.seconds[2],
            "reference_sweep_without_contact_damping": r.seconds[3],
            "sweep_breakdown": m.timings,
        },
        "c_api_calls": r.calls,
        "notes": kinematics::note(&job.settings.units, r).into_iter().collect::<Vec<_>>(),
    })
}

/// The a-posteriori check of each frequency, the frequency first (null where a
/// frequency has none: failed, singular, or a mode without the check).
fn checks_at<T: serde::Serialize>(freqs: &[f64], checks: &[Option<T>]) -> Vec<serde_json::Value> {
    freqs
        .iter()
        .zip(checks)
        .map(|(f, c)| {
            let mut entry = serde_json::Map::new();
            entry.insert("frequency".into(), json!(f));
            match serde_json::to_value(c) {
                Ok(serde_json::Value::Object(fields)) => entry.extend(fields),
                _ => {
                    entry.insert("check".into(), serde_json::Value::Null);
                }
            }
            serde_json::Value::Object(entry)
        })
        .collect()
}

/// The files `jointlin run` writes with fixed names; besides them it writes
/// `field_<f>_<unit>.vtu` and the contact maps `contact_ratio_…`/`contact_energy_…svg`
/// ([`field`]), named by their frequencies.
const RUN_FILES: &[&str] = &[
    "results.csv",
    "results_down.csv",
    "harmonics.csv",
    "results_without_contact_damping.csv",
    "points.csv",
    "stick_slip.csv",
    "frf.svg",
    "passes.svg",
    "stick_slip.svg",
    "fields.pvd",
];

/// Removes from `dir` the outputs an earlier `jointlin run` may have left there (its
/// fixed-name files and its fields and contact maps, whose names carry frequencies this
/// run may not have), so that after a run the directory holds this run's outputs only.
/// Other files are left alone.
pub fn clear_earlier_run(dir: &Path) -> Result<(), String> {
    let err = |e: std::io::Error| format!("{}: {e}", dir.display());
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for entry in entries {
        let entry = entry.map_err(err)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let per_frequency = (name.starts_with("field_") && name.ends_with(".vtu"))
            || ((name.starts_with("contact_ratio_") || name.starts_with("contact_energy_"))
                && name.ends_with(".svg"));
        if per_frequency || RUN_FILES.contains(&name.as_str()) {
            std::fs::remove_file(entry.path()).map_err(err)?;
        }
    }
    Ok(())
}

/// Writes every report of the run `r` of `job` (a scene, a deck or a [`Job`]) into `dir`
/// (created if missing); returns the files written. Each
/// file appears under its name only when complete ([`atomic`]); run.json, last, marks
/// the set complete, and an earlier run's is removed first, with the earlier run's
/// other outputs ([`clear_earlier_run`]).
pub fn write_all(
    dir: &Path,
    job: impl Into<Job>,
    r: &RunResult,
    opts: ReportOptions,
) -> Result<Vec<PathBuf>, String> {
    let job: &Job = &job.into();
    let mut out = Vec::new();
    atomic::prepare(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    clear_earlier_run(dir)?;
    let eff = job.settings.effects;
    let units = &job.settings.units;
    write(
        dir,
        "results.csv",
        &csv::results(&r.problem, &r.main, units),
        &mut out,
    )?;
    if let Some(down) = &r.down {
        let text = csv::results(&r.problem, down, units);
        write(dir, "results_down.csv", &text, &mut out)?;
    }
    if !r.main.harmonics.is_empty() {
        let text = csv::harmonics(&r.problem, &r.main, units);
        write(dir, "harmonics.csv", &text, &mut out)?;
    }
    if let Some(reference) = &r.reference {
        let text = csv::results(&r.problem, reference, units);
        write(dir, "results_without_contact_damping.csv", &text, &mut out)?;
    }
    if eff.point_energy_output {
        let text = csv::points(
            &r.problem,
            &r.main,
            &r.stat.closed,
            &r.stat.pressure,
            eff.stick_slip_map,
            units,
            &job.node_ids(&r.problem),
        );
        write(dir, "points.csv", &text, &mut out)?;
    }
    if eff.stick_slip_map {
        write(
            dir,
            "stick_slip.csv",
            &csv::stick_slip(&r.main, &r.stat.closed, units),
            &mut out,
        )?;
    }
    if let Some(fields) = &r.fields {
        let node_ids = job.node_ids(&r.problem);
        let ctx = field::FieldContext {
            closed: &r.stat.closed,
            pressure: &r.stat.pressure,
            node_ids: &node_ids,
        };
        for (name, text) in field::files(&r.problem, fields, &ctx, units) {
            write(dir, &name, &text, &mut out)?;
        }
    }
    out.extend(point_loops::balance_files(dir, job, r, opts.plots)?);
    if opts.plots {
        let title = job.title();
        let main_label = match (&r.down, &r.reference) {
            (Some(_), _) => "sweep up",
            (None, Some(_)) => "with contact damping",
            (None, None) => "",
        };
        let mut curves = vec![(&r.main, main_label)];
        curves.extend(r.down.as_ref().map(|d| (d, "sweep down")));
        curves.extend(r.reference.as_ref().map(|d| (d, "without contact damping")));
        let p = dir.join("frf.svg");
        atomic::with_temp(&p, |t| {
            frf_plot::frf(t, title, &job.settings.units, &r.problem, &curves)
        })?;
        out.push(p);
        // Frequencies per pass: a picture only where there are passes (thesis mode's
        // Fig. 4.33); a one-pass sweep would draw a single bar.
        if r.main.passes.len() > 1 {
            let p = dir.join("passes.svg");
            atomic::with_temp(&p, |t| svg::passes(t, &r.main))?;
            out.push(p);
        }
        if let Some(fields) = &r.fields {
            for p in field::contact_maps(dir, job, r, fields)? {
                out.push(p);
            }
        }
        if eff.stick_slip_map {
            let p = dir.join("stick_slip.svg");
            atomic::with_temp(&p, |t| {
                svg::stick_slip(t, &job.settings.units, &r.problem, &r.main, &r.stat.closed)
            })?;
            out.push(p);
        }
    }
    // Last: the marker of a complete run.
    let json = serde_json::to_string_pretty(&run_json(job, r)).map_err(|e| e.to_string())?;
    out.push(atomic::write_marker(dir, &json)?);
    Ok(out)
}
