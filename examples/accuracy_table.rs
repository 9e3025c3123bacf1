//! What accuracy costs per call: every linearization option's worst relative error in k*
//! and in the energy per cycle (against a 64-point graded reference) over representative
//! amplitudes, next to its measured cost per call, as a Markdown table.
//!
//! `cargo run --release --example accuracy_table` (the README's table comes from here).

use jointlin::hysteresis::Rule;
use jointlin::law::TangentialLaw;
use jointlin::linearize::{linearize, Contact, Method};
use std::hint::black_box;
use std::time::Instant;

/// Amplitudes A/δ* covering microslip, the thesis rule's sliding onset (5/6) and sliding.
const RATIOS: [f64; 6] = [0.01, 0.3, 0.8, 0.9, 2.0, 20.0];
/// The accuracy at which the default and Simpson are compared (issue 2).
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

/// Median over 7 batches of the mean wall time per call (ns), cycling through all cases.
fn cost_ns(method: Method) -> f64 {
    let cases: Vec<(Contact, f64)> = contacts()
        .into_iter()
        .flat_map(|c| RATIOS.map(|r| (c, r * 1.5 * c.mu * c.normal_force / c.k_t0)))
        .collect();
    let mut calls = 1usize;
    loop {
        let t = Instant::now();
        for i in 0..calls {
            let (c, a) = cases[i % cases.len()];
            black_box(linearize(black_box(&c), black_box(a), 1.3, method).unwrap());
        }
        if t.elapsed().as_millis() >= 20 {
            break;
        }
        calls *= 2;
    }
    let mut batches: Vec<f64> = (0..7)
        .map(|_| {
            let t = Instant::now();
            for i in 0..calls {
                let (c, a) = cases[i % cases.len()];
                black_box(linearize(black_box(&c), black_box(a), 1.3, method).unwrap());
            }
            t.elapsed().as_nanos() as f64 / calls as f64
        })
        .collect();
    batches.sort_by(f64::total_cmp);
    batches[3]
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
