//! Arbitrary bytes as an Abaqus-format deck through the harness's deck path: the
//! reader (keywords and parameters against the implemented table, sets, surfaces,
//! steps), the `jointlin check` summary with its pairing, the run's reading of the deck
//! (units, steps, property tables, size estimate), and for small decks the sweep's
//! frequencies and the model build. Properties: no panic, abort or hang; every error
//! names a line within the text; frequencies finite and non-negative.
//!
//! Texts that name a file (`INPUT=`) are skipped: a fuzzer would find /dev/zero and read
//! a GiB per input (that path is tested in harness/tests/deck_as_written.rs).

#![cfg_attr(not(feature = "replay"), no_main)]

#[path = "../src/common.rs"]
mod common;

#[cfg(feature = "replay")]
use common::replay_main;
use common::{assert_line_within, text_input};
use jointlin_harness::input::deck::job::DeckJob;
use jointlin_harness::input::deck::{self, summary};
use jointlin_harness::input::scene::model_file::deck_scene;

/// Largest model built per input (DOFs of the deck's nodes): keeps each run short.
const MAX_BUILD_DOFS: usize = 3000;
/// Most frequencies listed per input.
const MAX_FREQUENCIES: usize = 100_000;

fn run(data: &[u8]) {
    let Some(text) = text_input(data) else {
        return;
    };
    if text.to_ascii_uppercase().contains("INPUT") {
        return;
    }
    let (d, warnings) = match deck::read_str(text, "fuzz.inp", std::path::Path::new("/nonexistent"))
    {
        Ok(r) => r,
        Err(e) => return assert_line_within(text, e.line, &e),
    };
    if let Err(e) = summary::summary(&d, "fuzz.inp", "1/time") {
        assert_line_within(text, e.line, &e);
    }
    let job = match DeckJob::new("fuzz.inp".into(), text, d, warnings) {
        Ok(j) => j,
        Err(e) => return assert_line_within(text, e.line, &e),
    };
    let count: usize = job.sweep().map_or(0, |s| {
        s.count + s.refine.iter().map(|b| b.count).sum::<usize>()
    });
    let small = 3 * job.deck.nodes.len() <= MAX_BUILD_DOFS && count <= MAX_FREQUENCIES;
    if small {
        let scene = deck_scene(job, text.to_string());
        let f = scene.frequencies();
        assert!(f.iter().all(|x| x.is_finite() && *x >= 0.0), "{f:?}");
        let _ = jointlin_harness::model::build(&scene);
    }
}

#[cfg(not(feature = "replay"))]
libfuzzer_sys::fuzz_target!(|data: &[u8]| run(data));

#[cfg(feature = "replay")]
fn main() {
    replay_main(run);
}
