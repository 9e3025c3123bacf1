//! The harness from Python: the one input path's check of a scene or deck with its
//! overrides (in-process, for errors at `Scene.load`), and the commands of `jointlin`
//! (run by `python -m jointlin` in a child process, see `jointlin/_scene.py`).

use std::path::Path;

use jointlin_harness::input::{self, scene::overrides::Override};
use pyo3::prelude::*;

/// Reads `path` (a scene or an Abaqus-format deck) with the overrides `sets`
/// ("KEY=VALUE") through the harness's input path and checks the scene as `jointlin
/// check` does; returns (file, kind "scene" or "deck"). A bad input raises
/// jointlin.InputError with the CLI's message (file:line:column and key, or a deck's
/// file:line and keyword).
#[pyfunction]
pub fn check_input(py: Python<'_>, path: &str, sets: Vec<String>) -> PyResult<(String, String)> {
    let input_error = |msg: String| -> PyErr {
        match py
            .import("jointlin._errors")
            .and_then(|m| m.getattr("InputError"))
            .and_then(|c| c.call1((msg,)))
        {
            Ok(e) => PyErr::from_value(e),
            Err(e) => e,
        }
    };
    let overrides = sets
        .iter()
        .map(|s| s.parse::<Override>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(input_error)?;
    let loaded = py.detach(|| input::load_with(Path::new(path), &overrides));
    match loaded {
        Ok(i) => {
            let kind = match &i {
                input::Input::Scene(_) => "scene",
                input::Input::Deck(_) => "deck",
            };
            Ok((i.into_scene().file, kind.to_string()))
        }
        Err(e) => Err(input_error(e.to_string())),
    }
}

/// Runs the `jointlin` command line `argv` (program name first) as the program does and
/// returns its exit code (0 done, 1 the run failed, 2 bad input or arguments).
#[pyfunction]
pub fn cli(py: Python<'_>, argv: Vec<String>) -> u8 {
    py.detach(|| jointlin_harness::cli::run_args(argv))
}
