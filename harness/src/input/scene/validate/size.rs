//! The memory a scene's run needs, estimated from its tables before anything is
//! allocated, against the memory the machine has (or `JOINTLIN_MAX_MEMORY`): a scene
//! beyond it is refused at the key that makes it so big, never left to abort in an
//! allocation.
//!
//! Every count is a double, so no product overflows (`count = 2^64 − 1` is 1.8e19).

use super::Problem;
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;
use crate::util::memory::{
    self, format_bytes, LimitSource, BASE_BYTES, BYTES_PER_FREQUENCY, FACTOR_BYTES_PER_ENTRY,
    MATRIX_BYTES_PER_DOF, MAX_MEMORY_VAR, OUTPUT_BYTES_PER_FREQUENCY, POINT_BYTES_PER_FREQUENCY,
};

/// One part of the estimate: the key that sets it, its size (bytes) and what it is.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    pub key: KeyPath,
    pub bytes: f64,
    pub what: String,
}

/// The memory estimate of a scene's run (bytes), by part.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    pub parts: Vec<Part>,
}

impl Estimate {
    /// Total bytes.
    pub fn bytes(&self) -> f64 {
        BASE_BYTES + self.parts.iter().map(|p| p.bytes).sum::<f64>()
    }

    /// The largest part.
    pub fn largest(&self) -> Option<&Part> {
        self.parts.iter().max_by(|a, b| a.bytes.total_cmp(&b.bytes))
    }
}

/// Node counts of a box (divisions + 1 per axis), as doubles.
fn box_nodes(b: &BodySpec) -> Option<[f64; 3]> {
    let d = b.divisions?;
    Some(d.map(|n| n as f64 + 1.0))
}

/// Estimated entries of the LU factor of one box's matrix: nested dissection cuts a
/// box of a ≤ b ≤ c nodes into c/b blocks whose separators hold 3ab DOFs, each a dense
/// (3ab)² block: 9 a² b c (a cube of k nodes: 9k⁴ = O(n^{4/3}); a bar: O(n)).
fn factor_entries(nodes: [f64; 3]) -> f64 {
    let mut n = nodes;
    n.sort_by(f64::total_cmp);
    9.0 * n[0] * n[0] * n[1] * n[2]
}

/// Contact points of a box interface at most: the larger face of its two boxes
/// (the two largest node counts), times the sub-grid samples.
fn interface_points(s: &SceneFile, f: &InterfaceSpec) -> f64 {
    let face = |name: &str| {
        s.bodies
            .iter()
            .find(|b| b.name == name)
            .and_then(box_nodes)
            .map_or(1.0, |mut n| {
                n.sort_by(f64::total_cmp);
                n[1] * n[2]
            })
    };
    let samples = f
        .area_samples
        .map_or(1.0, |n| 1.0 + 4.0 * (n as f64).powi(2));
    face(&f.between[0]).max(face(&f.between[1])) * samples
}

/// The estimate of a validated scene.
pub fn estimate(s: &SceneFile) -> Estimate {
    let root = KeyPath::root();
    let mut parts = Vec::new();
    let mut all_dofs = 0.0;
    for (i, b) in s.bodies.iter().enumerate() {
        let Some(nodes) = box_nodes(b) else { continue };
        let dofs = 3.0 * nodes.iter().product::<f64>();
        all_dofs += dofs;
        let factor = factor_entries(nodes);
        parts.push(Part {
            key: root.key("bodies").index(i).key("divisions"),
            bytes: MATRIX_BYTES_PER_DOF * dofs + FACTOR_BYTES_PER_ENTRY * factor,
            what: format!(
                "body `{}`: {dofs:.0} DOFs, a sparse factor of about {factor:.3e} entries",
                b.name
            ),
        });
    }
    let points: f64 = s
        .interfaces
        .iter()
        .map(|f| interface_points(s, f))
        .sum::<f64>()
        + s.joints.len() as f64
        + s.springs.len() as f64;
    let directions = if s.sweep.direction == Direction::UpDown {
        2.0
    } else {
        1.0
    };
    let per_frequency = directions
        * (BYTES_PER_FREQUENCY
            + OUTPUT_BYTES_PER_FREQUENCY * s.outputs.len() as f64
            + POINT_BYTES_PER_FREQUENCY * points);
    let sw = root.key("sweep");
    parts.push(Part {
        key: sw.key("count"),
        bytes: per_frequency * s.sweep.count as f64,
        what: format!(
            "{} sweep frequencies × {points:.0} contact points and {} outputs",
            s.sweep.count,
            s.outputs.len()
        ),
    });
    for (i, r) in s.sweep.refine.iter().enumerate() {
        parts.push(Part {
            key: sw.key("refine").index(i).key("count"),
            bytes: per_frequency * r.count as f64,
            what: format!(
                "{} refine frequencies × {points:.0} contact points",
                r.count
            ),
        });
    }
    if s.sweep.method == SweepMethod::Modal && all_dofs > 0.0 {
        // The modal route keeps its mode shapes (the given count, else at most
        // MODAL_MAX_MODES; never more than the DOFs) and the residual flexibility's
        // columns (three per contact point), each a full vector of doubles. (A scene
        // over a deck: the deck's *FREQUENCY step is counted by the deck's estimate.)
        let modes = s.sweep.modes.unwrap_or(crate::settings::MODAL_MAX_MODES) as f64;
        let modes = modes.min(all_dofs);
        let columns = modes + 3.0 * points;
        parts.push(Part {
            key: sw.key("modes"),
            bytes: 8.0 * columns * all_dofs,
            what: format!(
                "modal route: {modes:.0} mode shapes and {:.0} residual columns of {all_dofs:.0} DOFs",
                3.0 * points
            ),
        });
    }
    if let Some(h) = s.iteration.harmonics {
        if s.iteration.mode == Mode::HarmonicBalance {
            // The balance condenses onto every contact direction and harmonic: a dense
            // complex matrix of (2 · points · (2H + 1))² entries.
            let m = 2.0 * points * (2.0 * h as f64 + 1.0);
            parts.push(Part {
                key: root.key("iteration").key("harmonics"),
                bytes: 16.0 * m * m,
                what: format!("harmonic balance: a dense {m:.3e}² matrix"),
            });
        }
    }
    Estimate { parts }
}

/// The scene's estimate against the memory limit ([`memory::limit`]): a problem at
/// the key of the largest part if beyond it.
pub fn check(s: &SceneFile) -> Option<Problem> {
    let limit = match memory::limit() {
        Ok(l) => l?,
        Err(msg) => return Some((KeyPath::root(), msg)),
    };
    check_against(s, limit)
}

/// [`check`] with a given limit (bytes) and its source.
pub fn check_against(s: &SceneFile, (limit, source): (f64, LimitSource)) -> Option<Problem> {
    let e = estimate(s);
    let total = e.bytes();
    if total <= limit {
        return None;
    }
    let part = e.largest()?;
    let from = source.describe();
    Some((
        part.key.clone(),
        format!(
            "the run needs about {} of memory ({}: {}), more than the {} {from}; make it smaller, or set {MAX_MEMORY_VAR}=<bytes> (e.g. 64G) to run it anyway",
            format_bytes(total),
            part.what,
            format_bytes(part.bytes),
            format_bytes(limit),
        ),
    ))
}
