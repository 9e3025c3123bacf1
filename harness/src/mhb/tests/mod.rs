//! Tests of the multi-harmonic balance, by subject; the shared oscillators and start
//! vectors live here.

use nalgebra::{Complex, DMatrix};

use super::continuation::{trace, Options};
use super::*;
use crate::bench::mhb_chain::jenkins_chain;
use crate::capi::Tangential;
use crate::names::{LawName, RuleName};
use crate::time::mhb_reference as reference;

fn point(law: LawName, rule: RuleName, mu: f64, normal: f64, k_t0: f64) -> Law {
    Law::Point(Tangential {
        law,
        rule,
        mu,
        normal,
        k_t0,
    })
}

/// One mass m on a ground spring k and dashpot d with one element to ground, load
/// f cos ωt (f̂ real) or −i f (f sin ωt).
fn oscillator(m: f64, d: f64, k: f64, f1: Complex<f64>, law: Law) -> System {
    System {
        m: DMatrix::from_element(1, 1, m),
        d: DMatrix::from_element(1, 1, d),
        k: DMatrix::from_element(1, 1, k),
        f0: vec![0.0],
        f1: vec![f1],
        elements: vec![Element { i: 0, j: None, law }],
    }
}

/// Duffing of thesis Appendix B: ẍ + ẋ + 20x + 40x³ = 30 sin(ωt).
fn duffing() -> System {
    oscillator(1.0, 1.0, 20.0, Complex::new(0.0, -30.0), Law::Cubic(40.0))
}

/// Start vector at H harmonics from a complex first harmonic per DOF.
fn start(h: usize, x1: &[Complex<f64>]) -> Vec<f64> {
    let m = 2 * h + 1;
    let mut u = vec![0.0; x1.len() * m];
    for (d, x) in x1.iter().enumerate() {
        u[d * m + 1] = x.re;
        u[d * m + 2] = -x.im;
    }
    u
}

/// Initial state (x, ẋ) at t = 0 from a solution.
fn initial(hb: &Hb, u: &[f64], omega: f64) -> (Vec<f64>, Vec<f64>) {
    super::state_at_zero(u, hb.h(), omega)
}

mod basics;
mod duffing;
mod friction;
mod thesis_loops;
mod time_domain;
