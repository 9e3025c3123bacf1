//! The modal route against the direct one on three-beams-coarse (324 free DOFs, 36
//! contact points, microslip at both resonances): with every mode it is the direct
//! route; with the default band the residual flexibility makes it close, and without it
//! the truncation shows.

use super::*;
use crate::solve::sweep::{run, three_beams_coarse, Options, SweepResult};

fn sweep(linear: LinearRoute) -> SweepResult {
    let (scene, p, stat) = three_beams_coarse();
    let mut opts = Options::from_scene(scene.spec.iteration, scene.spec.effects);
    opts.linear = linear;
    run(&p, &stat, &scene.frequencies(), &opts, &|_, _, _| {}).unwrap()
}

/// Largest relative difference of the first output's amplitude and of the joints'
/// power over the frequencies, every frequency converged in both.
fn largest_difference(a: &SweepResult, b: &SweepResult) -> (f64, f64) {
    assert!(a.converged.iter().chain(&b.converged).all(|&c| c));
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    let mut worst = (0.0f64, 0.0f64);
    for i in 0..a.freqs.len() {
        worst.0 = worst
            .0
            .max(rel(a.outputs[i][0].norm(), b.outputs[i][0].norm()));
        worst.1 = worst.1.max(rel(a.power[i], b.power[i]));
    }
    worst
}

#[test]
fn with_every_mode_the_modal_route_is_the_direct_one() {
    let direct = sweep(LinearRoute::Direct);
    let all = sweep(LinearRoute::Modal {
        modes: ModeChoice::Count(324),
        residual: false,
    });
    assert_eq!(all.modal.as_ref().unwrap().modes, 324);
    let (amp, power) = largest_difference(&all, &direct);
    eprintln!("every mode: {amp:.2e} / {power:.2e}");
    // Measured 3.8e-9 and 1.5e-8: the two routes iterate from different references
    // (the stuck state against each frequency's start estimate) to the same state.
    assert!(amp < 1e-7 && power < 1e-6, "{amp:e} {power:e}");
}

#[test]
fn the_residual_flexibility_makes_a_few_modes_as_good_as_all() {
    let direct = sweep(LinearRoute::Direct);
    let band = ModeChoice::Count(6);
    let with = sweep(LinearRoute::Modal {
        modes: band,
        residual: true,
    });
    let without = sweep(LinearRoute::Modal {
        modes: band,
        residual: false,
    });
    let s = with.modal.as_ref().unwrap();
    assert!(s.modes < 20 && s.residual_flexibility, "{s:?}");
    let (amp_with, power_with) = largest_difference(&with, &direct);
    let (amp_without, power_without) = largest_difference(&without, &direct);
    eprintln!(
        "{} modes: with the residual {amp_with:.2e} / {power_with:.2e}, without {amp_without:.2e} / {power_without:.2e}",
        s.modes
    );
    // Measured: 6 modes (below 18 kHz), with the residual and its inertia term 2.2e-5 /
    // 9.0e-5 (the static residual alone gave 2.0e-3 / 2.1e-3, largest at the
    // antiresonance near 5 kHz), without it 2.6e-1 / 1.1e-1.
    assert!(
        amp_with < 1e-4 && power_with < 3e-4,
        "{amp_with:e} {power_with:e}"
    );
    assert!(
        amp_without > 10.0 * amp_with,
        "{amp_without:e} vs {amp_with:e}"
    );
}

#[test]
fn the_harmonic_balance_condenses_through_the_same_modes() {
    let (scene, p, stat) = three_beams_coarse();
    let freqs = [1150.0, 1170.0, 1180.0, 1200.0, 7250.0];
    let mut opts = Options::from_scene(scene.spec.iteration, scene.spec.effects);
    opts.iteration.mode = crate::input::scene::Mode::HarmonicBalance;
    opts.iteration.harmonics = Some(3);
    let direct = run(&p, &stat, &freqs, &opts, &|_, _, _| {}).unwrap();
    // The band must hold the third harmonic of the top frequency.
    opts.linear = LinearRoute::Modal {
        modes: ModeChoice::Below(2.0 * 3.0 * 7250.0),
        residual: true,
    };
    let modal = run(&p, &stat, &freqs, &opts, &|_, _, _| {}).unwrap();
    assert_eq!(modal.factorizations, 0);
    let (amp, power) = largest_difference(&modal, &direct);
    eprintln!(
        "H = 3, {} modes: {amp:.2e} / {power:.2e}",
        modal.modal.as_ref().unwrap().modes
    );
    // Measured 9 modes (below 43.5 kHz): 9.5e-6 / 3.5e-6; the whole 100-frequency sweep
    // with its default band (11 modes) 1.2e-6 / 2.4e-6.
    assert!(amp < 3e-5 && power < 3e-5, "{amp:e} {power:e}");
}
