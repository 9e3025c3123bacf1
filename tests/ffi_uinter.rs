//! jointlin_uinter against the safe core: the time-domain cycle of the block (LINPER = 0)
//! equals the Rust hysteresis point, LINPER = 1 returns exactly `linearize`'s k* and d*, and
//! 16 threads sharing one store give the same results as a serial run.

mod ffi_common;

use ffi_common::*;
use jointlin::ffi::error::*;
use jointlin::ffi::store::*;
use jointlin::hysteresis::{Point, PointState, Rule};
use jointlin::law::hertz::Hertz;
use jointlin::law::{Backbone, TangentialLaw};
use jointlin::linearize::{linearize, Contact, Method};
use std::f64::consts::PI;

/// Relative agreement demanded between the C ABI and the core: both run the same code, so
/// only the per-area bookkeeping could differ; 1e-12 leaves room for nothing else.
const REL: f64 = 1e-12;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= REL * a.abs().max(b.abs()) || a == b
}

#[test]
fn time_domain_cycle_of_the_block_matches_the_rust_hysteresis() {
    for rule in [Rule::Thesis, Rule::Masing] {
        let mut props = block_props();
        props[1] = if rule == Rule::Thesis { 0.0 } else { 1.0 };
        let mut u = Uinter::new(props, 3);
        let h = 2e-4;
        assert_eq!(u.step_to([h, 0.0, 0.0]), JOINTLIN_OK);
        let p = u.stress[0];
        assert!(close(p, 1e4 * h));
        assert_eq!(u.ddsddr[0], 1e4);
        assert_eq!(u.lopenclose, 1);
        let backbone = Backbone::new(TangentialLaw::Mindlin, 0.3 * p, 1282.7).unwrap();
        let point = Point::new(backbone, rule);
        let d = backbone.slip_limit();
        // Direction 1: a cycle into sliding; direction 2: a microslip cycle, reversed sign.
        let mut states = [PointState::virgin(rule, 0.0); 2];
        let mut rust_energy = 0.0;
        let mut c_energy = 0.0;
        let mut saw_sliding = false;
        let n = 60;
        for k in 1..=3 * n {
            let t = k as f64 / n as f64 * 2.0 * PI;
            let s1 = 1.5 * d * t.sin();
            let s2 = -0.4 * d * (0.5 * t).sin();
            assert_eq!(u.step_to([h, s1, s2]), JOINTLIN_OK);
            c_energy += u.sfd;
            for (i, s) in [(1usize, s1), (2, s2)] {
                let (next, r) = point.step(&states[i - 1], s).unwrap();
                // dτ/dp at fixed slip history by one-sided differences either side (step 1e-6 p:
                // truncation ~1e-6 relative): τ(p) has kinks (sliding onset), where the C
                // side's forward difference may sit anywhere between the two.
                let at = |scale: f64| {
                    let b = Backbone::new(TangentialLaw::Mindlin, 0.3 * p * scale, 1282.7).unwrap();
                    Point::new(b, rule).step(&states[i - 1], s).unwrap().1.force
                };
                let (lo, mid, hi) = (at(1.0 - 1e-6), at(1.0), at(1.0 + 1e-6));
                let sides = [(mid - lo) / (1e-6 * p) * 1e4, (hi - mid) / (1e-6 * p) * 1e4];
                states[i - 1] = next;
                rust_energy += r.dissipated;
                assert!(close(u.stress[i], r.force), "{rule:?} k {k} dir {i}");
                assert!(close(u.ddsddr[i + 3 * i], r.tangent));
                // DDSDDR(i,1) = dτ/dp · dp/dh: μ dp/dh sign(τ) while sliding (tangent 0).
                // The C side's forward difference (step 1.5e-8 p) must lie between the two
                // one-sided slopes, to 1e-5 of the coupling's scale μ dp/dh.
                let coupling = u.ddsddr[i];
                let scale = 0.3 * 1e4;
                let (low, high) = (sides[0].min(sides[1]), sides[0].max(sides[1]));
                assert!(
                    coupling >= low - 1e-5 * scale && coupling <= high + 1e-5 * scale,
                    "{rule:?} k {k} dir {i}: {coupling} vs {sides:?}"
                );
                if r.tangent == 0.0 {
                    saw_sliding = true;
                    assert!((coupling - scale * r.force.signum()).abs() <= 1e-6 * scale);
                }
                assert_eq!(u.ddsddr[3 * i], 0.0); // DDSDDR(1,i)
            }
            assert!(u.dviscous.iter().chain(&u.dstructural).all(|&v| v == 0.0));
        }
        assert!(saw_sliding);
        assert!(rust_energy > 0.0 && close(c_energy, rust_energy));
        assert!(close(u.statev[4], rust_energy)); // STATEV(5)
        assert_eq!((u.statev[1], u.statev[2], u.statev[3]), (p, h, 1.0));
        // Opening resets the histories; closing again starts virgin at the current slip.
        let slip_now = u.rdisp;
        assert_eq!(u.step_to([-1e-5, slip_now[1], slip_now[2]]), JOINTLIN_OK);
        assert_eq!(u.lopenclose, 0);
        assert!(u.stress.iter().chain(&u.ddsddr).all(|&v| v == 0.0));
        assert!(u.statev[5..51].iter().all(|&v| v == 0.0));
        assert_eq!(u.step_to([h, slip_now[1], slip_now[2]]), JOINTLIN_OK);
        assert_eq!(u.stress[1], 0.0);
        assert_eq!(
            u.step_to([h, slip_now[1] + 0.1 * d, slip_now[2]]),
            JOINTLIN_OK
        );
        let fresh = point
            .step(
                &PointState::virgin(rule, slip_now[1]),
                slip_now[1] + 0.1 * d,
            )
            .unwrap()
            .1;
        assert!(close(u.stress[1], fresh.force));
    }
}

fn run_steady(u: &mut Uinter, store: *const jointlin_store) -> i32 {
    u.linper = 1;
    u.kstep = 2;
    u.call(store)
}

#[test]
fn linper_one_returns_exactly_the_core_linearization() {
    for damping in [0.0, 1.0] {
        let mut props = block_props();
        props.extend([0.0, 0.0, damping]);
        let mut u = Uinter::new(props, 3);
        u.area = 0.5;
        assert_eq!(u.step_to([2e-4, 0.0, 0.0]), JOINTLIN_OK);
        let p0 = u.statev[1];
        let store = new_store(3e-4, 1e-6, JOINTLIN_KINC_ORIGINAL);
        assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
        assert_eq!(uexternaldb(store, 1, 0, 2, 1), 0);
        u.freqr = 7.5;
        u.kinc = 1;
        let stress_before = u.stress;
        assert_eq!(run_steady(&mut u, store), JOINTLIN_OK);
        let c = Contact {
            law: TangentialLaw::Mindlin,
            rule: Rule::Thesis,
            mu: 0.3,
            normal_force: p0,
            k_t0: 1282.7,
        };
        let omega = 2.0 * PI * 7.5;
        let l = linearize(&c, 3e-4, omega, Method::default()).unwrap();
        assert_eq!(u.stress, stress_before);
        assert_eq!(u.ddsddr[0], 1e4);
        for i in [1usize, 2] {
            assert_eq!(u.ddsddr[i + 3 * i], l.k_star);
            if damping == 0.0 {
                assert_eq!(u.dviscous[i + 3 * i], l.d_star);
            } else {
                assert_eq!(u.dstructural[i + 3 * i], omega * l.d_star);
                // ω d* = η k* (3.14): equal up to the rounding of the two formulas.
                let eta_k = l.eta * l.k_star;
                assert!(((u.dstructural[i + 3 * i] - eta_k) / eta_k).abs() < 1e-14);
            }
        }
        let off_diag_zero = |m: &[f64; 9]| (0..9).filter(|j| j % 4 != 0).all(|j| m[j] == 0.0);
        assert!(
            off_diag_zero(&u.ddsddr) && off_diag_zero(&u.dviscous) && off_diag_zero(&u.dstructural)
        );
        let (used, unused) = if damping == 0.0 {
            (u.dviscous, u.dstructural)
        } else {
            (u.dstructural, u.dviscous)
        };
        assert!(unused.iter().all(|&v| v == 0.0) && used[4] > 0.0);
        // STATEV(52:57) and the report.
        assert_eq!(&u.statev[51..55], &[l.k_star, l.k_star, l.d_star, l.d_star]);
        assert_eq!(u.statev[55], 2.0 * l.energy_per_cycle);
        assert_eq!(u.statev[56], 2.0 * l.energy_per_cycle * 7.5);
        assert_eq!(u.report.k_star, [l.k_star; 2]);
        assert_eq!(u.report.amplitude, [3e-4; 2]);
        assert_eq!((u.report.point, u.statev[0]), (1, 1.0));
        assert_eq!(u.report.regime, [2, 2]); // microslip
        unsafe { jointlin_store_free(store) };
    }
}

#[test]
fn hertz_normal_law_and_hertz_mindlin_stiffness_per_area() {
    // PROPS: Mindlin, thesis, μ 0.2, k_T0 (unused), Hertz E* = 1.15e5, r* = 5, k_T0 from
    // G* = 4e4 (2.37), k_T0 = 8 r_A G* (2.38).
    let props = vec![0.0, 0.0, 0.2, 0.0, 1.0, 1.15e5, 5.0, 1.0, 4e4];
    let mut u = Uinter::new(props, 2);
    u.area = 0.25;
    let h = 1e-3;
    assert_eq!(u.step_to([h, 0.0, 0.0]), JOINTLIN_OK);
    let hz = Hertz::new(5.0, 1.15e5).unwrap();
    assert!(close(u.stress[0], hz.force(h) / 0.25)); // (2.34)
    let p0 = u.stress[0];
    let store = new_store(1e-4, 1e-6, JOINTLIN_KINC_ORIGINAL);
    assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
    assert_eq!(uexternaldb(store, 1, 0, 2, 1), 0);
    assert_eq!(run_steady(&mut u, store), JOINTLIN_OK);
    let f_n = p0 * 0.25;
    let k_t0 = 8.0 * hz.contact_radius(f_n) * 4e4 / 0.25; // (2.38) per area
    let c = Contact {
        law: TangentialLaw::Mindlin,
        rule: Rule::Thesis,
        mu: 0.2,
        normal_force: p0,
        k_t0,
    };
    let l = linearize(&c, 1e-4, 2.0 * PI, Method::default()).unwrap();
    assert!(close(u.ddsddr[3], l.k_star) && close(u.dviscous[3], l.d_star));
    assert!(close(u.ddsddr[0], hz.normal_stiffness(f_n) / 0.25)); // (2.35)
    unsafe { jointlin_store_free(store) };
}

#[test]
fn steady_state_without_a_general_step_uses_stress_on_entry_and_open_points_skip_the_store() {
    let store = new_store(1e-4, 1e-6, JOINTLIN_KINC_ORIGINAL);
    assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
    assert_eq!(uexternaldb(store, 1, 0, 2, 1), 0);
    let mut u = Uinter::new(block_props(), 2);
    u.stress[0] = 2.0; // never closed in a general step: p0 = STRESS(1)
    assert_eq!(run_steady(&mut u, store), JOINTLIN_OK);
    assert_eq!(u.report.pressure, 2.0);
    assert!(u.ddsddr[3] > 0.0);
    let mut open = Uinter::new(block_props(), 2);
    open.coords = [1.0, 0.0, 0.0];
    open.stress[0] = 0.0;
    open.ddsddr = [7.0; 9];
    assert_eq!(run_steady(&mut open, store), JOINTLIN_OK);
    assert!(open.ddsddr[..4].iter().all(|&v| v == 0.0)); // NDIR × NDIR written
    assert_eq!((open.report.point, open.report.closed), (0, 0));
    let mut count = 0;
    assert_eq!(unsafe { jointlin_store_point_count(store, &mut count) }, 0);
    assert_eq!(count, 1, "the open point was not registered");
    // NDIR = 1 (frictionless normal only) needs no store.
    let mut normal_only = Uinter::new(block_props(), 1);
    normal_only.stress[0] = 2.0;
    assert_eq!(run_steady(&mut normal_only, std::ptr::null()), JOINTLIN_OK);
    assert_eq!(normal_only.ddsddr[0], 1e4);
    unsafe { jointlin_store_free(store) };
}

/// Results of one LINPER = 1 call that must not depend on threading.
#[derive(Debug, Clone, PartialEq)]
struct Seen {
    ddsddr: [f64; 9],
    dviscous: [f64; 9],
    statev_tail: Vec<f64>,
    amplitude: [f64; 2],
}

const POINTS: usize = 48;
const THREADS: usize = 16;
const FREQS: [f64; 3] = [3.0, 5.0, 8.0];

/// A toy host response: the computed amplitude from the point's own k*, d* (a 1-DOF
/// oscillator per point and direction, different per point), deterministic.
fn host_amplitude(point: usize, freq: f64, k: f64, d: f64) -> f64 {
    let omega = 2.0 * PI * freq;
    let force = 0.05 + 0.004 * point as f64;
    let (re, im) = (k + 300.0 - 2.0 * omega * omega, omega * d);
    force / (re * re + im * im).sqrt()
}

/// Drives the store to the end: per increment, `THREADS` workers (or one) call UINTER for
/// their share of the points and report back. Returns every call's results by point and
/// the pass stats.
fn sweep(threads: usize) -> (Vec<Vec<Seen>>, Vec<jointlin_pass_stats>) {
    let store = new_store(1e-4, 1e-7, JOINTLIN_KINC_SEQUENTIAL);
    let store_addr = store as usize;
    let mut seen: Vec<Vec<Seen>> = vec![Vec::new(); POINTS];
    // Base state of each point from a general step (serial, as Abaqus's static step).
    let base: Vec<Uinter> = (0..POINTS)
        .map(|p| {
            let mut u = Uinter::new(block_props(), 3);
            u.coords = [p as f64 * 0.5, 1.0, -0.0];
            assert_eq!(u.step_to([1e-4 * (1.0 + 0.05 * p as f64), 0.0, 0.0]), 0);
            u
        })
        .collect();
    loop {
        let (action, _) = next_action(store);
        let list = match action {
            JOINTLIN_ACTION_RUN_SWEEP => vec![1, 2, 3],
            JOINTLIN_ACTION_RUN_PASS | JOINTLIN_ACTION_RUN_FINAL => increments(store),
            _ => break,
        };
        assert_eq!(uexternaldb(store, 0, 0, 2, 0), 0);
        for (i, &sweep_kinc) in list.iter().enumerate() {
            let kinc = i as i32 + 1;
            let freq = FREQS[sweep_kinc as usize - 1];
            assert_eq!(uexternaldb(store, 1, 0, 2, kinc), 0);
            let work = |worker: usize| -> Vec<(usize, Seen)> {
                let store = store_addr as *const jointlin_store;
                (worker..POINTS)
                    .step_by(threads)
                    .map(|p| {
                        let mut u = base[p].clone();
                        u.freqr = freq;
                        u.kinc = kinc;
                        assert_eq!(run_steady(&mut u, store), 0);
                        let amp = [
                            host_amplitude(p, freq, u.ddsddr[4], u.dviscous[4]),
                            host_amplitude(p + 7, freq, u.ddsddr[8], u.dviscous[8]),
                        ];
                        let rc = unsafe {
                            jointlin_store_report(store, u.report.point, kinc, amp.as_ptr())
                        };
                        assert_eq!(rc, 0);
                        let seen = Seen {
                            ddsddr: u.ddsddr,
                            dviscous: u.dviscous,
                            statev_tail: u.statev[51..57].to_vec(),
                            amplitude: u.report.amplitude,
                        };
                        (p, seen)
                    })
                    .collect()
            };
            let results: Vec<(usize, Seen)> = if threads == 1 {
                work(0)
            } else {
                std::thread::scope(|s| {
                    let handles: Vec<_> = (0..threads).map(|w| s.spawn(move || work(w))).collect();
                    handles
                        .into_iter()
                        .flat_map(|h| h.join().unwrap())
                        .collect()
                })
            };
            for (p, r) in results {
                seen[p].push(r);
            }
            assert_eq!(uexternaldb(store, 2, 0, 2, kinc), 0);
        }
        assert_eq!(uexternaldb(store, 3, 0, 2, 0), 0);
    }
    assert_eq!(next_action(store).0, JOINTLIN_ACTION_DONE);
    let (_, passes) = next_action(store);
    let stats = (1..=passes)
        .map(|n| {
            let mut s = jointlin_pass_stats::default();
            assert_eq!(unsafe { jointlin_store_pass_stats(store, n, &mut s) }, 0);
            s
        })
        .collect();
    unsafe { jointlin_store_free(store) };
    (seen, stats)
}

#[test]
fn sixteen_threads_sharing_a_store_match_a_serial_run() {
    let (serial, serial_stats) = sweep(1);
    let (parallel, parallel_stats) = sweep(THREADS);
    assert_eq!(serial_stats, parallel_stats);
    assert!(serial_stats.len() >= 3, "{serial_stats:?}");
    for p in 0..POINTS {
        assert_eq!(serial[p], parallel[p], "point {p}");
    }
}
