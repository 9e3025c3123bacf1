//! Regressions of the lumped harmonic balance (harness/src/mhb) on a 3-DOF Jenkins
//! chain: M = I, K tridiagonal (2, −1), D = 0.02 K, Jenkins elements (k_T0 = 20,
//! μF_N = 1) from DOF 1 to ground and between DOFs 1 and 2, force 3 cos Ωt on DOF 2.

#![allow(clippy::needless_range_loop)]

use jointlin_harness::capi::Tangential;
use jointlin_harness::mhb::continuation::{trace, Options};
use jointlin_harness::mhb::{
    default_samples, first_order, Element, Hb, Law, NewtonOptions, System,
};
use jointlin_harness::names::{LawName, RuleName};
use nalgebra::{Complex, DMatrix};

fn chain(force: f64) -> System {
    let k = DMatrix::from_row_slice(3, 3, &[2.0, -1.0, 0.0, -1.0, 2.0, -1.0, 0.0, -1.0, 2.0]);
    let jen = Law::Point(Tangential {
        law: LawName::Jenkins,
        rule: RuleName::Masing,
        mu: 1.0,
        normal: 1.0,
        k_t0: 20.0,
    });
    let z = Complex::new(0.0, 0.0);
    System {
        m: DMatrix::identity(3, 3),
        d: &k * 0.02,
        k,
        f0: vec![0.0; 3],
        f1: vec![z, Complex::new(force, 0.0), z],
        elements: vec![
            Element {
                i: 0,
                j: None,
                law: jen,
            },
            Element {
                i: 0,
                j: Some(1),
                law: jen,
            },
        ],
    }
}

#[test]
fn continuation_does_not_turn_back_without_a_fold() {
    // H = 1, N = 64. With a maximum step of 0.5 the corrector used to land on the branch
    // behind the predictor near Ω = 1.52, the tangent turned, and the trace walked into
    // negative Ω reporting 61 folds. The branch has no fold (first order: one solution
    // per Ω, checked below at the points), so Ω must rise monotonically to the end.
    let sys = chain(3.0);
    for (start, step_max) in [(0.2, 0.5), (0.2, 1.0), (1.0, 0.5), (1.0, 1.0)] {
        let mut hb = Hb::new(&sys, 1, 64);
        let u0 = hb.stuck_start(start);
        let opt = Options {
            omega_start: start,
            omega_end: 2.1,
            step: 0.05,
            step_min: 1e-6,
            step_max,
            max_points: 2000,
            rtol: 1e-9,
        };
        let br = trace(&mut hb, &u0, opt).unwrap();
        assert!(
            br.folds.is_empty(),
            "{start} {step_max}: folds {:?}",
            br.folds
        );
        assert!(br.points.last().unwrap().sol.omega >= 2.1);
        for p in br.points.windows(2) {
            assert!(
                p[1].sol.omega > p[0].sol.omega,
                "{start} {step_max}: Ω turns back"
            );
        }
        // One solution per Ω: at every tenth point, Newton started elsewhere (the stuck
        // linear response, and the point's motion scaled by 0.3 and by 3) finds the
        // point's amplitude again.
        for p in br.points.iter().step_by(10) {
            let w = p.sol.omega;
            let a = hb.amplitude(&p.sol.u, 1);
            let scaled = |f: f64| p.sol.u.iter().map(|v| v * f).collect::<Vec<f64>>();
            for (start, u) in [
                ("stuck", hb.stuck_start(w)),
                ("0.3×", scaled(0.3)),
                ("3×", scaled(3.0)),
            ] {
                let s = hb
                    .solve(&u, w, NewtonOptions::default())
                    .unwrap_or_else(|e| panic!("Ω {w} from {start}: {e}"));
                let e = hb.amplitude(&s.u, 1) / a - 1.0;
                assert!(
                    e.abs() < 1e-6,
                    "Ω {w} from {start}: another solution ({e:e})"
                );
            }
        }
    }
}

#[test]
fn first_order_converges_through_the_stick_slip_transition() {
    // The thesis's relaxation stalled at these Ω (factor halved to 4e-16, mismatch 0.155).
    // The converged first-order response is checked against the H = 1 harmonic balance
    // of the actual loop started from it (N = 512: they differ by the sampling of the
    // loop's kinks only, measured ≤ 4.4e-5).
    let sys = chain(3.0);
    for w in [0.2, 0.5, 1.0, 1.1, 1.2, 1.214, 1.2209, 1.5, 2.0] {
        let x = first_order::solve(&sys, w, &[0.1, 0.1]).unwrap();
        let mut hb = Hb::new(&sys, 1, 512);
        let mut u0 = vec![0.0; hb.size()];
        for d in 0..3 {
            u0[d * 3 + 1] = x[d].re;
            u0[d * 3 + 2] = -x[d].im;
        }
        let s = hb.solve(&u0, w, NewtonOptions::default()).unwrap();
        for d in 0..3 {
            let e = hb.amplitude(&s.u, d) / x[d].norm() - 1.0;
            assert!(e.abs() < 2e-4, "Ω {w}, DOF {d}: {e:e}");
        }
    }
}

#[test]
fn stuck_start_is_the_solution_while_the_contacts_stick() {
    // Force 0.05: the stuck response stays below the slip limit δ* = μF_N/k_T0 = 0.05 at
    // these Ω, so the stuck linear start solves the harmonic balance exactly; the start
    // without contacts does not (it misses the stiffness 20 per element).
    let sys = chain(0.05);
    for h in [1usize, 3] {
        let mut hb = Hb::new(&sys, h, default_samples(h));
        let f = hb.load().norm();
        for w in [0.5, 1.0, 2.5] {
            let stuck = hb.stuck_start(w);
            let r = hb.eval(&stuck, w).unwrap().r.norm() / f;
            assert!(r < 1e-12, "H {h}, Ω {w}: stuck start residual {r:e}");
            let free = hb.linear_start(w);
            let r = hb.eval(&free, w).unwrap().r.norm() / f;
            assert!(r > 0.1, "H {h}, Ω {w}: free start residual {r:e}");
        }
    }
}
