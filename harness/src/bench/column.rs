//! `jointlin bench --modal-box`: the first-order sweep of a large box model by the modal
//! route, with the direct route at every k-th of its frequencies for time and difference.
//!
//! The model is a steel column of two boxes 10 × 10 mm, stacked along z with one joint
//! between them (Mindlin tangential law, μ = 0.2, k_T0 = 2e4 N/mm³ per area, linear
//! normal law 1e6 N/mm³, 1 N/mm² pressing the upper box down), clamped at the foot and
//! driven at the head by 0.05 N along x: the joint sees the shear of the first bending
//! modes. Cubic elements of 0.625 mm (16 × 16 per section), as many layers as the DOF
//! count asks, so the joint keeps 289 contact points at any size: a bolted joint's
//! contact patch is a small part of a large model's surface, and the modal route's
//! per-frequency cost is that of the contact directions (docs/model.md §10). The sweep
//! covers ±10 % around the first stuck bending frequency.

use std::io::Write;
use std::time::Instant;

use crate::model::Job;
use crate::run::linear_route;
use crate::settings::SweepMethod;
use crate::solve::static_step;
use crate::solve::sweep::{self, Options, SweepResult};
use crate::util::rusage::peak_rss_bytes;

use super::{mindlin_interface, steel_head, stuck_modes};

/// Elements across the 10 mm section (each way).
const SECTION_DIVISIONS: usize = 16;
/// Element edge (mm).
const EDGE_MM: f64 = 10.0 / SECTION_DIVISIONS as f64;

/// The column scene with `layers` element layers per box and `freqs` (Hz from, to,
/// count), first-order fast mode, by `method`.
pub fn column_scene(layers: usize, freqs: (f64, f64, usize), method: SweepMethod) -> Job {
    let h = layers as f64 * EDGE_MM;
    let (n, top) = (SECTION_DIVISIONS, 2.0 * h);
    let method = match method {
        SweepMethod::Direct => "direct",
        SweepMethod::Modal => "modal",
    };
    let text = format!(
        r#"{head}
[[bodies]]
name = "lower"
kind = "box"
origin = [0.0, 0.0, 0.0]
size = [10.0, 10.0, {h}]
divisions = [{n}, {n}, {layers}]
material = "steel"
[[bodies]]
name = "upper"
kind = "box"
origin = [0.0, 0.0, {h}]
size = [10.0, 10.0, {h}]
divisions = [{n}, {n}, {layers}]
material = "steel"
{joint}
[[preload]]
kind = "pressure"
body = "upper"
face = "z_max"
pressure = 1.0
[[clamp]]
body = "lower"
face = "z_min"
[[excitation]]
kind = "point"
body = "upper"
at = [5.0, 5.0, {top}]
direction = [1.0, 0.0, 0.0]
amplitude = 0.05
[sweep]
f_min = {f0}
f_max = {f1}
count = {count}
method = "{method}"
[iteration]
mode = "fast"
tolerance = 1e-3
initial_amplitude = 1e-6
[[outputs]]
name = "head"
body = "upper"
at = [5.0, 5.0, {top}]
direction = [1.0, 0.0, 0.0]
"#,
        head = steel_head("bench column"),
        joint = mindlin_interface("joint", ["lower", "upper"]),
        f0 = freqs.0,
        f1 = freqs.1,
        count = freqs.2,
    );
    Job::parse("bench-column", &text).expect("the bench column scene is valid")
}

/// Element layers per box for at least `dofs` free DOFs: 3 × 289 nodes per layer, 2L + 1
/// free layers (the foot's is clamped).
pub fn layers_for(dofs: usize) -> usize {
    let per_layer = 3 * (SECTION_DIVISIONS + 1).pow(2);
    dofs.div_ceil(per_layer)
        .saturating_sub(1)
        .div_ceil(2)
        .max(1)
}

/// One route's measured sweep.
struct Measured {
    dofs: usize,
    points: usize,
    static_s: f64,
    basis_s: f64,
    sweep_s: f64,
    peak_mb: f64,
    result: SweepResult,
}

/// Builds, runs the static step and sweeps `freqs` of `scene` by its own route.
fn measure(job: &Job, freqs: &[f64]) -> Result<Measured, String> {
    let t = Instant::now();
    let p = job.build().map_err(|e| e.to_string())?;
    let stat = static_step::solve(&p, true).map_err(|e| e.to_string())?;
    let static_s = t.elapsed().as_secs_f64();
    let settings = &job.settings;
    let mut opts = Options::from_scene(settings.iteration, settings.effects);
    opts.linear = linear_route(settings, freqs);
    let t = Instant::now();
    let result = sweep::run(&p, &stat, freqs, &opts, &|_, _, _| {}).map_err(|e| e.to_string())?;
    Ok(Measured {
        dofs: p.sys.dofs.n_free(),
        points: p.contacts.len(),
        static_s,
        basis_s: result
            .timings
            .get("modal basis (modes, residual)")
            .copied()
            .unwrap_or(0.0),
        sweep_s: t.elapsed().as_secs_f64(),
        peak_mb: peak_rss_bytes() as f64 / 1048576.0,
        result,
    })
}

/// Largest relative differences (head amplitude, joint power) of the modal sweep `a`
/// from the direct one `b` at b's frequencies where both converged; `None` where none
/// did.
fn differences(a: &SweepResult, b: &SweepResult) -> Option<(f64, f64)> {
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs().max(f64::MIN_POSITIVE);
    let both = b.freqs.iter().enumerate().filter_map(|(j, f)| {
        let i = a.freqs.iter().position(|g| g == f)?;
        (a.converged[i] && b.converged[j]).then_some((i, j))
    });
    both.fold(None, |acc, (i, j)| {
        let (amp, pow) = acc.unwrap_or((0.0f64, 0.0f64));
        Some((
            amp.max(rel(a.outputs[i][0].norm(), b.outputs[j][0].norm())),
            pow.max(rel(a.power[i], b.power[j])),
        ))
    })
}

/// Prints the table (Markdown): the modal route over `nfreq` frequencies, then the direct
/// route at every `stride`-th of them, on the column of about `dofs` DOFs.
pub fn modal_table(
    dofs: usize,
    nfreq: usize,
    stride: usize,
    out: &mut dyn Write,
) -> Result<(), String> {
    let io = |e: std::io::Error| e.to_string();
    let layers = layers_for(dofs);
    let probe = column_scene(layers, (1.0, 2.0, 2), SweepMethod::Direct);
    let f1 = stuck_modes(&probe, 1)?[0];
    let band = (0.9 * f1, 1.1 * f1, nfreq.max(2));
    let modal_scene = column_scene(layers, band, SweepMethod::Modal);
    let freqs = modal_scene.settings.sweep.frequencies();
    let modal = measure(&modal_scene, &freqs)?;
    let direct_freqs: Vec<f64> = freqs.iter().step_by(stride.max(1)).copied().collect();
    let direct_scene = column_scene(layers, band, SweepMethod::Direct);
    let direct = measure(&direct_scene, &direct_freqs)?;
    let diffs = match differences(&modal.result, &direct.result) {
        Some((amp, pow)) => format!("{amp:.1e} | {pow:.1e}"),
        None => "none converged in both | –".to_string(),
    };
    writeln!(
        out,
        "| route | free DOFs | contact points | frequencies | modes | build and static step (s) | modal basis (s) | sweep (s) | per frequency (s) | total (s) | converged | peak RSS so far (MB) | largest difference from direct, head amplitude | largest difference, joint power |"
    )
    .map_err(io)?;
    writeln!(
        out,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    )
    .map_err(io)?;
    for (route, m, diffs) in [
        ("modal", &modal, diffs),
        ("direct", &direct, "– | –".to_string()),
    ] {
        let r = &m.result;
        let n = r.freqs.len();
        let per_frequency = (m.sweep_s - m.basis_s) / n.max(1) as f64;
        let converged = r.converged.iter().filter(|&&c| c).count();
        let status = match r.singular.iter().filter(|&&s| s).count() {
            0 => format!("{converged}/{n}"),
            s => format!("{converged}/{n} ({s} singular)"),
        };
        let modes = r.modal.as_ref().map_or("–".into(), |s| s.modes.to_string());
        let basis = if r.modal.is_some() {
            format!("{:.1}", m.basis_s)
        } else {
            "–".into()
        };
        writeln!(
            out,
            "| {route} | {} | {} | {n} | {modes} | {:.1} | {basis} | {:.1} | {per_frequency:.2} | {:.1} | {status} | {:.0} | {diffs} |",
            m.dofs,
            m.points,
            m.static_s,
            m.sweep_s,
            m.static_s + m.sweep_s,
            m.peak_mb,
        )
        .map_err(io)?;
        out.flush().map_err(io)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_column_has_the_asked_dofs_and_a_289_point_joint() {
        let layers = layers_for(100_000);
        assert_eq!(layers, 58);
        // 2 × 58 + 1 free layers of 289 nodes.
        assert_eq!(3 * 289 * (2 * layers + 1), 101_439);
        let p = column_scene(2, (1.0, 2.0, 2), SweepMethod::Modal)
            .build()
            .unwrap();
        assert_eq!(p.contacts.len(), 289);
        assert_eq!(p.sys.dofs.n_free(), 3 * 289 * 5);
    }
}
