//! The contact points' loops of an FE run: which to draw (the points that dissipate
//! most), and the harmonic balance's loops.csv and loops.svg (its largest converged
//! response; the time domain writes loops_time.csv and loops_time.svg the same way).

use std::path::{Path, PathBuf};

use super::loop_plot::{self, JointLoop, MAX_PANELS};
use crate::mhb::loops::LoopSample;
use crate::model::{Job, Problem};
use crate::run::RunResult;
use crate::settings::units::frequency_unit;
use crate::time::tables::{point_loops_csv, PointLoops};
use crate::util::atomic;

/// Energy point `i` dissipates over the closed period of `samples`: ∮ F·du along both
/// tangential directions by the trapezoid rule (force·length).
fn enclosed(samples: &[Vec<LoopSample>], i: usize) -> f64 {
    let n = samples.len();
    (0..n)
        .map(|k| {
            let (a, b) = (&samples[(k + n - 1) % n][i], &samples[k][i]);
            (0..2)
                .map(|c| 0.5 * (a.force[c] + b.force[c]) * (b.displacement[c] - a.displacement[c]))
                .sum::<f64>()
        })
        .sum()
}

/// The loops of the (at most [`MAX_PANELS`]) points among `points` that enclose the
/// most energy, named by point index, interface and node.
pub fn most_dissipating(
    p: &Problem,
    node_ids: &[u64],
    samples: &[Vec<LoopSample>],
    points: &[usize],
) -> Vec<JointLoop> {
    let mut order: Vec<(usize, f64)> = points.iter().map(|&i| (i, enclosed(samples, i))).collect();
    order.sort_by(|a, b| b.1.total_cmp(&a.1));
    order
        .iter()
        .take(MAX_PANELS)
        .map(|&(i, _)| {
            let c = &p.contacts[i];
            let node = node_ids
                .get(c.nodes[1])
                .map_or(String::new(), |n| format!(", node {n}"));
            let along = |a: usize| {
                samples
                    .iter()
                    .map(move |s| (s[i].displacement[a], s[i].force[a]))
            };
            JointLoop {
                name: format!("point {i} ({}{node})", p.interfaces[c.interface].name),
                t1: along(0).collect(),
                t2: along(1).collect(),
            }
        })
        .collect()
}

/// loops.csv (and with `plots` loops.svg) of a harmonic-balance run's largest
/// converged response; nothing without one.
pub fn balance_files(
    dir: &Path,
    job: &Job,
    r: &RunResult,
    plots: bool,
) -> Result<Vec<PathBuf>, String> {
    let Some(l) = &r.main.loops else {
        return Ok(Vec::new());
    };
    let units = &job.settings.units;
    let node_ids = job.node_ids(&r.problem);
    let table = PointLoops {
        freq: l.freq,
        samples: &l.samples,
        points: &l.points,
        overclosure: l.overclosure,
    };
    let csv = dir.join("loops.csv");
    atomic::write_text(&csv, &point_loops_csv(&r.problem, &table, units, &node_ids))?;
    let mut out = vec![csv];
    let loops = most_dissipating(&r.problem, &node_ids, &l.samples, &l.points);
    if plots && !loops.is_empty() {
        let fu = frequency_unit(units);
        let title = format!(
            "{}: harmonic balance, the {} points dissipating most, one period at {:.4} {}",
            job.title(),
            loops.len(),
            fu.show(l.freq),
            fu.text
        );
        let svg = dir.join("loops.svg");
        atomic::with_temp(&svg, |t| loop_plot::draw(t, &title, units, &loops))?;
        out.push(svg);
    }
    Ok(out)
}
