//! The Rust loop the Python package is measured against: `jointlin_linearize` (the C
//! entry, default method) over N amplitudes of the thesis's block (μ = 0.3, F_N = 2 N,
//! k_T0 = 1282.7 N/mm, ω = 1.3 rad/s), A = δ*·10^(−3 + 4 i/(N − 1)) mm, i = 0…N−1.
//! Prints the best of 5 runs in ns per call and the sum of k* (N/mm), on one line:
//! `ns_per_call <t> sum_k_star <s>`.
//!
//! `cargo run --release --example linearize_loop -- [N]` (default 10^6; called by
//! scripts/python-bench.sh).

use std::hint::black_box;
use std::time::Instant;

use jointlin::ffi::linearize::{
    jointlin_contact, jointlin_linearization, jointlin_linearize, JOINTLIN_LAW_MINDLIN,
    JOINTLIN_RULE_THESIS,
};

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().expect("N must be a positive integer"))
        .unwrap_or(1_000_000);
    let c = jointlin_contact {
        law: JOINTLIN_LAW_MINDLIN,
        rule: JOINTLIN_RULE_THESIS,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    };
    let slip_limit = 1.5 * c.mu * c.normal_force / c.k_t0;
    let amplitudes: Vec<f64> = (0..n)
        .map(|i| slip_limit * 10f64.powf(-3.0 + 4.0 * i as f64 / (n.max(2) - 1) as f64))
        .collect();
    let mut best = f64::INFINITY;
    let mut sum = 0.0;
    for _ in 0..5 {
        let started = Instant::now();
        let mut k_star = vec![0.0; n];
        for (k, &a) in k_star.iter_mut().zip(&amplitudes) {
            let mut out = jointlin_linearization::default();
            // SAFETY: pointers to live locals; NULL method = the default.
            let status = unsafe { jointlin_linearize(&c, a, 1.3, std::ptr::null(), &mut out) };
            assert_eq!(status, 0, "jointlin_linearize failed at A = {a:e}");
            *k = out.k_star;
        }
        black_box(&k_star);
        best = best.min(started.elapsed().as_secs_f64());
        sum = k_star.iter().sum();
    }
    println!(
        "ns_per_call {:.1} sum_k_star {sum:.12e}",
        best * 1e9 / n as f64
    );
}
