//! What accuracy costs per call: every linearization option's worst relative error in k*
//! and in the energy per cycle (against a 64-point graded reference) over representative
//! amplitudes, next to its measured cost per call, as a Markdown table.
//!
//! `cargo run --release --example accuracy_table` (the table in docs/c-fortran.md comes from here).

use jointlin::hysteresis::Rule;
use jointlin::law::TangentialLaw;
use jointlin::linearize::{linearize, Contact, Method};
use std::hint::black_box;
use std::time::Instant;

/// Amplitudes A/δ* covering microslip, the thesis rule's sliding onset (5/6) and sliding.
const RATIOS: [f64; 6] = [0.01, 0.3, 0.8, 0.9, 2.0, 20.0];
/// The accuracy at which the default and Simpson are compared.
const TARGET: f64 = 1e-8;

fn contacts() -> [Contact; 2] {
    let block = |rule| Contact {
        law: TangentialLaw::Mindlin,
        rule,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    };
    [block(Rule::Thesis), block(Rule::Masing)]
}

/// Worst relative error of k* and of the energy per cycle over both rules and all RATIOS.
fn worst_error(method: Method) -> f64 {
    let mut worst: f64 = 0.0;
    for c in contacts() {
        let d = 1.5 * c.mu * c.normal_force / c.k_t0;
        for r in RATIOS {
            let reference = linearize(&c, r * d, 1.3, Method::Graded { points: 64 }).unwrap();
            let got = linearize(&c, r * d, 1.3, method).unwrap();
            let ek = ((got.k_star - reference.k_star) / reference.k_star).abs();
            let ee = ((got.energy_per_cycle - reference.energy_per_cycle)
                / reference.energy_per_cycle)
                .abs();
            worst = worst.max(ek).max(ee);
        }
    }
    worst
}

/// Median over 7 batches of the mean wall time per call (ns) of `call`, cycling through
/// every (contact, amplitude) case.
fn median_ns(mut call: impl FnMut(&Contact, f64)) -> f64 {
    let cases: Vec<(Contact, f64)> = contacts()
        .into_iter()
        .flat_map(|c| RATIOS.map(|r| (c, r * 1.5 * c.mu * c.normal_force / c.k_t0)))
        .collect();
    let mut batch = |calls: usize| {
        let t = Instant::now();
        for i in 0..calls {
            let (c, a) = cases[i % cases.len()];
            call(black_box(&c), black_box(a));
        }
        t.elapsed()
    };
    let mut calls = 1usize;
    while batch(calls).as_millis() < 20 {
        calls *= 2;
    }
    let mut ns: Vec<f64> = (0..7)
        .map(|_| batch(calls).as_nanos() as f64 / calls as f64)
        .collect();
    ns.sort_by(f64::total_cmp);
    ns[3]
}

fn cost_ns(method: Method) -> f64 {
    median_ns(|c, a| {
        black_box(linearize(c, a, 1.3, method).unwrap());
    })
}

/// The same cases through the C entry point a host calls (default method: NULL).
fn c_entry_ns() -> f64 {
    use jointlin::ffi::linearize::{jointlin_contact, jointlin_linearization};
    let mut out = jointlin_linearization::default();
    median_ns(|c, a| {
        let contact = jointlin_contact {
            law: 0,
            rule: i32::from(c.rule == Rule::Masing),
            mu: c.mu,
            normal_force: c.normal_force,
            k_t0: c.k_t0,
        };
        // SAFETY: pointers to live locals; a NULL method selects the default.
        let status = unsafe {
            jointlin::ffi::linearize::jointlin_linearize(
                &contact,
                a,
                1.3,
                std::ptr::null(),
                &mut out,
            )
        };
        assert_eq!(status, 0);
        black_box(out.k_star);
    })
}

fn main() {
    let mut rows: Vec<(String, Method)> = vec![];
    for points in [4, 6, 8, 12, 16] {
        let tag = if Method::default() == (Method::Graded { points }) {
            " (default)"
        } else {
            ""
        };
        rows.push((
            format!("graded Gauss, {points} pts/panel{tag}"),
            Method::Graded { points },
        ));
    }
    for points in [8, 16, 32, 64, 128] {
        rows.push((
            format!("plain Gauss, {points} pts"),
            Method::Gauss { points },
        ));
    }
    for k in [4, 6, 8, 10, 12, 14, 16] {
        let n = 1usize << k;
        rows.push((
            format!("Simpson (thesis), {n} intervals"),
            Method::Simpson { intervals: n },
        ));
    }
    println!("| method | worst rel. error (k*, energy) | ns per call |");
    println!("|---|---:|---:|");
    let mut measured = vec![];
    for (name, method) in rows {
        let (err, ns) = (worst_error(method), cost_ns(method));
        println!("| {name} | {err:.1e} | {ns:.0} |");
        measured.push((method, err, ns));
    }
    println!();
    println!("`jointlin_linearize` (C entry, default method), median over the same cases: {:.0} ns per call.", c_entry_ns());
    let default = measured
        .iter()
        .find(|m| m.0 == Method::default())
        .expect("default row");
    let simpson = measured
        .iter()
        .find(|m| matches!(m.0, Method::Simpson { .. }) && m.1 <= TARGET);
    println!();
    match simpson {
        Some((Method::Simpson { intervals }, err, ns)) => println!(
            "At relative error ≤ {TARGET:.0e}: Simpson needs {intervals} intervals ({err:.1e}, {ns:.0} ns); \
             the default reaches {:.1e} in {:.0} ns: {:.0}× faster.",
            default.1,
            default.2,
            ns / default.2
        ),
        _ => println!("Simpson did not reach {TARGET:.0e} with up to 65536 intervals; the default reaches {:.1e} in {:.0} ns.", default.1, default.2),
    }
}
