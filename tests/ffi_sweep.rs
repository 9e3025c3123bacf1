//! A whole multi-pass frequency sweep through the C ABI, driven exactly as Abaqus would:
//! every pass is an "analysis" (LOP 0 … 3) with a static general step (LINPER = 0) and a
//! steady-state step (LINPER = 1) whose KINC restart at 1 for the re-run frequencies. The
//! tiny host couples two contact points through a spring and solves its own 2×2 complex
//! system per frequency with the k*, d* that jointlin_uinter hands it (thesis §4.3.2).

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::store::*;
use jointlin::hysteresis::Rule;
use jointlin::law::TangentialLaw;
use jointlin::linearize::{linearize, Contact, Method};
use std::f64::consts::PI;

const FREQS: [f64; 3] = [1.5, 3.0, 4.0];
const MASS: f64 = 1.0;
const COUPLING: f64 = 400.0;
const FORCE: f64 = 0.25;
const AREA: [f64; 2] = [1.0, 0.8];
/// Overclosures of the static step: pressures 2.0 and 1.5 with k_N = 1e4.
const OVERCLOSURE: [f64; 2] = [2e-4, 1.5e-4];
const RTOL: f64 = 1e-6;

/// |x| of m ẍ + (k + i ω d) x + coupling = F e^{iωt} for two masses, each on its own
/// contact (k, d in force units), mass 1 driven: x = Z⁻¹ (F, 0).
fn solve(omega: f64, k: [f64; 2], d: [f64; 2]) -> [f64; 2] {
    type C = (f64, f64);
    let mul = |a: C, b: C| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let div = |a: C, b: C| {
        let n = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / n, (a.1 * b.0 - a.0 * b.1) / n)
    };
    let z11 = (k[0] + COUPLING - MASS * omega * omega, omega * d[0]);
    let z22 = (k[1] + COUPLING - MASS * omega * omega, omega * d[1]);
    let z12 = (-COUPLING, 0.0);
    let zz = mul(z11, z22);
    let z12sq = mul(z12, z12);
    let det = (zz.0 - z12sq.0, zz.1 - z12sq.1);
    // Cramer: x1 = F z22 / det, x2 = −z12 F / det.
    let x1 = div(mul((FORCE, 0.0), z22), det);
    let x2 = div(mul((-z12.0 * FORCE, 0.0), (1.0, 0.0)), det);
    [x1.0.hypot(x1.1), x2.0.hypot(x2.1)]
}

struct Host {
    store: *mut jointlin_store,
    points: [Uinter; 2],
}

impl Host {
    fn new(store: *mut jointlin_store) -> Self {
        let points = [0, 1].map(|p| {
            let mut u = Uinter::new(block_props(), 2);
            u.coords = [p as f64, 0.0, 0.0];
            u.node = 0; // surface-to-surface: NODE is 0 for both
            u.area = AREA[p];
            u
        });
        Self { store, points }
    }

    /// One analysis: static step, then the steady-state step over `freqs`. Returns the
    /// (estimate, computed) amplitude pairs per frequency and point.
    fn analysis(&mut self, freqs: &[f64]) -> Vec<[(f64, f64); 2]> {
        let s = self.store;
        assert_eq!(uexternaldb(s, 0, 0, 0, 0), 0);
        // Step 1, static: a new job starts from fresh STATEV.
        assert_eq!(uexternaldb(s, 5, 0, 1, 0), 0);
        assert_eq!(uexternaldb(s, 1, 0, 1, 1), 0);
        for (p, u) in self.points.iter_mut().enumerate() {
            u.statev.fill(0.0);
            u.rdisp = [0.0; 3];
            u.kstep = 1;
            assert_eq!(u.step_to([OVERCLOSURE[p], 0.0, 0.0]), 0);
            assert_eq!(u.lopenclose, 1);
        }
        assert_eq!(uexternaldb(s, 2, 0, 1, 1), 0);
        assert_eq!(uexternaldb(s, 6, 0, 1, 1), 0);
        // Step 2, steady state: KINC = 1..m.
        assert_eq!(uexternaldb(s, 5, 0, 2, 0), 0);
        let mut out = Vec::new();
        for (i, &f) in freqs.iter().enumerate() {
            let kinc = i as i32 + 1;
            assert_eq!(uexternaldb(s, 1, 0, 2, kinc), 0);
            let (mut k, mut d, mut a, mut ids) = ([0.0; 2], [0.0; 2], [0.0; 2], [0; 2]);
            for (p, u) in self.points.iter_mut().enumerate() {
                u.linper = 1;
                u.kstep = 2;
                u.kinc = kinc;
                u.freqr = f;
                assert_eq!(u.call(s), 0);
                k[p] = u.ddsddr[3] * u.area;
                d[p] = u.dviscous[3] * u.area;
                a[p] = u.report.amplitude[0];
                ids[p] = u.report.point;
            }
            let x = solve(2.0 * PI * f, k, d);
            for p in 0..2 {
                let amp = [x[p], 0.0];
                assert_eq!(
                    unsafe { jointlin_store_report(s, ids[p], kinc, amp.as_ptr()) },
                    0
                );
            }
            out.push([(a[0], x[0]), (a[1], x[1])]);
            assert_eq!(uexternaldb(s, 2, 1, 2, kinc), 0); // LRESTART = 1: restart file
        }
        assert_eq!(uexternaldb(s, 6, 0, 2, 0), 0);
        assert_eq!(uexternaldb(s, 3, 0, 2, 0), 0);
        out
    }
}

fn store_with_restart(path: &std::path::Path) -> *mut jointlin_store {
    let bytes = path.as_os_str().as_encoded_bytes();
    unsafe {
        let mut cfg = std::mem::zeroed::<jointlin_store_config>();
        assert_eq!(jointlin_store_config_default(&mut cfg), 0);
        cfg.initial_amplitude = 1e-4;
        cfg.rtol = RTOL;
        cfg.sweep_step = 2;
        cfg.kinc_numbering = JOINTLIN_KINC_SEQUENTIAL;
        cfg.restart_path = bytes.as_ptr().cast();
        cfg.restart_path_len = bytes.len();
        let mut store = std::ptr::null_mut();
        assert_eq!(jointlin_store_new(&cfg, &mut store), 0);
        store
    }
}

#[test]
fn two_points_three_frequencies_converge_over_passes_through_uexternaldb() {
    let dir = std::env::temp_dir().join(format!("jointlin-sweep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("store.restart");
    let store = store_with_restart(&path);
    let mut host = Host::new(store);
    let mut per_pass = Vec::new();
    let mut last = Vec::new();
    loop {
        let (action, pass) = next_action(store);
        let list: Vec<i32> = match action {
            JOINTLIN_ACTION_RUN_SWEEP => vec![1, 2, 3],
            JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL => increments(store),
            JOINTLIN_ACTION_DONE => break,
            other => panic!("pass {pass}: action {other}"),
        };
        per_pass.push((action, list.len()));
        let freqs: Vec<f64> = list.iter().map(|&k| FREQS[k as usize - 1]).collect();
        last = host.analysis(&freqs);
        assert!(per_pass.len() < 15, "no convergence: {per_pass:?}");
    }
    // Fig. 4.33-style log: frequencies per analysis.
    eprintln!("frequencies per pass: {per_pass:?}");
    let (_, passes) = next_action(store);
    assert_eq!(passes as usize, per_pass.len());
    assert!(
        passes >= 3,
        "pass 1, at least one re-run, the final: {per_pass:?}"
    );
    assert_eq!(per_pass[0], (JOINTLIN_ACTION_RUN_SWEEP, 3));
    assert_eq!(*per_pass.last().unwrap(), (JOINTLIN_ACTION_RUN_FINAL, 3));
    let stats = |n: i32| {
        let mut s = jointlin_pass_stats::default();
        assert_eq!(unsafe { jointlin_store_pass_stats(store, n, &mut s) }, 0);
        s
    };
    assert_eq!((stats(1).increments_run, stats(1).evaluations), (3, 6));
    let fin = stats(passes);
    assert_eq!(
        (fin.kind, fin.increments_run, fin.increments_converged),
        (2, 3, 3)
    );
    // The final pass is self-consistent to the tolerance …
    for (f, pair) in FREQS.iter().zip(&last) {
        for &(a, a_star) in pair {
            assert!(
                (a - a_star).abs() <= RTOL * a.max(a_star),
                "{f} Hz: {a} vs {a_star}"
            );
        }
    }
    // … and, checked independently of the store with the core linearization, its
    // amplitudes are a fixed point of the host's 2×2 system (rtol 1e-6 on a map with
    // derivative well below 1 leaves < 1e-5 relative).
    for (f, pair) in FREQS.iter().zip(&last) {
        let omega = 2.0 * PI * f;
        let (mut k, mut d) = ([0.0; 2], [0.0; 2]);
        for p in 0..2 {
            let c = Contact {
                law: TangentialLaw::Mindlin,
                rule: Rule::Thesis,
                mu: 0.3,
                normal_force: 1e4 * OVERCLOSURE[p],
                k_t0: 1282.7,
            };
            let l = linearize(&c, pair[p].0, omega, Method::default()).unwrap();
            k[p] = l.k_star * AREA[p];
            d[p] = l.d_star * AREA[p];
            assert!(
                l.amplitude_ratio > 0.05,
                "{f} Hz: nonlinear regime expected"
            );
        }
        let x = solve(omega, k, d);
        for p in 0..2 {
            assert!((x[p] / pair[p].0 - 1.0).abs() < 1e-5, "{f} Hz point {p}");
        }
    }
    // The restart file written at LOP 2/3 restores the same state in another store.
    let again = store_with_restart(&path);
    assert_eq!(unsafe { jointlin_store_restore(again) }, 0);
    assert_eq!(next_action(again), next_action(store));
    for id in 1..=2 {
        for kinc in 1..=3 {
            let (mut s1, mut s2) = Default::default();
            unsafe {
                assert_eq!(jointlin_store_point_status(store, id, kinc, &mut s1), 0);
                assert_eq!(jointlin_store_point_status(again, id, kinc, &mut s2), 0);
            }
            assert_eq!(s1, s2);
            let s1: jointlin_point_status = s1;
            assert_eq!((s1.converged, s1.directions), (1, 1));
        }
    }
    unsafe {
        jointlin_store_free(store);
        jointlin_store_free(again);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
