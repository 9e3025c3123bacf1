//! Arbitrary bytes as a scene file through the harness's input path: TOML parse,
//! validation with its file:line:col errors, the size limit, and for small scenes the
//! sweep's frequencies and the model build (mesh, matrices, pairing, contact points).
//! Properties: no panic, abort or hang; every error names a line within the text.

#![cfg_attr(not(feature = "replay"), no_main)]

#[path = "../src/common.rs"]
mod common;

#[cfg(feature = "replay")]
use common::replay_main;
use common::{assert_line_within, text_input};
use jointlin_harness::input::scene::Scene;

/// Largest model built per input (DOFs of the boxes' nodes): keeps each run short.
const MAX_BUILD_DOFS: f64 = 3000.0;
/// Most frequencies listed per input.
const MAX_FREQUENCIES: f64 = 1e5;

fn run(data: &[u8]) {
    let Some(text) = text_input(data) else {
        return;
    };
    let scene = match Scene::parse("fuzz.toml", text) {
        Ok(s) => s,
        Err(e) => return assert_line_within(text, e.line, &e),
    };
    let s = &scene.spec;
    let freqs = s.sweep.count as f64 + s.sweep.refine.iter().map(|b| b.count as f64).sum::<f64>();
    if freqs <= MAX_FREQUENCIES {
        let f = scene.frequencies();
        assert!(f.iter().all(|x| x.is_finite() && *x > 0.0), "{f:?}");
    }
    let dofs: f64 = s
        .bodies
        .iter()
        .filter_map(|b| b.divisions)
        .map(|d| 3.0 * d.iter().map(|&n| n as f64 + 1.0).product::<f64>())
        .sum();
    if dofs <= MAX_BUILD_DOFS {
        let _ = jointlin_harness::model::build(&scene);
    }
}

#[cfg(not(feature = "replay"))]
libfuzzer_sys::fuzz_target!(|data: &[u8]| run(data));

#[cfg(feature = "replay")]
fn main() {
    replay_main(run);
}
