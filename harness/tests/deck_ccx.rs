//! The deck path against CalculiX on the non-conforming three-layer stack
//! (validate::deck_ccx, validate::stack_deck: three 100 × 10 × 2 mm steel plates, C3D20
//! meshes of 10×2, 13×3 and 16×2 elements, clamped at x = 0). Measured (ours/ccx − 1):
//! `*TIE` modes 1–4 (all bending) −9e-7 … −3e-8; `*CONTACT PAIR` stuck (μ = 1e3,
//! k_T0 = k_N = 1e9 N/mm³) first bending −2.6e-4, modes 2–4 ≥ −1.3e-3; k_T0 = 1e-3 N/mm³
//! (sliding) first bending 169.68 Hz against ccx's one layer 170.08 Hz (−2.4e-3), a
//! third of the tied stack's 504.24 Hz as three identical layers sliding freely give.
//!
//! Skipped with a printed reason where ccx is missing, except under CI=true.

#[path = "../../tests/tools/mod.rs"]
mod tools;

use jointlin_harness::validate::ccx::ccx_missing;
use jointlin_harness::validate::deck_ccx::{comparison, MODES};

#[test]
fn tied_stuck_and_sliding_stacks_against_ccx() {
    if let Some(why) = ccx_missing() {
        tools::missing("deck_ccx", "ccx", &why);
        return;
    }
    let dir = std::env::temp_dir().join(format!("jointlin-deck-ccx-{}", std::process::id()));
    let c = comparison(&dir).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    eprintln!("{}", c.markdown());
    let d = |a: f64, b: f64| (a / b - 1.0).abs();
    // (a) *TIE against ccx's *TIE: the first bending modes (1–4) within 0.1 %.
    for i in 0..MODES {
        assert!(d(c.tie[i], c.ccx_tie[i]) < 1e-3, "mode {}: {c:?}", i + 1);
    }
    // (b) contact stuck: the first bending resonance within 0.5 % of the tied stack.
    assert!(d(c.stuck[0], c.ccx_tie[0]) < 5e-3, "{c:?}");
    // (c) k_T0 → 0: the layers bend each about its own axis, as one layer does (1 %),
    // a third of the tied stack's frequency (EI 27× and mass 3× of one layer's).
    assert!(d(c.sliding[0], c.ccx_single[0]) < 1e-2, "{c:?}");
    assert!(d(c.ccx_tie[0] / c.sliding[0], 3.0) < 2e-2, "{c:?}");
}
