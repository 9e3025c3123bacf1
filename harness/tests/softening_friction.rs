//! The softening friction oscillator with folds (
//! scenes/softening-friction.toml): a Mindlin contact to ground on a mass whose support
//! softens (cubic α < 0). Sweeps up and down through `jointlin run`'s engine jump at the
//! folds of an independent first-order residual scan (validate::softening); continuation
//! of the harmonic balance passes both folds and marks the branch between them unstable;
//! RK4 confirms the stable branches and leaves the unstable one.

use jointlin_harness::input::scene::Scene;
use jointlin_harness::run::{run, Extras};
use jointlin_harness::solve::sweep::SweepResult;
use jointlin_harness::validate::softening::{continuation, time_domain, SofteningFriction};

const TWO_PI: f64 = 2.0 * std::f64::consts::PI;
/// ω grid of the fold scan (rad/s).
const SCAN_STEP: f64 = 1e-3;

/// The scan's folds (lower, upper).
fn scan_folds() -> (f64, f64) {
    SofteningFriction::scene()
        .first_order_folds(9.0, 10.5, SCAN_STEP)
        .unwrap()
        .expect("three first-order amplitudes somewhere")
}

/// (ω, amplitude, joint power) in the order run.
fn curve(r: &SweepResult) -> Vec<(f64, f64, f64)> {
    (0..r.freqs.len())
        .map(|i| (TWO_PI * r.freqs[i], r.outputs[i][0].norm(), r.power[i]))
        .collect()
}

/// Index j of the jump (amplitude ratio beyond e^0.3) between points j and j + 1.
fn jump(c: &[(f64, f64, f64)]) -> usize {
    let j: Vec<usize> = (0..c.len() - 1)
        .filter(|&i| (c[i + 1].1 / c[i].1).ln().abs() > 0.3)
        .collect();
    assert_eq!(j.len(), 1, "one jump per sweep: {j:?}");
    j[0]
}

#[test]
fn sweeps_up_and_down_jump_at_the_scanned_folds() {
    let (lo, hi) = scan_folds();
    // Measured 9.511 and 9.838 rad/s.
    assert!(hi - lo > 0.2, "{lo} {hi}");
    let p = format!(
        "{}/../scenes/softening-friction.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let s = Scene::load(std::path::Path::new(&p)).unwrap();
    let r = run(&s, Extras::default(), &|_, _, _| {}).unwrap();
    let down = r.down.as_ref().expect("direction = up_down");
    assert!(r.main.converged.iter().all(|&c| c));
    assert!(down.converged.iter().all(|&c| c));
    let sf = SofteningFriction::scene();
    let dstar = 1.5 * 0.5 * 0.2 / 100.0;
    for (name, sw) in [("up", &r.main), ("down", down)] {
        let c = curve(sw);
        // Every amplitude is a first-order solution: measured |g|/F ≤ 2e-7 (amplitude
        // tolerance 1e-7 of the scene); 1e-5 allows for flat residuals next to a fold.
        for &(w, a, _) in c.iter() {
            let g = sf.residual(a, w).unwrap();
            assert!(g.abs() < 1e-5, "{name} ω {w}: A {a}, g/F {g:e}");
        }
        // The contact dissipates on both branches, and slips: A/δ* > 1 everywhere
        // (microslip/slip on the low branch, ~75 δ* on the resonant one).
        for (i, &(w, a, power)) in c.iter().enumerate() {
            assert!(power > 0.0, "{name} ω {w}: power {power}");
            let ratio = sw.points[i][0].ratio[0];
            assert!(
                ratio > 1.0 && (ratio * dstar / a - 1.0).abs() < 1e-6,
                "{name} ω {w}: {ratio}"
            );
        }
    }
    let up = curve(&r.main);
    let mut dn = curve(down);
    dn.reverse();
    // Up: the low branch until the upper fold, then up onto the resonant branch; down:
    // the resonant branch until the lower fold, then down. Each jump lies between the
    // two frequencies that bracket its fold (± the scan's grid).
    let (i, j) = (jump(&up), jump(&dn));
    let (a, b) = (up[i], up[i + 1]);
    assert!(
        b.1 > a.1 && a.0 - SCAN_STEP <= hi && hi <= b.0 + SCAN_STEP,
        "up {a:?} {b:?} vs {hi}"
    );
    let (a, b) = (dn[j], dn[j + 1]);
    assert!(
        b.1 < a.1 && b.0 - SCAN_STEP <= lo && lo <= a.0 + SCAN_STEP,
        "down {a:?} {b:?} vs {lo}"
    );
    // Between the folds the two sweeps sit on different branches, both dissipating;
    // the resonant branch more (measured ~15×).
    let mid = up.iter().position(|p| p.0 > 0.5 * (lo + hi)).unwrap();
    let (u, d) = (up[mid], curve(down)[mid]);
    assert!((u.0 - d.0).abs() < 1e-12);
    assert!(d.1 > 3.0 * u.1 && d.2 > 3.0 * u.2, "{u:?} {d:?}");
    // Bounded: the resonant branch stays below half the support's stability limit
    // √(k/|α|) (measured 0.114 m against 0.158 m).
    let top = dn.iter().fold(0.0f64, |m, p| m.max(p.1));
    assert!(top < sf.amplitude_bound(), "{top}");
}

#[test]
fn continuation_passes_both_folds_and_rk4_confirms_the_branches() {
    let (lo, hi) = scan_folds();
    let sys = SofteningFriction::scene().system();
    for h in [1usize, 3] {
        let (hb, br) = continuation(&sys, h, 8.5, 11.0).unwrap();
        assert!(br.points.last().unwrap().sol.omega >= 11.0);
        // Passed in order: upper fold (turning back), lower fold.
        assert_eq!(br.folds.len(), 2, "H {h}: {:?}", br.folds);
        let (f_hi, f_lo) = (br.folds[0], br.folds[1]);
        eprintln!(
            "H = {h}: folds {f_lo:.4} {f_hi:.4} (scan {lo} {hi}), {} points",
            br.points.len()
        );
        // H = 1 is the first-order balance: measured 1.4e-3 and 0.8e-3 from the scan,
        // whose first/last grid point with three roots lies up to one grid step (1e-3)
        // inside the fold, plus roots merging between its 4000 amplitudes. H = 3: the
        // higher harmonics move the folds by measured 1e-2 and 5e-4 rad/s.
        let tol = if h == 1 { 3e-3 } else { 2e-2 };
        assert!((f_lo - lo).abs() < tol && (f_hi - hi).abs() < tol, "H {h}");
        // Unstable: exactly the stretch between the folds.
        let unstable: Vec<f64> = br
            .points
            .iter()
            .filter(|q| !q.stable)
            .map(|q| q.sol.omega)
            .collect();
        assert!(unstable.len() > 10);
        assert!(unstable
            .iter()
            .all(|&w| w >= f_lo - 1e-6 && w <= f_hi + 1e-6));
        if h != 3 {
            continue;
        }
        // RK4 (1024 steps per period, periodic to 1e-9) from H = 3 solutions at ω = 9.7:
        // the stable ones stay (measured 3.5e-4 on the resonant branch, 2.8e-3 on the low
        // one, where the loop's higher harmonics beyond H = 3 matter more); the unstable
        // one, perturbed by 1 %, leaves (> 5 %).
        let at = |stable: bool| {
            let mut v: Vec<_> = br
                .points
                .windows(2)
                .filter(|q| {
                    q[0].stable == stable && (q[0].sol.omega - 9.7) * (q[1].sol.omega - 9.7) <= 0.0
                })
                .map(|q| q[0].clone())
                .collect();
            v.sort_by(|a, b| {
                hb.amplitude(&a.sol.u, 0)
                    .total_cmp(&hb.amplitude(&b.sol.u, 0))
            });
            v
        };
        let stable = at(true);
        assert_eq!(stable.len(), 2);
        for (q, tol) in stable.iter().zip([5e-3, 1e-3]) {
            let a = hb.amplitude(&q.sol.u, 0);
            let td = time_domain(&sys, &hb, &q.sol.u, q.sol.omega).unwrap();
            eprintln!("ω {:.4}: H = 3 {a:.6e}, RK4 {td:.6e}", q.sol.omega);
            assert!((a / td - 1.0).abs() < tol, "ω {}: {a} vs {td}", q.sol.omega);
        }
        let mid = &at(false)[0];
        let u: Vec<f64> = mid.sol.u.iter().map(|v| 1.01 * v).collect();
        let a = hb.amplitude(&mid.sol.u, 0);
        let td = time_domain(&sys, &hb, &u, mid.sol.omega).unwrap();
        eprintln!(
            "unstable ω {:.4}: H = 3 {a:.6e}, RK4 {td:.6e}",
            mid.sol.omega
        );
        assert!((td / a - 1.0).abs() > 0.05, "{a} vs {td}");
    }
}

#[test]
fn thesis_mode_sweeps_jump_within_one_step_of_the_folds() {
    // The UEXTERNALDB multi-pass scheme on the same scene: it stays on the resonant
    // branch sweeping down (unlike Duffing's, docs/robustness.md) and drops one step
    // earlier than fast mode (measured 9.519 → 9.513 rad/s against the fold 9.511,
    // after 15 re-run passes); the sweep up jumps where fast mode does. Asserted: each
    // jump's midpoint within one sweep step of its scanned fold.
    let (lo, hi) = scan_folds();
    let p = format!(
        "{}/../scenes/softening-friction.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut s = Scene::load(std::path::Path::new(&p)).unwrap();
    s.spec.iteration.mode = jointlin_harness::input::scene::Mode::Thesis;
    let step = TWO_PI * (s.spec.sweep.f_max - s.spec.sweep.f_min) / (s.spec.sweep.count - 1) as f64;
    let r = run(&s, Extras::default(), &|_, _, _| {}).unwrap();
    let down = r.down.as_ref().expect("direction = up_down");
    assert!(r.main.converged.iter().all(|&c| c));
    assert!(down.converged.iter().all(|&c| c));
    let up = curve(&r.main);
    let mut dn = curve(down);
    dn.reverse();
    for (name, c, fold, rises) in [("up", &up, hi, true), ("down", &dn, lo, false)] {
        let i = jump(c);
        let (a, b) = (c[i], c[i + 1]);
        let mid = 0.5 * (a.0 + b.0);
        assert!(
            (b.1 > a.1) == rises && (mid - fold).abs() <= step,
            "{name}: {a:?} {b:?} vs {fold}"
        );
    }
}
