//! `jointlin loss SCENE --out DIR`: joint power loss against amplitude at resonance, per
//! screw torque; `--calibrate` and `--mesh-study` instead.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use jointlin_harness::input::scene::Scene;
use jointlin_harness::loss::{self, effects as loss_effects, mesh, LossError};
use jointlin_harness::model::Job;
use jointlin_harness::settings::{CalibratedParameter, LossStudySpec};
use jointlin_harness::util::atomic;

use super::{begin_outputs, load_scene_with, study_written, with_progress, SceneOverrides};

// The command's help is the doc comment of `Command::Loss`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML) with a [loss_study] table (scenes/knife.toml).
    scene: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Output directory (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Instead: fit the `[loss_study] calibration` (factors on every interface's
    /// k_t0_per_area and/or mu at as many reference points; default k_T0 at the first),
    /// print the fitted values and the model at every reference point (the others are
    /// predictions), and write nothing.
    #[arg(long)]
    calibrate: bool,
    /// Instead: a mesh study at the first reference point's torque (its amplitude
    /// and a quarter of it) with every box's divisions × each factor, area-sampled
    /// and node-based; writes mesh_study.md and mesh_study.csv.
    #[arg(long, value_delimiter = ',', num_args = 1..)]
    mesh_study: Vec<usize>,
    /// With --mesh-study: multiply only these divisions, AXES[:PREFIX,…] (e.g. `z`,
    /// `x:jaw_,blade_in`: x of the boxes whose names start so); repeat for several,
    /// each compared with the scene itself. Default: every axis of every box.
    #[arg(long)]
    refine: Vec<String>,
    /// Instead: at the first reference point's torque and these amplitudes (the study's
    /// amplitude unit), the resonance and loss with each point model of the contact (the
    /// thesis's, coupled slip, normal load variation, both; a harmonic-balance scene);
    /// writes effects.md and effects.csv.
    #[arg(long, value_delimiter = ',', num_args = 1..)]
    effects: Vec<f64>,
    /// With --mesh-study: only the area-sampled law (half the time; the node-based
    /// columns are left out).
    #[arg(long)]
    sampled_only: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

pub fn main(a: Args) -> ExitCode {
    let s = match load_scene_with(&a.scene, &a.overrides.set) {
        Ok(s) => s,
        Err(code) => return code,
    };
    let Some(st) = s.spec.loss_study.clone() else {
        eprintln!("error: {}: no [loss_study] table", s.file);
        return ExitCode::from(2);
    };
    if a.calibrate {
        return match calibrate(&s, &st) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(1)
            }
        };
    }
    if !a.effects.is_empty() {
        return effects(&s, &st, &a.out, &a.effects, a.quiet);
    }
    if !a.mesh_study.is_empty() {
        return mesh_study(
            &s,
            &a.out,
            &a.mesh_study,
            &a.refine,
            !a.sampled_only,
            a.quiet,
        );
    }
    if let Err(code) = begin_outputs(&a.out) {
        return code;
    }
    let t = std::time::Instant::now();
    let r = match with_progress(a.quiet, st.torques.len(), |p| loss::run_study(&s, p)) {
        Ok(r) => r,
        Err(code) => return code,
    };
    let job = Job::from(&s);
    print!("{}", loss::report::markdown(&job, &st, &r));
    eprintln!("{:.1} s", t.elapsed().as_secs_f64());
    study_written("loss", &s, &a.out, t, loss::report::write(&a.out, &job, &r))
}

/// `jointlin loss --mesh-study`.
fn mesh_study(
    s: &Scene,
    out: &Path,
    factors: &[usize],
    refine: &[String],
    node_based: bool,
    quiet: bool,
) -> ExitCode {
    if factors.contains(&0) {
        eprintln!("error: --mesh-study factors must be >= 1");
        return ExitCode::from(2);
    }
    let refinements = if refine.is_empty() {
        vec![mesh::Refinement::everything()]
    } else {
        match refine.iter().map(|r| mesh::Refinement::parse(r)).collect() {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: --refine {e}");
                return ExitCode::from(2);
            }
        }
    };
    if let Err(code) = begin_outputs(out) {
        return code;
    }
    let t = std::time::Instant::now();
    let steps = mesh::laws(node_based).len() * mesh::plan(factors, refinements.len()).len();
    let rows = match with_progress(quiet, steps, |p| {
        mesh::study(s, factors, &refinements, node_based, p)
    }) {
        Ok(r) => r,
        Err(code) => return code,
    };
    let md = mesh::markdown(&Job::from(s), &rows);
    print!("{md}");
    eprintln!("{:.1} s", t.elapsed().as_secs_f64());
    write_table(
        "loss --mesh-study",
        s,
        out,
        t,
        "mesh_study",
        &md,
        &mesh::csv(&rows),
    )
}

/// Writes NAME.md and NAME.csv into `out` (created if missing), each atomically, then
/// run.json for `command` ([`study_written`]).
fn write_table(
    command: &str,
    s: &Scene,
    out: &Path,
    started: std::time::Instant,
    name: &str,
    md: &str,
    csv: &str,
) -> ExitCode {
    let write = || -> Result<Vec<PathBuf>, String> {
        let io = |e: std::io::Error| format!("{}: {e}", out.display());
        std::fs::create_dir_all(out).map_err(io)?;
        let (a, b) = (
            out.join(format!("{name}.md")),
            out.join(format!("{name}.csv")),
        );
        atomic::write_text(&a, md)?;
        atomic::write_text(&b, csv)?;
        Ok(vec![a, b])
    };
    study_written(command, s, out, started, write())
}

/// `jointlin loss --effects`.
fn effects(s: &Scene, st: &LossStudySpec, out: &Path, amplitudes: &[f64], quiet: bool) -> ExitCode {
    if amplitudes.iter().any(|a| !(a.is_finite() && *a > 0.0)) {
        eprintln!(
            "error: --effects amplitudes must be finite and > 0 [{}]",
            st.amplitude_unit
        );
        return ExitCode::from(2);
    }
    let lengths: Vec<f64> = amplitudes.iter().map(|a| a * st.amplitude_factor).collect();
    if let Err(code) = begin_outputs(out) {
        return code;
    }
    let t = std::time::Instant::now();
    let rows = match with_progress(
        quiet,
        loss_effects::variant_count(s.spec.iteration.mode),
        |p| loss_effects::study(s, &lengths, p),
    ) {
        Ok(r) => r,
        Err(code) => return code,
    };
    let md = loss_effects::markdown(&Job::from(s), &rows);
    print!("{md}");
    eprintln!("{:.1} s", t.elapsed().as_secs_f64());
    write_table(
        "loss --effects",
        s,
        out,
        t,
        "effects",
        &md,
        &loss_effects::csv(&Job::from(s), &rows),
    )
}

/// `--calibrate`: fits the study's calibration, prints the fitted values per interface,
/// the calibration points and the predictions at the other reference points.
fn calibrate(s: &Scene, st: &LossStudySpec) -> Result<(), LossError> {
    let cal = loss::calibrate::calibrate(s, &|l| eprintln!("{l}"))?;
    let fitted = loss::calibrate::scaled(s, &cal.factors);
    for i in &s.spec.interfaces {
        let values: Vec<String> = cal
            .factors
            .iter()
            .map(|&(p, factor)| {
                let was = match p {
                    CalibratedParameter::KT0 => i.k_t0_per_area,
                    CalibratedParameter::Mu => i.mu,
                };
                let is = was * factor;
                format!("{} = {is:.6e} (× {factor:.5} of {was:.6e})", p.key())
            })
            .collect();
        println!("{}: {}", i.name, values.join(", "));
    }
    let used: Vec<usize> = st
        .calibration
        .as_ref()
        .map_or(vec![0], |c| c.points.clone());
    let (au, pu) = (&st.amplitude_unit, &st.power_unit);
    for (k, r) in st.reference.iter().enumerate() {
        let power = match used.iter().position(|&u| u == k) {
            Some(j) => cal.powers[j],
            None => loss::power_at(&fitted, r.torque, r.amplitude)?.0.power * st.power_factor,
        };
        let dev = 100.0 * (power / r.power - 1.0);
        let role = if used.contains(&k) {
            "calibrated".to_string()
        } else {
            match r.source_deviation_percent {
                Some(sd) => format!("predicted; the source's own deviation {sd} %"),
                None => "predicted".to_string(),
            }
        };
        println!(
            "torque {} [{}], {:.1} {au}: reference {:.4} {pu}, model {power:.4} {pu} ({dev:+.1} %), {role}",
            r.torque,
            loss::report::torque_unit(&Job::from(s)),
            r.amplitude / st.amplitude_factor,
            r.power
        );
    }
    Ok(())
}
