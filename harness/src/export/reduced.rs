//! A reduction as files (docs/reduce.md): `K.mtx`, `M.mtx` (and `D.mtx`) as Matrix
//! Market, `dofs.csv` (the retained coordinates by point and axis, then `modal,k`), and
//! `scene.toml`, the full scene's units, sweep, iteration and effects over a
//! `[[matrices]]` model with one `[[joints]]` entry per contact direction, the load and
//! the outputs on their coordinates.

use std::path::{Path, PathBuf};

use crate::formats::mtx::write_symmetric;
use crate::input::scene::schema::{DofsSpec, SceneFile};
use crate::input::scene::schema::{ExcitationKind, ExcitationSpec, JointSpec, MatricesSpec};
use crate::settings::{Effects, Mode, OutputSpec, SweepMethod, SweepSpec};
use crate::util::atomic;

use crate::reduce::Reduction;

/// The name of the `[[matrices]]` model, the prefix of its points.
pub const MODEL: &str = "reduced";

fn unit_axis(label: char, sign: f64) -> [f64; 3] {
    let mut d = [0.0; 3];
    d[(label as u8 - b'x') as usize] = sign;
    d
}

/// The DOF list: a header, the frame notes, the retained rows, `modal,k` per interior
/// mode.
pub fn dofs_csv(r: &Reduction) -> String {
    let mut s = String::from(
        "# Retained coordinates (relative tangential displacements of the closed contact\n\
         # points, second surface minus first, and with the three-direction effects their\n\
         # opening; the outputs; the load), then the interior modes' amplitudes\n\
         # (modal,k). Named by global axes unless noted:\n",
    );
    for n in &r.set.notes {
        s.push_str(&format!("# {n}\n"));
    }
    s.push_str("point,direction\n");
    for row in &r.set.rows {
        s.push_str(&format!("{},{}\n", row.point, row.label));
    }
    for k in 1..=r.interior {
        s.push_str(&format!("modal,{k}\n"));
    }
    s
}

/// The reduced scene over the full one's `spec`: its units, title, sweep (direct),
/// iteration (mode `thesis`, FE-only, becomes `fast`) and outputs; of the effects a
/// lumped system switches material damping, on where D.mtx is written.
pub fn scene_file(r: &Reduction, spec: &SceneFile) -> SceneFile {
    let point = |k: usize| format!("{MODEL}.{}", r.set.rows[k].point);
    let joints = r
        .set
        .joints
        .iter()
        .map(|j| JointSpec {
            name: j.name.clone(),
            between: [point(j.coordinate), "ground".into()],
            direction: unit_axis(r.set.rows[j.coordinate].label, 1.0),
            law: j.law.law,
            rule: j.law.rule,
            mu: j.law.mu,
            normal_force: Some(j.law.normal),
            k_t0: j.law.k_t0,
            normal: None,
            normal_stiffness: None,
        })
        .chain(r.set.points.iter().map(|pt| {
            let axis = |a: usize| {
                let mut d = [0.0; 3];
                d[pt.axes[a].0] = pt.axes[a].1;
                d
            };
            // Opening along n = ±e_k, g = the point's coordinate along it: δ_n (the
            // normal row is the coordinate along +e_k, so n·x = δ_n); clamped by N₀.
            JointSpec {
                name: pt.name.clone(),
                between: ["ground".into(), point(pt.coordinates[0])],
                direction: axis(0),
                law: pt.law.law,
                rule: pt.law.rule,
                mu: pt.law.mu,
                normal_force: Some(pt.law.normal),
                k_t0: pt.law.k_t0,
                normal: Some(axis(2)),
                normal_stiffness: Some(pt.k_n),
            }
        }))
        .collect();
    let excitation = r
        .set
        .load
        .iter()
        .map(|l| ExcitationSpec {
            kind: ExcitationKind::Point,
            body: point(l.coordinate),
            at: None,
            face: None,
            direction: unit_axis(r.set.rows[l.coordinate].label, l.sign),
            amplitude: l.amplitude,
            phase_deg: l.phase_deg,
        })
        .collect();
    let outputs = r
        .set
        .outputs
        .iter()
        .map(|o| OutputSpec {
            name: o.name.clone(),
            body: point(o.coordinate),
            at: None,
            direction: unit_axis(r.set.rows[o.coordinate].label, o.sign),
        })
        .collect();
    let mut iteration = spec.iteration;
    if iteration.mode == Mode::Thesis {
        iteration.mode = Mode::Fast;
    }
    SceneFile {
        title: format!("{} (reduced)", spec.title),
        model: None,
        units: spec.units.clone(),
        materials: Default::default(),
        bodies: Vec::new(),
        matrices: vec![MatricesSpec {
            name: MODEL.into(),
            mass: "M.mtx".into(),
            stiffness: "K.mtx".into(),
            damping: r.d.as_ref().map(|_| "D.mtx".into()),
            dofs: DofsSpec::File("dofs.csv".into()),
        }],
        interfaces: Vec::new(),
        ties: Vec::new(),
        preload: Vec::new(),
        screws: Vec::new(),
        clamp: Vec::new(),
        springs: Vec::new(),
        joints,
        excitation,
        outputs,
        sweep: SweepSpec {
            method: SweepMethod::Direct,
            modes: None,
            residual: None,
            modal_damping: Vec::new(),
            ..spec.sweep.clone()
        },
        iteration,
        // A lumped system switches material damping (D.mtx is written with it on) and,
        // on joints with `normal`, the three-direction point's effects.
        effects: Effects {
            material_damping: r.d.is_some(),
            normal_load_variation: spec.effects.normal_load_variation,
            coupled_slip: spec.effects.coupled_slip,
            ..Effects::default()
        },
        loss_study: None,
        time_domain: None,
        field_output: None,
    }
}

/// Writes the reduction's files into `dir` (created if missing); returns their paths.
/// `origin`: the reduced input and how, for the files' comments.
pub fn write(
    r: &Reduction,
    spec: &SceneFile,
    dir: &Path,
    origin: &str,
) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let comment = format!(
        "{origin}\n{} retained coordinates then {} interior modes (dofs.csv)",
        r.set.rows.len(),
        r.interior
    );
    let mut files = vec![
        (
            "K.mtx",
            write_symmetric(&r.k, &format!("K (force/length): {comment}")),
        ),
        (
            "M.mtx",
            write_symmetric(&r.m, &format!("M (mass): {comment}")),
        ),
    ];
    if let Some(d) = &r.d {
        files.push((
            "D.mtx",
            write_symmetric(d, &format!("D (force·time/length): {comment}")),
        ));
    }
    files.push(("dofs.csv", dofs_csv(r)));
    let scene = toml::to_string(&scene_file(r, spec)).map_err(|e| e.to_string())?;
    files.push((
        "scene.toml",
        format!("# {origin}\n# Run it: jointlin run scene.toml --out DIR (or backbone, modes).\n{scene}"),
    ));
    let mut written = Vec::new();
    for (name, text) in files {
        let path = dir.join(name);
        atomic::write_text(&path, &text)?;
        written.push(path);
    }
    Ok(written)
}
