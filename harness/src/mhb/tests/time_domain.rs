//! Friction oscillators against the time-domain reference.

use super::*;

#[test]
fn jenkins_chain_against_time_domain() {
    // 3-DOF chain, two Jenkins elements that stick and slip within a cycle near the first
    // resonance (f = 0.05). Reference: RK4, 512 steps per period, periodic to 1e-7
    // (started from the H = 7 solution to shorten the transient). Measured: first order
    // +30 %, +53 %, +24 % at ω = 0.50, 0.54, 0.58; H = 7 within 1e-3 and H = 15 within
    // 3e-4 (H = 15 vs the reference is the reference's own step error). Asserted: first
    // order and H = 7 at the README's printed digit, H = 15 within 3e-4.
    let sys = jenkins_chain(0.05);
    // H = 7 bounds at the README's printed digit (measured 8.9e-4, 2.7e-4, 1.6e-4).
    // First order at the README's printed percent (measured +29.96 %, +53.23 %, +23.99 %).
    let cases = [(0.50, 1e-3, 0.30), (0.54, 4e-4, 0.53), (0.58, 2.5e-4, 0.24)];
    for (w, h7_tol, fo_printed) in cases {
        let x1 = first_order::solve(&sys, w, &[0.1, 0.1]).unwrap();
        let mut amp = Vec::new();
        let mut u7 = Vec::new();
        for &h in &[7usize, 15] {
            let mut hb = Hb::new(&sys, h, default_samples(h));
            let s = hb
                .solve(&start(h, &x1), w, NewtonOptions::default())
                .unwrap();
            amp.push(hb.amplitude(&s.u, 2));
            if h == 7 {
                u7 = s.u;
            }
        }
        let hb = Hb::new(&sys, 7, 128);
        let (x0, v0) = initial(&hb, &u7, w);
        let td = reference::steady(&sys, w, &x0, &v0, 512, 1e-7, 3000).unwrap();
        let r = td.amplitude[2];
        let fo = x1[2].norm() / r - 1.0;
        assert!((fo - fo_printed).abs() < 5e-3, "ω {w}: first order {fo:e}");
        assert!(
            (amp[0] / r - 1.0).abs() < h7_tol,
            "ω {w}: H=7 {}",
            amp[0] / r - 1.0
        );
        assert!(
            (amp[1] / r - 1.0).abs() < 3e-4,
            "ω {w}: H=15 {}",
            amp[1] / r - 1.0
        );
    }
}

#[test]
fn mindlin_block_against_time_domain() {
    // The block of Appendix C (Masing rule) on a ground spring through its microslip range
    // (ω = 18 ... 25: A/δ* ~ 1 ... 1.6). Reference: RK4, 4096 steps per period (k_T0/m
    // is stiff), periodic to 1e-7. Measured: first order 1.6e-2 at most (ω = 18), H = 7
    // 1.8e-4 at most (README). Asserted: first order within 1.65e-2, H = 7 within 2e-4
    // and at least 5× closer than first order.
    let law = point(LawName::Mindlin, RuleName::Masing, 0.3, 2.0, 1282.7);
    let sys = oscillator(2.0, 0.5, 200.0, Complex::new(0.4, 0.0), law);
    for &w in &[18.0, 22.0, 25.0] {
        let x1 = first_order::solve(&sys, w, &[1e-4]).unwrap();
        let mut hb = Hb::new(&sys, 7, default_samples(7));
        let s = hb
            .solve(&start(7, &x1), w, NewtonOptions::default())
            .unwrap();
        let (x0, v0) = initial(&hb, &s.u, w);
        let td = reference::steady(&sys, w, &x0, &v0, 4096, 1e-7, 3000).unwrap();
        let r = td.amplitude[0];
        let e7 = (hb.amplitude(&s.u, 0) / r - 1.0).abs();
        let e1 = (x1[0].norm() / r - 1.0).abs();
        assert!(e7 < 2e-4, "ω {w}: {e7:e}");
        assert!(e1 < 1.65e-2, "ω {w}: {e1:e}");
        assert!(e1 > 5.0 * e7, "ω {w}: {e1:e} vs {e7:e}");
    }
}
