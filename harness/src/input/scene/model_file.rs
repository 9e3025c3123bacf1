//! Scenes that take their model from a deck, `model = "file.inp"` (path relative to the
//! scene): the mesh, materials, sets, boundaries, ties, contact pairs, loads and the
//! steady-state step's frequencies come from the deck; the scene keeps `[units]`,
//! `[effects]`, `[iteration]`, `[[outputs]]` (`body` = a node or element set of the
//! deck: its node nearest `at`) and the study tables. The deck itself is read by
//! `input::load` (its errors are the deck's, `file:line: *KEYWORD: message`).

use std::path::Path;
use std::sync::Arc;

use super::error::Problem;
use super::error::{at_path, KeyPath, Seg};
use super::schema::{SceneFile, SweepMethod, SweepSpec};
use super::Scene;
use crate::input::deck::job::DeckJob;
use crate::input::InputError;

/// The tables a deck provides, which a scene with `model` must leave out.
const FROM_THE_DECK: &[&str] = &[
    "materials",
    "bodies",
    "interfaces",
    "ties",
    "preload",
    "screws",
    "clamp",
    "springs",
    "joints",
    "excitation",
    "sweep",
];

fn first_key(p: &KeyPath) -> Option<&str> {
    match p.0.first() {
        Some(Seg::Key(k)) => Some(k),
        _ => None,
    }
}

/// The validation's problems adjusted for `model`: without it, a missing `[sweep]` is
/// named as missing; with it, the checks of tables the deck provides give way to "comes
/// from the deck", and outputs' bodies are the deck's sets (checked when it is built).
pub fn adjust(s: &SceneFile, problems: Vec<Problem>) -> Vec<Problem> {
    let root = KeyPath::root();
    let no_sweep = s.sweep == SweepSpec::default();
    let Some(model) = &s.model else {
        if !no_sweep {
            return problems;
        }
        let mut out: Vec<Problem> = problems
            .into_iter()
            .filter(|(p, _)| first_key(p) != Some("sweep"))
            .collect();
        out.insert(
            0,
            (
                root.key("sweep"),
                "missing: required (or `model` = a deck with a *STEADY STATE DYNAMICS step)".into(),
            ),
        );
        return out;
    };
    let mut out: Vec<Problem> = problems
        .into_iter()
        .filter(|(p, _)| {
            let k = first_key(p);
            // The sweep's route (method, modes, residual) stays the scene's.
            let route = k == Some("sweep")
                && matches!(p.0.get(1), Some(Seg::Key(r)) if ["method", "modes", "residual"].contains(&r.as_str()));
            let deck_table = k.is_some_and(|k| FROM_THE_DECK.contains(&k)) && !route;
            let outputs_body = k == Some("outputs")
                && (p.0.len() == 1 || matches!(p.0.get(2), Some(Seg::Key(b)) if b == "body"));
            !deck_table && !outputs_body
        })
        .collect();
    let given = [
        ("materials", !s.materials.is_empty()),
        ("bodies", !s.bodies.is_empty()),
        ("interfaces", !s.interfaces.is_empty()),
        ("ties", !s.ties.is_empty()),
        ("preload", !s.preload.is_empty()),
        ("screws", !s.screws.is_empty()),
        ("clamp", !s.clamp.is_empty()),
        ("springs", !s.springs.is_empty()),
        ("joints", !s.joints.is_empty()),
        ("excitation", !s.excitation.is_empty()),
    ];
    for (key, present) in given {
        if present {
            out.push((
                root.key(key),
                "not allowed with `model`: the deck provides it".into(),
            ));
        }
    }
    if model.trim().is_empty() {
        out.push((root.key("model"), "must name a deck file (.inp)".into()));
    }
    out
}

/// Reads the deck named by the scene's `model` (relative to the scene file `path`) and
/// attaches it: the sweep is the deck's steady-state step (a `[sweep]` of the scene's
/// own is an error), the outputs the deck's node outputs unless the scene names its own.
pub fn attach(scene: &mut Scene, path: &Path) -> Result<(), InputError> {
    let Some(model) = &scene.spec.model else {
        return Ok(());
    };
    // The route of the linear part (method, modes, residual) is the scene's to choose;
    // the frequencies are the deck's.
    let own = &scene.spec.sweep;
    let route_only = SweepSpec {
        method: own.method,
        modes: own.modes,
        residual: own.residual,
        // A `[sweep]` table present reads bias 1 by default, an absent one is default.
        bias: if own.bias == 1.0 { 1.0 } else { 0.0 },
        ..SweepSpec::default()
    };
    if *own != route_only {
        return Err(at_path(
            &scene.file,
            &scene.text,
            &KeyPath::root().key("sweep"),
            "not allowed with `model` but for `method`, `modes` and `residual`: the deck's *STEADY STATE DYNAMICS step gives the frequencies"
                .into(),
        )
        .into());
    }
    let deck_path = path.parent().unwrap_or(Path::new("")).join(model);
    let job = DeckJob::load(&deck_path)?;
    // The scene may ask for the modal route and its modes; a modal deck step stays modal.
    let deck_sweep = job.sweep().unwrap_or_default();
    scene.spec.sweep = SweepSpec {
        method: match route_only.method {
            SweepMethod::Direct => deck_sweep.method,
            m => m,
        },
        modes: route_only.modes.or(deck_sweep.modes),
        residual: route_only.residual.or(deck_sweep.residual),
        ..deck_sweep
    };
    if scene.spec.sweep.method == SweepMethod::Direct
        && (route_only.modes.is_some() || route_only.residual.is_some())
    {
        return Err(at_path(
            &scene.file,
            &scene.text,
            &KeyPath::root().key("sweep"),
            "`modes` and `residual` apply to the modal route, and the deck's steady state is DIRECT: give method = \"modal\"".into(),
        )
        .into());
    }
    if scene.spec.outputs.is_empty() {
        scene.spec.outputs = job.outputs();
    }
    let peaks = scene
        .spec
        .field_output
        .as_ref()
        .is_some_and(|f| f.peaks > 0);
    if peaks && scene.spec.outputs.is_empty() {
        return Err(at_path(
            &scene.file,
            &scene.text,
            &KeyPath::root().key("field_output").key("peaks"),
            "needs an output: the peaks are the first output's, and neither the scene's [[outputs]] nor the deck's *NODE OUTPUT/*NODE PRINT names one".into(),
        )
        .into());
    }
    scene.sources.extend(job.deck.sources.iter().cloned());
    scene.deck = Some(Arc::new(job));
    Ok(())
}

/// The scene of a deck run (`jointlin run DECK.inp`): the deck's model, sweep, node
/// outputs and units, the default `[effects]` and `[iteration]`; `text` (the deck's) is
/// echoed into run.json.
pub fn deck_scene(job: DeckJob, text: String) -> Scene {
    let spec = SceneFile {
        title: job
            .deck
            .heading
            .lines()
            .next()
            .unwrap_or("")
            .trim()
            .to_string(),
        model: Some(job.file.clone()),
        units: job.units.clone(),
        materials: Default::default(),
        bodies: Vec::new(),
        matrices: Vec::new(),
        interfaces: Vec::new(),
        ties: Vec::new(),
        preload: Vec::new(),
        screws: Vec::new(),
        clamp: Vec::new(),
        springs: Vec::new(),
        joints: Vec::new(),
        excitation: Vec::new(),
        sweep: job.sweep().unwrap_or_default(),
        iteration: Default::default(),
        outputs: job.outputs(),
        effects: Default::default(),
        loss_study: None,
        time_domain: None,
        field_output: None,
    };
    Scene {
        file: job.file.clone(),
        text,
        spec,
        sources: job.deck.sources.clone(),
        deck: Some(Arc::new(job)),
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::GOOD;
    use super::*;

    const UNITS: &str = "[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n";

    #[test]
    fn a_scene_without_sweep_names_it_missing() {
        let text = GOOD.replace("[sweep]\nf_min = 100.0\nf_max = 200.0\ncount = 3\n", "");
        assert_ne!(text, GOOD);
        let e = Scene::parse("s.toml", &text).unwrap_err();
        assert_eq!(e.key, "sweep", "{e}");
        assert!(e.message.starts_with("missing: required"), "{e}");
    }

    #[test]
    fn a_model_scene_needs_no_bodies_and_takes_none() {
        let ok = format!("model = \"stack.inp\"\n{UNITS}[effects]\nmaterial_damping = false\n");
        let s = Scene::parse("s.toml", &ok).unwrap();
        assert_eq!(s.spec.model.as_deref(), Some("stack.inp"));
        assert!(
            s.deck.is_none(),
            "input::load attaches the deck, not Scene::parse"
        );
        let bad = format!("{ok}[materials.steel]\nE = 1.0\nnu = 0.3\nrho = 1.0\n");
        let e = Scene::parse("s.toml", &bad).unwrap_err();
        assert_eq!(e.key, "materials", "{e}");
        assert!(e.message.contains("not allowed with `model`"), "{e}");
        let e = Scene::parse("s.toml", &format!("model = \" \"\n{UNITS}")).unwrap_err();
        assert_eq!(e.key, "model", "{e}");
    }
}
