//! Mesh study of a loss study (thesis §5.4.2, "a finer mesh changes the loss by less
//! than 2 %"): the power at resonance at the first reference point's torque, at its
//! amplitude and a quarter of it (each at its own resonance, as [`super::power_at`]), for every
//! box's divisions multiplied by each factor, or only some axes' of some boxes
//! ([`Refinement`]: which part of the discretization error a change comes from), with
//! the contact law averaged over area samples ([`crate::model::subgrid`]) and,
//! optionally, at the nodes (the thesis's way).

use std::fmt::Write as _;

use super::{powers_at, LossError};
use crate::model::Job;
use crate::util::number::exact;
use crate::util::parallel::{in_parallel, threads};

/// Samples per quarter face and direction of the area-sampled variant.
pub const STUDY_AREA_SAMPLES: usize = 4;

/// Which divisions a study multiplies: those along `axes` of the boxes whose name
/// starts with one of `bodies` (every box when empty). Boxes tied or in contact must
/// keep matching grids on their common faces (else the model build names the node).
#[derive(Debug, Clone, PartialEq)]
pub struct Refinement {
    pub axes: [bool; 3],
    pub bodies: Vec<String>,
}

impl Refinement {
    /// Every axis of every box.
    pub fn everything() -> Self {
        Refinement {
            axes: [true; 3],
            bodies: Vec::new(),
        }
    }

    /// Parses `AXES` or `AXES:PREFIX,PREFIX…` with AXES letters from x, y, z, e.g. `z`,
    /// `xyz`, `x:jaw_,blade_in`.
    pub fn parse(spec: &str) -> Result<Self, String> {
        let (axes_text, bodies) = match spec.split_once(':') {
            Some((a, b)) => (a, b.split(',').map(str::to_string).collect::<Vec<_>>()),
            None => (spec, Vec::new()),
        };
        let mut axes = [false; 3];
        for ch in axes_text.chars() {
            let a = "xyz"
                .find(ch)
                .ok_or_else(|| format!("refinement `{spec}`: axis `{ch}` is not x, y or z"))?;
            axes[a] = true;
        }
        if !axes.contains(&true) || bodies.iter().any(String::is_empty) {
            return Err(format!(
                "refinement `{spec}`: expected AXES[:PREFIX,…], e.g. `z` or `x:jaw_,blade_in`"
            ));
        }
        Ok(Refinement { axes, bodies })
    }

    /// Short description, e.g. "x of jaw_*, blade_in*".
    pub fn label(&self) -> String {
        let axes: String = "xyz"
            .chars()
            .zip(self.axes)
            .filter_map(|(c, on)| on.then_some(c))
            .collect();
        if self.bodies.is_empty() {
            format!("{axes} of every box")
        } else {
            let b: Vec<String> = self.bodies.iter().map(|b| format!("{b}*")).collect();
            format!("{axes} of {}", b.join(", "))
        }
    }

    fn applies_to(&self, body: &str) -> bool {
        self.bodies.is_empty() || self.bodies.iter().any(|p| body.starts_with(p.as_str()))
    }
}

/// One mesh of the study.
#[derive(Debug, Clone)]
pub struct MeshRow {
    /// Divisions multiplied by this.
    pub factor: usize,
    /// Which divisions ([`Refinement::label`]).
    pub refined: String,
    /// Index of the row this one is compared with (the next coarser of its refinement).
    pub compared_to: Option<usize>,
    pub free_dofs: usize,
    pub contact_points: usize,
    /// Resonance (1/time) per amplitude with the area-sampled law.
    pub freq: [f64; 2],
    /// Target amplitudes (scene length).
    pub amplitudes: [f64; 2],
    /// Power (reported unit) per amplitude, area-sampled.
    pub sampled: [f64; 2],
    /// Node-based (when the study ran it), per amplitude.
    pub node: Option<NodeBased>,
}

/// The node-based half of a [`MeshRow`].
#[derive(Debug, Clone, Copy)]
pub struct NodeBased {
    /// Power (reported unit) per amplitude.
    pub power: [f64; 2],
    /// Share of the loss dissipated by points whose pressure is below
    /// [`LOW_PRESSURE`] × the largest pressure (the edges of the contact patch).
    pub low_pressure_share: [f64; 2],
}

/// "Low pressure" for [`NodeBased::low_pressure_share`]: below this fraction of the
/// largest contact pressure.
pub const LOW_PRESSURE: f64 = 0.2;

/// Share of the energy per cycle of `sample`'s points dissipated where the pressure is
/// below [`LOW_PRESSURE`] × the largest one.
fn low_pressure_share(pressure: &[f64], sample: &super::Sample) -> f64 {
    let p_max = pressure.iter().copied().fold(0.0, f64::max);
    let (mut low, mut all) = (0.0, 0.0);
    for (p, q) in pressure.iter().zip(&sample.points) {
        all += q.energy;
        if *p < LOW_PRESSURE * p_max {
            low += q.energy;
        }
    }
    if all > 0.0 {
        low / all
    } else {
        0.0
    }
}

/// The job with every box's divisions multiplied by `factor`.
pub fn refined(job: impl Into<Job>, factor: usize) -> Job {
    refined_by(&job.into(), factor, &Refinement::everything())
}

/// The job with the divisions `r` selects multiplied by `factor`.
pub fn refined_by(job: &Job, factor: usize, r: &Refinement) -> Job {
    job.refined(factor, |name| r.applies_to(name), r.axes)
}

/// The meshes a study computes for `factors` and `refinements`: (factor, refinement
/// index, index of the row it is compared with). Factor 1 is the scene itself, once,
/// and every refinement's first finer mesh is compared with it.
pub fn plan(factors: &[usize], refinements: usize) -> Vec<(usize, usize, Option<usize>)> {
    let mut out = Vec::new();
    let mut base = None;
    for r in 0..refinements {
        let mut prev = base;
        for &f in factors {
            if f == 1 {
                if base.is_none() {
                    out.push((1, r, None));
                    base = Some(out.len() - 1);
                }
                prev = base;
                continue;
            }
            out.push((f, r, prev));
            prev = Some(out.len() - 1);
        }
    }
    out
}

/// The contact laws a study runs per mesh, as `area_samples` (`None`: node-based).
pub fn laws(node_based: bool) -> &'static [Option<usize>] {
    if node_based {
        &[None, Some(STUDY_AREA_SAMPLES)]
    } else {
        &[Some(STUDY_AREA_SAMPLES)]
    }
}

/// Runs the study over `factors` and `refinements` ([`plan`]), with the node-based law
/// too when `node_based`; the meshes on as many threads as the machine has cores (each
/// mesh is independent); `progress(message)` before each model (one per law and mesh).
pub fn study(
    job: impl Into<Job>,
    factors: &[usize],
    refinements: &[Refinement],
    node_based: bool,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Vec<MeshRow>, LossError> {
    let job: &Job = &job.into();
    let st = job.settings.loss_study.as_ref().ok_or(LossError::NoStudy)?;
    let reference = st
        .reference
        .first()
        .ok_or_else(|| LossError::Spec("the mesh study needs a reference point".into()))?;
    let amplitudes = [0.25 * reference.amplitude, reference.amplitude];
    let laws = laws(node_based);
    let mesh_row = |&(factor, r, compared_to): &(usize, usize, Option<usize>)| {
        let refinement = &refinements[r];
        let refined = if factor == 1 {
            "none (the job)".to_string()
        } else {
            refinement.label()
        };
        let mut row = MeshRow {
            factor,
            refined: refined.clone(),
            compared_to,
            free_dofs: 0,
            contact_points: 0,
            freq: [0.0; 2],
            amplitudes,
            sampled: [0.0; 2],
            node: None,
        };
        for &samples in laws {
            progress(&format!(
                "divisions × {factor} ({refined}), {}",
                samples.map_or("node-based".into(), |s| format!("{s} × {s} area samples"))
            ));
            let sc = refined_by(job, factor, refinement).with_area_samples(samples);
            // Each amplitude at its own resonance, as `power_at` (the trend tests') does.
            let (got, op) = powers_at(&sc, reference.torque, &amplitudes)?;
            let power = [0, 1].map(|k| got[k].power * st.power_factor);
            row.free_dofs = op.problem.sys.dofs.n_free();
            row.contact_points = op.problem.contacts.len();
            if samples.is_none() {
                row.node = Some(NodeBased {
                    power,
                    low_pressure_share: [0, 1]
                        .map(|k| low_pressure_share(&op.stat.pressure, &got[k])),
                });
            } else {
                row.freq = [0, 1].map(|k| got[k].freq);
                row.sampled = power;
            }
        }
        Ok(row)
    };
    let jobs = plan(factors, refinements.len());
    in_parallel(&jobs, threads(), mesh_row)
        .into_iter()
        .collect()
}

/// Change of `now` against `before`, percent.
fn change(before: Option<f64>, now: f64) -> String {
    before.map_or("".into(), |b| format!("{:+.1} %", 100.0 * (now - b) / b))
}

/// Markdown table of the study (power in the study's unit, change to the coarser mesh);
/// node-based columns when the study ran that law.
pub fn markdown(job: &Job, rows: &[MeshRow]) -> String {
    let Some(st) = job.settings.loss_study.as_ref() else {
        return String::new();
    };
    let (pu, au, af) = (&st.power_unit, &st.amplitude_unit, st.amplitude_factor);
    let node_based = rows.iter().any(|r| r.node.is_some());
    let mut s = format!(
        "Mesh study, `{}` ({}): power loss at resonance with the divisions named under \
         \"refined\" × factor, each change against the next coarser mesh of its kind (the \
         scene itself for the first){}.\n\n",
        job.settings.title,
        job.file(),
        if node_based {
            format!(
                "; low-p share: part of the node-based loss from points below {:.0} % of \
                 the largest pressure",
                100.0 * LOW_PRESSURE
            )
        } else {
            String::new()
        }
    );
    let Some(first) = rows.first() else {
        return s;
    };
    let [a0, a1] = first.amplitudes.map(|a| a / af);
    let _ = write!(
        s,
        "| × | refined | free DOFs | points | resonance at {a1:.1} {au} |"
    );
    let mut align = String::from("|---:|---|---:|---:|---:|");
    if node_based {
        for a in [a0, a1] {
            let _ = write!(s, " node-based {a:.1} {au} [{pu}] | change | low-p share |");
            align.push_str("---:|---:|---:|");
        }
    }
    for a in [a0, a1] {
        let _ = write!(s, " sampled {a:.1} {au} [{pu}] | change |");
        align.push_str("---:|---:|");
    }
    let _ = writeln!(s, "\n{align}");
    for r in rows {
        let prev = r.compared_to.map(|j| &rows[j]);
        let _ = write!(
            s,
            "| {} | {} | {} | {} | {:.1} |",
            r.factor, r.refined, r.free_dofs, r.contact_points, r.freq[1],
        );
        if node_based {
            for k in 0..2 {
                match &r.node {
                    Some(n) => {
                        let before = prev.and_then(|p| p.node).map(|p| p.power[k]);
                        let _ = write!(
                            s,
                            " {:.4} | {} | {:.0} % |",
                            n.power[k],
                            change(before, n.power[k]),
                            100.0 * n.low_pressure_share[k]
                        );
                    }
                    None => s.push_str(" – | | |"),
                }
            }
        }
        for k in 0..2 {
            let before = prev.map(|p| p.sampled[k]);
            let _ = write!(
                s,
                " {:.4} | {} |",
                r.sampled[k],
                change(before, r.sampled[k])
            );
        }
        s.push('\n');
    }
    s
}

/// CSV of the study (node-based fields empty when not run).
pub fn csv(rows: &[MeshRow]) -> String {
    let mut s = String::from(
        "factor,refined,free_dofs,contact_points,frequency,amplitude,power_node_based,power_area_sampled,low_pressure_share\n",
    );
    let opt = |x: Option<f64>| x.map_or(String::new(), exact);
    for r in rows {
        for k in 0..2 {
            let _ = writeln!(
                s,
                "{},\"{}\",{},{},{},{},{},{},{}",
                r.factor,
                r.refined,
                r.free_dofs,
                r.contact_points,
                exact(r.freq[k]),
                exact(r.amplitudes[k]),
                opt(r.node.map(|n| n.power[k])),
                exact(r.sampled[k]),
                opt(r.node.map(|n| n.low_pressure_share[k]))
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refinement_specs_parse_and_bad_ones_are_named() {
        let r = Refinement::parse("x:jaw_,blade_in").unwrap();
        assert_eq!(r.axes, [true, false, false]);
        assert_eq!(r.bodies, ["jaw_", "blade_in"]);
        assert_eq!(r.label(), "x of jaw_*, blade_in*");
        assert_eq!(Refinement::parse("zy").unwrap().label(), "yz of every box");
        for bad in ["", "w", "x:", "x:a,,b", ":jaw"] {
            assert!(Refinement::parse(bad).is_err(), "{bad}");
        }
    }

    /// The scene itself once, first (which divisions a refinement multiplies:
    /// `model::variants`' test).
    #[test]
    fn the_plan_computes_the_scene_itself_once_first() {
        let r = Refinement::parse("xz:jaw_").unwrap();
        assert!(r.applies_to("jaw_left") && !r.applies_to("blade"));
        assert_eq!(r.axes, [true, false, true]);
        assert_eq!(
            plan(&[1, 2, 3], 2),
            vec![
                (1, 0, None),
                (2, 0, Some(0)),
                (3, 0, Some(1)),
                (2, 1, Some(0)),
                (3, 1, Some(3))
            ]
        );
        assert_eq!(plan(&[2], 2), vec![(2, 0, None), (2, 1, None)]);
    }
}
