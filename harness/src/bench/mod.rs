//! `jointlin bench` and `jointlin modes`; the harmonic-balance cost tables of `jointlin mhb`
//! are [`mhb_chain`] (the 3-DOF Jenkins chain) and [`mhb_fe`] (FE scenes).
//!
//! The benchmark builds three-beam stacks (steel 60×10×(2, 1, 2) mm, clamped at x = 0,
//! pressed together, tip force 0.05 N in z: the three-beams scene's data) meshed for about the requested DOF count, sweeps the
//! same frequencies around the first bending resonance (i) linearly (every joint stuck at
//! k_T0: the cost of one linear sweep), (ii) in fast mode and (iii) in thesis mode, and
//! reports the time ratios and the peak resident memory (getrusage ru_maxrss, which only
//! grows: the value after each row is the peak so far).

pub mod backbone;
pub mod column;
pub mod mhb_chain;
pub mod mhb_fe;

use std::io::Write;
use std::time::Instant;

use crate::model::Job;
use crate::settings::Mode;
use crate::solve::modal_stuck::{self, ModeCount};
use crate::solve::static_step;
use crate::solve::sweep::{self, Options};
use crate::util::rusage::peak_rss_bytes;

/// Eigenfrequencies (1/time) of the model with every closed joint stuck (k_T0 tangential,
/// static normal stiffness), after the static step.
pub fn stuck_modes(job: impl Into<Job>, count: usize) -> Result<Vec<f64>, String> {
    let s = modal_stuck::stuck_modes(job, ModeCount::Exactly(count))?;
    Ok(s.band.modes.frequencies_hz())
}

/// The benches' scenes' head: `title`, units mm, N, s, t and steel (E = 210 000 N/mm²,
/// ν = 0.3, ρ = 7.85e-9 t/mm³, mass-proportional Rayleigh damping α = 146 /s).
fn steel_head(title: &str) -> String {
    format!(
        r#"
title = "{title}"
[units]
length = "mm"
force = "N"
time = "s"
mass = "t"
[materials.steel]
E = 210000.0
nu = 0.3
rho = 7.85e-9
rayleigh_alpha = 146.0"#
    )
}

/// A joint of the benches between two bodies: the three-beams scene's Mindlin law
/// (μ = 0.2, k_T0 = 2e4 N/mm³ per area) with a linear normal law (1e6 N/mm³).
fn mindlin_interface(name: &str, between: [&str; 2]) -> String {
    let [a, b] = between;
    format!(
        r#"[[interfaces]]
name = "{name}"
between = ["{a}", "{b}"]
law = "mindlin"
mu = 0.2
k_t0_per_area = 2e4
normal_law = "linear"
normal_stiffness_per_area = 1e6"#
    )
}

/// A three-beam scene with in-plane divisions (nx, ny) and nz per 1 mm of thickness.
pub fn beam_scene(
    nx: usize,
    ny: usize,
    nz_per_mm: usize,
    freqs: (f64, f64, usize),
    mode: Mode,
) -> Job {
    let nz = |t: usize| (t * nz_per_mm).max(1);
    let text = format!(
        r#"{head}
[[bodies]]
name = "bottom"
kind = "box"
origin = [0.0, 0.0, 0.0]
size = [60.0, 10.0, 2.0]
divisions = [{nx}, {ny}, {n2}]
material = "steel"
[[bodies]]
name = "middle"
kind = "box"
origin = [0.0, 0.0, 2.0]
size = [60.0, 10.0, 1.0]
divisions = [{nx}, {ny}, {n1}]
material = "steel"
[[bodies]]
name = "top"
kind = "box"
origin = [0.0, 0.0, 3.0]
size = [60.0, 10.0, 2.0]
divisions = [{nx}, {ny}, {n2}]
material = "steel"
{lower}
{upper}
[[preload]]
kind = "pressure"
body = "top"
face = "z_max"
pressure = 1.0
[[preload]]
kind = "pressure"
body = "bottom"
face = "z_min"
pressure = 1.0
[[clamp]]
body = "bottom"
face = "x_min"
[[clamp]]
body = "middle"
face = "x_min"
[[clamp]]
body = "top"
face = "x_min"
[[excitation]]
kind = "point"
body = "top"
at = [60.0, 5.0, 5.0]
direction = [0.0, 0.0, 1.0]
amplitude = 0.05
[sweep]
f_min = {f0}
f_max = {f1}
count = {n}
[iteration]
{mode}
tolerance = 1e-3
initial_amplitude = 1e-6
[[outputs]]
name = "tip"
body = "middle"
at = [60.0, 5.0, 3.0]
direction = [0.0, 0.0, 1.0]
"#,
        head = steel_head("bench"),
        lower = mindlin_interface("lower", ["bottom", "middle"]),
        upper = mindlin_interface("upper", ["middle", "top"]),
        n2 = nz(2),
        n1 = nz(1),
        f0 = freqs.0,
        f1 = freqs.1,
        n = freqs.2,
        mode = match mode {
            Mode::Fast => "mode = \"fast\"",
            Mode::Thesis => "mode = \"thesis\"",
            Mode::HarmonicBalance => "mode = \"harmonic_balance\"\nharmonics = 7",
        },
    );
    Job::parse("bench", &text).expect("the bench scene is valid")
}

/// Mesh divisions for about `dofs` DOFs: (nx, ny = nx/6, 1 element per mm of thickness),
/// so the contact points (≈ (nx+1)(ny+1) per interface) grow with the DOFs.
pub fn divisions_for(dofs: usize) -> (usize, usize, usize) {
    divisions_for_z(dofs, 1)
}

/// As [`divisions_for`] with `z` elements per mm of thickness: more DOFs through the
/// thickness, fewer contact points for the same DOF count.
pub fn divisions_for_z(dofs: usize, z: usize) -> (usize, usize, usize) {
    let count = |nx: usize| 3 * (nx + 1) * (nx / 6 + 1) * ((2 * z + 1) * 2 + z + 1);
    let err = |d: usize| (d as f64 / dofs as f64).ln().abs();
    let nx = (6..=1200)
        .step_by(6)
        .min_by(|a, b| err(count(*a)).total_cmp(&err(count(*b))))
        .expect("non-empty search");
    (nx, nx / 6, z)
}

/// One benchmark row.
#[derive(Debug, Clone)]
pub struct Row {
    pub dofs: usize,
    pub points: usize,
    pub linear_s: f64,
    pub fast_s: f64,
    pub thesis_s: Option<f64>,
    pub fast_iterations: f64,
    pub thesis_passes: Option<usize>,
    pub peak_rss_mb: f64,
}

/// Runs one size.
pub fn row(dofs: usize, nfreq: usize, with_thesis: bool) -> Result<Row, String> {
    row_with(divisions_for(dofs), nfreq, with_thesis)
}

/// Runs one mesh (nx, ny, elements per mm).
pub fn row_with(
    div: (usize, usize, usize),
    nfreq: usize,
    with_thesis: bool,
) -> Result<Row, String> {
    let (nx, ny, z) = div;
    let probe = beam_scene(nx, ny, z, (1.0, 2.0, 2), Mode::Fast);
    let f1 = stuck_modes(&probe, 1)?[0];
    let band = (0.9 * f1, 1.1 * f1, nfreq);
    let time =
        |mode: Mode, linear: bool| -> Result<(f64, sweep::SweepResult, usize, usize), String> {
            let s = beam_scene(nx, ny, z, band, mode);
            let p = s.build().map_err(|e| e.to_string())?;
            let stat = static_step::solve(&p, true).map_err(|e| e.to_string())?;
            let mut opts = Options::from_scene(s.settings.iteration, s.settings.effects);
            opts.effects.tangential_microslip = !linear;
            let t = Instant::now();
            let r = sweep::run(
                &p,
                &stat,
                &s.settings.sweep.frequencies(),
                &opts,
                &|_, _, _| {},
            )
            .map_err(|e| e.to_string())?;
            Ok((
                t.elapsed().as_secs_f64(),
                r,
                p.sys.dofs.n_free(),
                p.contacts.len(),
            ))
        };
    let (lin, _, n, pts) = time(Mode::Fast, true)?;
    let (fast, rf, _, _) = time(Mode::Fast, false)?;
    let (thesis_s, thesis_passes) = if with_thesis {
        let (t, r, _, _) = time(Mode::Thesis, false)?;
        (Some(t), Some(r.passes.len()))
    } else {
        (None, None)
    };
    Ok(Row {
        dofs: n,
        points: pts,
        linear_s: lin,
        fast_s: fast,
        thesis_s,
        fast_iterations: rf.iterations.iter().sum::<usize>() as f64
            / rf.iterations.len().max(1) as f64,
        thesis_passes,
        peak_rss_mb: peak_rss_bytes() as f64 / 1048576.0,
    })
}

/// Prints the benchmark table (Markdown).
pub fn table(
    dofs: &[usize],
    nfreq: usize,
    thesis_max: usize,
    out: &mut dyn Write,
) -> Result<(), String> {
    let io = |e: std::io::Error| e.to_string();
    writeln!(
        out,
        "| DOF | contact points | linear sweep [s] | fast [s] | fast / linear | fast iterations per frequency | thesis [s] | thesis / linear | thesis passes | peak RSS so far [MB] |"
    )
    .map_err(io)?;
    writeln!(out, "|---|---|---|---|---|---|---|---|---|---|").map_err(io)?;
    for &d in dofs {
        let r = row(d, nfreq, d <= thesis_max)?;
        let th = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.2}"));
        writeln!(
            out,
            "| {} | {} | {:.2} | {:.2} | {:.2} | {:.1} | {} | {} | {} | {:.0} |",
            r.dofs,
            r.points,
            r.linear_s,
            r.fast_s,
            r.fast_s / r.linear_s,
            r.fast_iterations,
            th(r.thesis_s),
            r.thesis_s
                .map_or("—".to_string(), |t| format!("{:.2}", t / r.linear_s)),
            r.thesis_passes.map_or("—".to_string(), |p| p.to_string()),
            r.peak_rss_mb
        )
        .map_err(io)?;
        out.flush().map_err(io)?;
    }
    Ok(())
}

/// Cost against the number of contact points at about the same DOF count: meshes with
/// 1, 2 and 4 elements per mm of thickness (fewer, larger in-plane elements). Fast mode
/// only. Prints a Markdown table.
pub fn contact_table(dofs: usize, nfreq: usize, out: &mut dyn Write) -> Result<(), String> {
    let io = |e: std::io::Error| e.to_string();
    writeln!(
        out,
        "| DOF | contact points | elements per mm thickness | linear sweep [s] | fast [s] | fast / linear | fast iterations per frequency |"
    )
    .map_err(io)?;
    writeln!(out, "|---|---|---|---|---|---|---|").map_err(io)?;
    for z in [4, 2, 1] {
        let r = row_with(divisions_for_z(dofs, z), nfreq, false)?;
        writeln!(
            out,
            "| {} | {} | {z} | {:.2} | {:.2} | {:.2} | {:.1} |",
            r.dofs,
            r.points,
            r.linear_s,
            r.fast_s,
            r.fast_s / r.linear_s,
            r.fast_iterations
        )
        .map_err(io)?;
        out.flush().map_err(io)?;
    }
    Ok(())
}
