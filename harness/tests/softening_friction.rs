//! The softening friction oscillator with folds (issue 7 item 2,
//! scenes/softening-friction.toml): a Mindlin contact to ground on a mass whose support
//! softens (cubic α < 0). Sweeps up and down through `jointlin run`'s engine jump at the
//! folds of an independent first-order residual scan (validate::softening); continuation
//! of the harmonic balance passes both folds and marks the branch between them unstable;
//! RK4 confirms the stable branches.

use jointlin_harness::run::{run, Extras};
use jointlin_harness::scene::Scene;
use jointlin_harness::validate::softening::{continuation, time_domain, SofteningFriction};

const TWO_PI: f64 = 2.0 * std::f64::consts::PI;

/// The scan's folds (lower, upper), ω steps of 1e-3 rad/s.
fn scan_folds() -> (f64, f64) {
    SofteningFriction::scene()
        .first_order_folds(9.0, 10.5, 1e-3)
        .unwrap()
        .expect("three first-order amplitudes somewhere")
}

#[test]
fn sweeps_up_and_down_jump_at_the_scanned_folds() {
    let (lo, hi) = scan_folds();
    eprintln!("scan folds {lo} {hi}");
    let p = format!(
        "{}/../scenes/softening-friction.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let s = Scene::load(std::path::Path::new(&p)).unwrap();
    let r = run(&s, Extras::default(), &|_, _, _| {}).unwrap();
    let down = r.down.as_ref().expect("direction = up_down");
    let step = TWO_PI * (s.spec.sweep.f_max - s.spec.sweep.f_min) / (s.spec.sweep.count - 1) as f64;
    // (ω, amplitude, power, converged) in the order run.
    let curve = |r: &jointlin_harness::solve::sweep::SweepResult| -> Vec<(f64, f64, f64, bool)> {
        (0..r.freqs.len())
            .map(|i| (TWO_PI * r.freqs[i], r.outputs[i][0].norm(), r.power[i], r.converged[i]))
            .collect()
    };
    let up = curve(&r.main);
    let mut dn = curve(down);
    dn.reverse();
    let jump = |c: &[(f64, f64, f64, bool)]| {
        c.windows(2)
            .position(|p| (p[1].1 / p[0].1).ln().abs() > 1.0)
            .expect("a jump")
    };
    for (name, c) in [("up", &up), ("down", &dn)] {
        let j = jump(c);
        eprintln!("{name}: {:?}", &c[j.saturating_sub(3)..j + 3]);
        let bad: Vec<f64> = c.iter().filter(|p| !p.3).map(|p| p.0).collect();
        eprintln!("{name} not converged at {bad:?}");
    }
}

#[test]
fn continuation_passes_both_folds_and_rk4_confirms_the_branches() {
    let (lo, hi) = scan_folds();
    let p = SofteningFriction::scene();
    let sys = p.system();
    for h in [1usize, 3] {
        let (hb, br) = continuation(&sys, h, 8.5, 11.0).unwrap();
        eprintln!("H {h}: folds {:?}, {} points, scan {lo} {hi}", br.folds, br.points.len());
        let unstable: Vec<f64> = br.points.iter().filter(|q| !q.stable).map(|q| q.sol.omega).collect();
        eprintln!("unstable {} in {:?} {:?}", unstable.len(), unstable.first(), unstable.last());
        if h == 3 {
            for q in br.points.iter().filter(|q| q.stable && (q.sol.omega - 9.7).abs() < 0.003) {
                let a = hb.amplitude(&q.sol.u, 0);
                let td = time_domain(&sys, &hb, &q.sol.u, q.sol.omega).unwrap();
                eprintln!("ω {} a {a} td {td} rel {:e}", q.sol.omega, a / td - 1.0);
            }
        }
    }
}
