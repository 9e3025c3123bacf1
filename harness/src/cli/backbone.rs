//! `jointlin backbone`: frequency and damping ratio of one mode of a lumped scene, or of
//! an FE scene reduced onto its contact points (`backbone::fe`), against its amplitude,
//! first order or EPMC; backbone.csv, backbone.svg, run.json.

use std::cell::Cell;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use serde_json::json;

use jointlin_harness::backbone::report::{self, Row};
use jointlin_harness::backbone::{
    epmc, fe, first_order, log_space, BackboneError, BackbonePoint, C64,
};
use jointlin_harness::capi;
use jointlin_harness::input::scene::{Reading, Scene};
use jointlin_harness::mhb::{default_samples, System};
use jointlin_harness::model::lumped::{self, Lumped};
use jointlin_harness::model::{self, Kind};
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::util::progress::progress_bar;
use jointlin_harness::util::{atomic, provenance};

use super::{load_scene_for, print_findings, report_written, SceneOverrides};

// The command's help is the doc comment of `Command::Backbone`.
#[derive(clap::Args)]
pub struct Args {
    /// Lumped scene (mass bodies, springs, [[joints]], [[matrices]]) or FE scene (box
    /// bodies with [[interfaces]], or a deck); [sweep], [[excitation]] and [[outputs]]
    /// may be left out (outputs given become amplitude columns).
    scene: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Mode number (1 = lowest frequency with every contact stuck).
    #[arg(long, default_value_t = 1)]
    mode: usize,
    /// Output directory.
    #[arg(long)]
    out: PathBuf,
    /// Harmonics of the EPMC; without it, the first-order backbone.
    #[arg(long)]
    harmonics: Option<usize>,
    /// Modal amplitudes FROM,TO,COUNT (log spaced); default from a tenth of the first
    /// contact's slip onset to 30 times the last one's, 60 points.
    #[arg(long, value_delimiter = ',')]
    amplitudes: Vec<f64>,
    /// No progress (the EPMC's modal amplitude reached, on stderr).
    #[arg(long)]
    quiet: bool,
}

/// What a backbone traces: the lumped system (its own, or an FE scene's reduction with
/// how it was reduced) and, with three-direction points, the same scene as the thesis's
/// model (each point two 1D directions at its static normal force), which gives the stuck
/// mode and slip limits the EPMC starts from.
struct Built {
    lumped: Lumped,
    linearized: Option<Lumped>,
    reduction: Option<fe::Reduced>,
}

impl Built {
    /// The system of the stuck modes and slip limits (one-direction elements only).
    fn stuck(&self) -> &Lumped {
        self.linearized.as_ref().unwrap_or(&self.lumped)
    }

    /// Names per element of the EPMC's energies: the 1D elements, then each point's joint.
    fn element_names(&self) -> Vec<String> {
        let l = &self.lumped;
        let mut names = l.elements.clone();
        names.extend(point_names(l));
        names
    }
}

/// The joint of each three-direction point, in the points' order.
fn point_names(l: &Lumped) -> Vec<String> {
    (0..l.points.len())
        .map(|k| {
            l.joints
                .iter()
                .find(|j| j.point == Some(k))
                .map_or(format!("point{}", k + 1), |j| j.name.clone())
        })
        .collect()
}

fn build(scene: &Scene, mode: usize, epmc: bool) -> Result<Built, String> {
    let s = &scene.spec;
    // A lumped scene, and a masses-only one, is read as the lumped system (no
    // reduction needed); an FE scene or deck is reduced onto its contact directions.
    if model::kind(scene) != Kind::Fe {
        let lumped = lumped::build(scene)?;
        if lumped.points.is_empty() {
            return Ok(Built {
                lumped,
                linearized: None,
                reduction: None,
            });
        }
        if !epmc {
            return Err("the first-order backbone linearizes one-direction joints: joints with `normal` and [effects] normal_load_variation or coupled_slip need the EPMC (--harmonics H), or both effects off (the thesis's model)".into());
        }
        let linearized = Some(lumped::build(&scene.thesis_points()).map_err(|e| {
            format!("the stuck mode is the scene's as the thesis's model (both effects off), which fails: {e}")
        })?);
        return Ok(Built {
            lumped,
            linearized,
            reduction: None,
        });
    }
    let p = model::build(scene).map_err(|e| e.to_string())?;
    print_findings(&p);
    let r = fe::reduce(&p, &s.effects, mode)?;
    Ok(Built {
        lumped: r.lumped.clone(),
        linearized: None,
        reduction: Some(r),
    })
}

pub fn main(a: Args) -> ExitCode {
    let scene = match load_scene_for(&a.scene, &a.overrides.set, Reading::Free) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut pb = progress_bar(a.quiet);
    pb.set_message("building the model (an FE model: static step, stuck modes, reduction)");
    let built = build(&scene, a.mode, a.harmonics.is_some());
    pb.finish_and_clear();
    let built = match built {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: {}: {e}", a.scene.display());
            return ExitCode::from(2);
        }
    };
    let l = &built.lumped;
    print_reduction(&built, &scene, a.mode);
    let q = match amplitudes(&a, &built) {
        Ok(q) => q,
        Err(code) => return code,
    };
    // No earlier run's marker survives this one; an interrupt says so.
    if let Err(e) = atomic::begin(&a.out) {
        eprintln!("error: {}: {e}", a.out.display());
        return ExitCode::from(1);
    }
    // Both traces keep the points converged before a failure: they are written, the
    // failure is printed and the exit code is 1.
    let started = Instant::now();
    let (method, result) = match a.harmonics {
        None => (
            "first order (jointlin_linearize)".to_string(),
            first_order_with_progress(&l.system, (a.mode, a.quiet), &q)
                .map(|t| (t.points, Path::default(), t.stopped)),
        ),
        Some(h) => (
            format!("EPMC, H = {h}"),
            epmc_with_progress(&built, (&scene, a.quiet), a.mode, h, &q).map(|t| {
                (
                    t.points
                        .into_iter()
                        .map(|p| p.point)
                        .collect::<Vec<BackbonePoint>>(),
                    Path {
                        turning: t.turning_points,
                        gaps: t.gaps,
                        skipped: t.skipped,
                        fixed_q: t.fixed_q,
                    },
                    t.stopped,
                )
            }),
        ),
    };
    let (points, path, stopped) = match result {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    eprintln!(
        "{method}: {} points at {} amplitudes in {:.2} s",
        points.len(),
        q.len(),
        started.elapsed().as_secs_f64()
    );
    print_path(&path, &scene);
    let rows: Vec<Row> = points
        .into_iter()
        .map(|p| {
            let outputs = l
                .outputs
                .iter()
                .map(|(_, w)| {
                    w.iter()
                        .zip(&p.shape)
                        .map(|(w, x)| x * *w)
                        .sum::<C64>()
                        .norm()
                })
                .collect();
            Row { point: p, outputs }
        })
        .collect();
    if rows.is_empty() {
        eprintln!(
            "error: {}",
            stopped.map_or("no amplitudes".into(), |e| e.to_string())
        );
        return ExitCode::from(1);
    }
    let code = report_written(write(&a, &scene, &built, &method, &rows, &path));
    match stopped {
        Some(e) => stopped_early(&e, rows.len()),
        None => code,
    }
}

/// The reduction's line of the log (FE scenes): its points, joints and modes, the mode's
/// stuck frequency against the full model's and its sliding one.
fn print_reduction(built: &Built, scene: &Scene, mode: usize) {
    if let Some(r) = &built.reduction {
        let unit = frequency_unit(&scene.spec.units);
        let fu = &unit.text;
        let last = |f: &[f64]| {
            f.last()
                .map_or("–".into(), |&f| format!("{:.9}", unit.show(f)))
        };
        eprintln!(
            "reduced: {} closed contact points ({} open, no joint), {} joints, {} interior modes; \
             mode {}: stuck {} {fu} (full model {} {fu}), sliding {} {fu}{}",
            r.closed,
            r.open,
            r.lumped.elements.len(),
            r.modes,
            mode,
            last(&r.stuck),
            last(&r.stuck_full),
            last(&r.sliding),
            if r.converged {
                String::new()
            } else {
                format!(
                    " (not converged to {:e} at {} modes)",
                    fe::MODE_TOL,
                    r.modes
                )
            }
        );
    }
}

/// The modal amplitudes to trace: `--amplitudes FROM,TO,COUNT` log-spaced, else 60 over
/// the mode's slip range; an unusable option is exit 2.
fn amplitudes(a: &Args, built: &Built) -> Result<Vec<f64>, ExitCode> {
    if !a.amplitudes.is_empty() && a.amplitudes.len() != 3 {
        eprintln!("error: --amplitudes FROM,TO,COUNT: three numbers");
        return Err(ExitCode::from(2));
    }
    Ok(if a.amplitudes.len() == 3 {
        let (f, t, n) = (a.amplitudes[0], a.amplitudes[1], a.amplitudes[2]);
        if !(f > 0.0 && t > 0.0 && f.is_finite() && t.is_finite() && (1.0..=1e6).contains(&n)) {
            eprintln!(
                "error: --amplitudes FROM,TO,COUNT: positive finite amplitudes, 1 ≤ COUNT ≤ 1e6"
            );
            return Err(ExitCode::from(2));
        }
        log_space(f, t, n as usize)
    } else {
        match first_order::slip_range(&built.stuck().system, a.mode) {
            Ok((f, t)) => log_space(f, t, 60),
            Err(e) => {
                eprintln!("error: {e}; give --amplitudes FROM,TO,COUNT");
                return Err(ExitCode::from(1));
            }
        }
    })
}

/// The path's notes: gaps jumped over, requested amplitudes not in the results, stretches
/// continued in q alone, turning points.
fn print_path(path: &Path, scene: &Scene) {
    let unit = format!("{}·{}^½", scene.spec.units.length, scene.spec.units.mass);
    for (from, to) in &path.gaps {
        eprintln!(
            "no solution to the tolerance for modal amplitudes between {from:.6e} and {to:.6e} [{unit}]: the path jumped over them"
        );
    }
    if !path.skipped.is_empty() {
        let list: Vec<String> = path.skipped.iter().map(|q| format!("{q:.6e}")).collect();
        eprintln!(
            "requested amplitudes in those ranges, not in the results: {} [{unit}]",
            list.join(", ")
        );
    }
    for (from, to) in &path.fixed_q {
        eprintln!(
            "the arclength path stopped: continued in the modal amplitude alone from {from:.6e} to {to:.6e} [{unit}] (turning points in that range not followed)"
        );
    }
    let turning = &path.turning;
    if let (Some(lo), Some(hi)) = (
        turning.iter().copied().reduce(f64::min),
        turning.iter().copied().reduce(f64::max),
    ) {
        eprintln!(
            "{} turning points of the modal amplitude between {lo:.6e} and {hi:.6e} [{unit}]: \
             amplitudes in that range appear once per passage (rows in path order)",
            turning.len(),
        );
    }
}

/// The EPMC trace with its progress on stderr (a bar on a terminal, timed lines in a
/// batch log): the farthest modal amplitude reached and how many requested ones lie
/// below it.
fn epmc_with_progress(
    b: &Built,
    (scene, quiet): (&Scene, bool),
    mode: usize,
    h: usize,
    q: &[f64],
) -> Result<epmc::Traced, BackboneError> {
    let units = &scene.spec.units;
    let unit = format!("{}·{}^½", units.length, units.mass);
    let progress = progress_bar(quiet);
    progress.set_length(q.len() as u64);
    let farthest = Cell::new(0.0f64);
    // The farthest amplitude to two digits: a batch log gets a line when it changes
    // (at most one a second), not one per continuation step.
    let on_point = |reached: f64| {
        farthest.set(farthest.get().max(reached));
        progress.set_position(q.iter().filter(|v| **v <= farthest.get()).count() as u64);
        progress.set_message(&format!(
            "EPMC, H = {h}: modal amplitude {:.1e} reached [{unit}]",
            farthest.get()
        ));
    };
    epmc::trace_points(
        &b.lumped.system3(),
        &b.stuck().system,
        mode,
        h,
        default_samples(h.max(1)),
        q,
        &on_point,
    )
}

/// [`first_order::trace`] with its amplitudes counted on the progress (stderr).
fn first_order_with_progress(
    sys: &System,
    (mode, quiet): (usize, bool),
    q: &[f64],
) -> Result<first_order::Traced, BackboneError> {
    let mut pb = progress_bar(quiet);
    pb.set_message("first-order backbone: modal amplitudes");
    pb.set_length(q.len() as u64);
    let t = first_order::trace_with(sys, mode, q, &|i| pb.set_position(i as u64));
    pb.finish_and_clear();
    t
}

/// A trace that stopped after `kept` amplitudes: the failure, exit code 1.
fn stopped_early(e: &BackboneError, kept: usize) -> ExitCode {
    let kept = match kept {
        1 => "the amplitude below it is written".to_string(),
        n => format!("the {n} amplitudes below it are written"),
    };
    eprintln!("error: {e}; {kept}");
    ExitCode::from(1)
}

fn write(
    a: &Args,
    scene: &Scene,
    built: &Built,
    method: &str,
    rows: &[Row],
    path: &Path,
) -> Result<Vec<PathBuf>, String> {
    let (l, reduction) = (&built.lumped, built.reduction.as_ref());
    let units = &scene.spec.units;
    let names: Vec<String> = l.outputs.iter().map(|o| o.0.clone()).collect();
    let elements = built.element_names();
    let points = point_names(l);
    let csv = a.out.join("backbone.csv");
    let text = report::csv(units, &names, (&elements, &points), rows);
    atomic::write_text(&csv, &text)?;
    let svg = a.out.join("backbone.svg");
    let x_label = match names.first() {
        Some(n) => format!("{n} amplitude [{}]", units.length),
        None => format!("modal amplitude [{}·{}^½]", units.length, units.mass),
    };
    let title = format!("{}: mode {}, {method}", scene.title(), a.mode);
    atomic::with_temp(&svg, |t| report::svg(t, &title, units, &x_label, rows))?;
    let json_rows: Vec<_> = rows
        .iter()
        .map(|r| {
            json!({
                "modal_amplitude": r.point.modal_amplitude,
                "omega": r.point.omega,
                "frequency": report::frequency(r.point.omega, units),
                "damping_ratio": r.point.damping_ratio,
                "outputs": names.iter().zip(&r.outputs).map(|(n, v)| json!({"name": n, "amplitude": v})).collect::<Vec<_>>(),
                "elements": elements.iter().zip(r.point.element_amplitudes.iter().zip(&r.point.energy_per_cycle)).map(|(n, (amp, e))| json!({"name": n, "amplitude": amp, "energy_per_cycle": e})).collect::<Vec<_>>(),
                "normal_force_range": points.iter().zip(&r.point.normal_range).map(|(n, (lo, hi))| json!({"name": n, "min": lo, "max": hi})).collect::<Vec<_>>(),
            })
        })
        .collect();
    let fu = frequency_unit(units);
    let head = provenance::head("backbone", &capi::abi_version(), &scene.sources);
    let run = provenance::with_head(
        head,
        json!({
            "scene": {"file": scene.file, "spec": scene.spec, "text": scene.text},
            "units": units,
            "mode": a.mode,
            "method": method,
            "dofs": l.dofs,
            "reduction": reduction.map(|r| {
                let show = |f: &[f64]| f.iter().map(|&f| fu.show(f)).collect::<Vec<_>>();
                json!({
                    "closed_points": r.closed,
                    "open_points": r.open,
                    "joints": r.lumped.elements.len(),
                    "interior_modes": r.modes,
                    "stuck_frequencies": show(&r.stuck),
                    "stuck_frequencies_full_model": show(&r.stuck_full),
                    "sliding_frequencies": show(&r.sliding),
                    "sliding_frequencies_half_modes": show(&r.sliding_previous),
                    "converged": r.converged,
                    "tolerance": fe::MODE_TOL,
                })
            }),
            "frequency_unit": fu.text,
            "turning_points_modal_amplitude": path.turning,
            "gaps_modal_amplitude": path.gaps,
            "skipped_modal_amplitudes": path.skipped,
            "fixed_amplitude_steps_modal_amplitude": path.fixed_q,
            "rows": json_rows,
        }),
    );
    let text = serde_json::to_string_pretty(&run).map_err(|e| e.to_string())?;
    let run_path = atomic::write_marker(&a.out, &text)?;
    Ok(vec![csv, svg, run_path])
}

/// What an EPMC path passed besides its points (all modal amplitudes).
#[derive(Default)]
struct Path {
    turning: Vec<f64>,
    gaps: Vec<(f64, f64)>,
    skipped: Vec<f64>,
    /// Ranges continued in the modal amplitude alone (from, to).
    fixed_q: Vec<(f64, f64)>,
}
