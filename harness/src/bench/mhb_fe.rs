//! `jointlin mhb --scene SCENE`: cost vs H of the harmonic balance on an FE scene:
//! the scene's sweep replaced by `count` frequencies over a band
//! (default the scene's first refine band: its first resonance), run in fast mode (first
//! order) and with `mode = "harmonic_balance"` at each H, each frequency's Newton started
//! from the previous one's solution. Per row: time per frequency split into the mesh part
//! (per-harmonic factorizations and receptance solves) and the contact part (AFT marches
//! through the C API and the condensed Newton; CPU time: a shared machine inflates wall
//! time), iterations, C-API calls, and the first output's peak and deviation from the
//! last row.

use std::fmt::Write as _;

use crate::capi;
use crate::mhb::default_samples;
use crate::model::Job;
use crate::run::{run, Extras};
use crate::settings::{Mode, Spacing};
use crate::util::rusage::cpu_seconds;

/// One row of the table.
#[derive(Debug, Clone)]
pub struct FeRow {
    pub label: String,
    /// Harmonic-balance unknowns m(2H + 1) (0 for first order).
    pub unknowns: usize,
    /// Sweep seconds per frequency (wall), and its mesh and contact parts (CPU for the
    /// harmonic balance, wall for first order).
    pub per_freq: f64,
    /// CPU seconds per frequency of the whole run (build and static step included).
    pub cpu_per_freq: f64,
    pub mesh_per_freq: f64,
    pub contact_per_freq: f64,
    /// Newton (harmonic balance) or contact iterations (first order) per frequency.
    pub iterations: f64,
    /// FGMRES iterations per Newton iteration (harmonic balance).
    pub gmres_per_newton: f64,
    /// jointlin_point_step (harmonic balance) or jointlin_linearize calls per frequency.
    pub calls_per_freq: f64,
    pub peak: f64,
    /// Largest |y − y_last| / peak_last over the band, first output.
    pub deviation: f64,
}

/// What the table was run on.
#[derive(Debug, Clone)]
pub struct FeBench {
    pub scene: String,
    pub free_dofs: usize,
    /// Contact directions m (two per closed point).
    pub directions: usize,
    pub band: (f64, f64),
    pub count: usize,
    pub rows: Vec<FeRow>,
}

/// Runs the table. `band`: default the scene's first refine band, else its sweep range.
pub fn table(
    scene: impl Into<Job>,
    band: Option<(f64, f64)>,
    count: usize,
    hs: &[usize],
    log: &dyn Fn(&str),
) -> Result<FeBench, String> {
    let scene: Job = scene.into();
    let sw = &scene.settings.sweep;
    let band = band.unwrap_or_else(|| {
        sw.refine
            .first()
            .map_or((sw.f_min, sw.f_max), |b| (b.f_min, b.f_max))
    });
    let mut base = scene.clone();
    let s = &mut base.settings.sweep;
    (s.f_min, s.f_max, s.count, s.spacing) = (band.0, band.1, count.max(1), Spacing::Linear);
    if count <= 1 {
        s.f_max = s.f_min;
    }
    s.refine.clear();
    let mut rows = Vec::new();
    let mut curves = Vec::new();
    let (mut free_dofs, mut directions) = (0, 0);
    let runs: Vec<Option<usize>> = std::iter::once(None)
        .chain(hs.iter().map(|&h| Some(h)))
        .collect();
    for h in runs {
        let mut sc = base.clone();
        let label = match h {
            None => {
                sc.settings.iteration.mode = Mode::Fast;
                "first order (fast mode, jointlin_linearize)".to_string()
            }
            Some(h) => {
                let it = &mut sc.settings.iteration;
                (it.mode, it.harmonics, it.samples) = (Mode::HarmonicBalance, Some(h), None);
                format!("H = {h} (N = {})", default_samples(h))
            }
        };
        log(&label);
        let steps = capi::point_steps();
        let cpu = cpu_seconds();
        let r = run(&sc, Extras::default(), &|_, _, _| {}).map_err(|e| e.to_string())?;
        let steps = capi::point_steps() - steps;
        let cpu = cpu_seconds() - cpu;
        let n = r.main.freqs.len() as f64;
        let t = |k: &str| r.main.timings.get(k).copied().unwrap_or(0.0) / n;
        free_dofs = r.problem.sys.dofs.n_free();
        directions = 2 * r.stat.closed.iter().filter(|&&c| c).count();
        let iterations = r.main.iterations.iter().sum::<usize>() as f64;
        let (mesh, contact, calls) = match h {
            None => (
                t("receptance solves") + t("factorization"),
                t("linearization (C API)") + t("condensed iterations"),
                r.calls.linearize as f64 / n,
            ),
            Some(_) => (
                t("CPU: receptance solves"),
                t("CPU: harmonic balance (AFT + Newton)"),
                steps as f64 / n,
            ),
        };
        rows.push(FeRow {
            label,
            unknowns: h.map_or(0, |h| directions * (2 * h + 1)),
            per_freq: r.seconds[2] / n,
            cpu_per_freq: cpu / n,
            mesh_per_freq: mesh,
            contact_per_freq: contact,
            iterations: iterations / n,
            gmres_per_newton: if h.is_some() && iterations > 0.0 {
                r.main.gmres_solves as f64 / iterations
            } else {
                0.0
            },
            calls_per_freq: calls,
            peak: 0.0,
            deviation: 0.0,
        });
        curves.push(r.main.outputs.iter().map(|o| o[0]).collect::<Vec<_>>());
    }
    let last = curves.last().cloned().unwrap_or_default();
    let peak_last = last.iter().map(|z| z.norm()).fold(0.0, f64::max);
    for (row, c) in rows.iter_mut().zip(&curves) {
        row.peak = c.iter().map(|z| z.norm()).fold(0.0, f64::max);
        row.deviation = c
            .iter()
            .zip(&last)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max)
            / peak_last;
    }
    Ok(FeBench {
        scene: scene.file().to_string(),
        free_dofs,
        directions,
        band,
        count,
        rows,
    })
}

/// The table as Markdown.
pub fn markdown(b: &FeBench) -> String {
    let mut s = format!(
        "`{}`: {} free DOFs, {} contact directions; {} frequencies in [{}, {}], first output; \
         parts per frequency in CPU seconds for the harmonic balance, wall for first order:\n\n\
         | method | unknowns m(2H+1) | CPU s per frequency | wall s per frequency | mesh part (factorizations, receptances) | contact part (AFT, Newton) | iterations per frequency | FGMRES per Newton | C-API calls per frequency (point_step; linearize) | peak | max deviation from the last row |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
        b.scene, b.free_dofs, b.directions, b.count, b.band.0, b.band.1
    );
    for r in &b.rows {
        let _ = writeln!(
            s,
            "| {} | {} | {:.3e} | {:.3e} | {:.3e} | {:.3e} | {:.1} | {:.1} | {:.3e} | {:.5e} | {:.2e} |",
            r.label,
            r.unknowns,
            r.cpu_per_freq,
            r.per_freq,
            r.mesh_per_freq,
            r.contact_per_freq,
            r.iterations,
            r.gmres_per_newton,
            r.calls_per_freq,
            r.peak,
            r.deviation
        );
    }
    s
}
