//! The two-point sweep model of the sweep hosts (harness/c/sweep.c,
//! harness/fortran/sweep.f90, harness/fortran/abaqus_job.f90) and the Rust API's
//! version of their iteration, record for record.

use jointlin::hysteresis::Rule;
use jointlin::iterate::Scheme;
use jointlin::law::TangentialLaw;
use jointlin::linearize::{linearize, Contact, Method};
use jointlin::store::{Action, KincNumbering, PointKey, Store, StoreConfig};
use nalgebra::Complex;
use std::f64::consts::PI;

use super::Record;

// The hosts' data (harness/c/host.h, harness/fortran/host_data.f90).
pub const MU: f64 = 0.3;
pub const KT0: f64 = 1282.7;
pub const KN: f64 = 1.0e4;
pub const H_BLOCK: f64 = 2.0e-4;
pub const H_SECOND: f64 = 1.0e-4;
pub const MASS: f64 = 0.002;
pub const FORCE: f64 = 0.5;
pub const KC: f64 = 600.0;
pub const SWEEP_OMEGA: [f64; 3] = [1.3, 300.0, 500.0];

pub fn rec(name: &str, values: Vec<f64>) -> Record {
    Record {
        name: name.into(),
        values,
    }
}

pub fn contact(pressure: f64) -> Contact {
    Contact {
        law: TangentialLaw::Mindlin,
        rule: Rule::Thesis,
        mu: MU,
        normal_force: pressure, // stress form with AREA = 1
        k_t0: KT0,
    }
}

pub fn action_code(a: &Action) -> (f64, Vec<i32>) {
    match a {
        Action::RunSweep => (1.0, vec![]),
        Action::RunPass(l) => (2.0, l.clone()),
        Action::RunFinal(l) => (3.0, l.clone()),
        Action::Done => (4.0, vec![]),
        Action::Failed(l) => (5.0, l.clone()),
    }
}

/// The Rust API's version of the sweep hosts: the same store decisions, the same
/// linearizations, the same 2×2 complex solves.
pub fn sweep_reference(numbering: KincNumbering) -> Vec<Record> {
    let mut want = Vec::new();
    let pressures = [KN * H_BLOCK, KN * H_SECOND];
    for (j, p) in pressures.iter().enumerate() {
        want.push(rec("preload", vec![(j + 1) as f64, *p]));
    }
    let store = Store::new(StoreConfig {
        initial_amplitude: 1e-4,
        rtol: 1e-6,
        atol: 0.0,
        scheme: Scheme::Secant,
        max_passes: 30,
        sweep_step: 2,
        numbering,
        restart_path: None,
    })
    .unwrap();
    let keys: Vec<_> = (0..2)
        .map(|j| PointKey::new(b"SWEEP-PAIR", 0, &[10.0 * j as f64, 0.0, 0.0]).unwrap())
        .collect();
    loop {
        let (action, pass) = store.next_action().unwrap().expect("no pass running");
        let (code, list) = action_code(&action);
        let mut next = vec![code, pass as f64, list.len() as f64];
        next.extend(list.iter().map(|&k| k as f64));
        want.push(rec("next", next));
        let list: Vec<i32> = match action {
            Action::RunSweep => vec![1, 2, 3],
            Action::RunPass(l) | Action::RunFinal(l) => l,
            Action::Done | Action::Failed(_) => break,
        };
        store.external_db(0, 0, 0, 0).unwrap();
        store.external_db(5, 0, 2, 0).unwrap();
        for (i, &kinc) in list.iter().enumerate() {
            let call_kinc = match numbering {
                KincNumbering::Original => kinc,
                KincNumbering::Sequential => i as i32 + 1,
            };
            let omega_k = SWEEP_OMEGA[kinc as usize - 1];
            let omega = 2.0 * PI * (omega_k / (2.0 * PI)); // host FREQR -> jointlin omega
            store.external_db(1, 0, 2, call_kinc).unwrap();
            let mut lin = Vec::new();
            for (j, key) in keys.iter().enumerate() {
                let id = store.register(key.clone()).unwrap();
                let est = store.estimate(id, call_kinc, 1).unwrap()[0];
                let l = linearize(&contact(pressures[j]), est, omega, Method::default()).unwrap();
                lin.push((id, est, l.k_star, l.d_star));
            }
            let dyn_stiffness = |j: usize| {
                Complex::new(KC + lin[j].2 - MASS * omega_k * omega_k, omega_k * lin[j].3)
            };
            let (z11, z22, z12) = (dyn_stiffness(0), dyn_stiffness(1), Complex::new(-KC, 0.0));
            let det = z11 * z22 - z12 * z12;
            let x = [z22 * FORCE / det, -z12 * FORCE / det];
            for (j, &(id, est, k, d)) in lin.iter().enumerate() {
                let amp = x[j].norm();
                store.report(id, call_kinc, [amp, 0.0]).unwrap();
                want.push(rec(
                    "inc",
                    vec![pass as f64, kinc as f64, id as f64, est, k, d, amp],
                ));
            }
            store.external_db(2, 0, 2, call_kinc).unwrap();
        }
        store.external_db(6, 0, 2, 0).unwrap();
        store.external_db(3, 0, 0, 0).unwrap();
        let st = store.pass_stats(pass).unwrap().unwrap();
        want.push(rec(
            "stats",
            vec![
                st.number as f64,
                st.kind as i32 as f64,
                st.increments_run as f64,
                st.increments_converged as f64,
                st.evaluations as f64,
                st.not_reported as f64,
            ],
        ));
    }
    want.push(rec("points", vec![store.point_count().unwrap() as f64]));
    want
}
