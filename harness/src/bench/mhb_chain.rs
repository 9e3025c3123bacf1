//! `jointlin mhb`: cost vs H on the 3-DOF Jenkins chain: a sweep of
//! `count` frequencies at H = 1, 3, 7, 15 (each frequency's Newton started from the
//! previous frequency's solution), beside the first-order linearization, as a Markdown
//! table.

use std::time::Instant;

use nalgebra::{Complex, DMatrix};

use crate::capi::{self, Tangential};
use crate::mhb::{default_samples, first_order, Element, Hb, Law, NewtonOptions, System};
use crate::names::{LawName, RuleName};

/// The validation chain: ground –k– m₁ –k– m₂ –k– m₃ (k = 1, m = 1), D = 0.01 K, Jenkins
/// elements (μF_N = 0.1, k_T0 = 2) from m₁ to ground and between m₃ and m₂, force
/// f cos ωt on m₃. Stuck, its first mode is at 0.66 rad/s; free, at 0.45.
pub fn jenkins_chain(f: f64) -> System {
    let kk = DMatrix::from_row_slice(3, 3, &[2.0, -1.0, 0.0, -1.0, 2.0, -1.0, 0.0, -1.0, 1.0]);
    let jen = Law::Point(Tangential {
        law: LawName::Jenkins,
        rule: RuleName::Masing,
        mu: 1.0,
        normal: 0.1,
        k_t0: 2.0,
    });
    let zero = Complex::new(0.0, 0.0);
    System {
        m: DMatrix::identity(3, 3),
        d: &kk * 0.01,
        k: kk,
        f0: vec![0.0; 3],
        f1: vec![zero, zero, Complex::new(f, 0.0)],
        elements: vec![
            Element {
                i: 0,
                j: None,
                law: jen,
            },
            Element {
                i: 2,
                j: Some(1),
                law: jen,
            },
        ],
    }
}

/// One row of the table.
#[derive(Debug, Clone)]
pub struct Row {
    pub label: String,
    pub seconds: f64,
    pub newton: usize,
    pub point_steps: u64,
    pub failed: usize,
    pub peak: f64,
    pub peak_omega: f64,
    /// Largest deviation of the m₃ amplitude from the H = 15 sweep over the band,
    /// relative to H = 15's peak.
    pub deviation: f64,
}

/// Sweeps ω ∈ [w0, w1] (`count` points) at each H, and at first order.
pub fn sweep_table(f: f64, w0: f64, w1: f64, count: usize, hs: &[usize]) -> Vec<Row> {
    let sys = jenkins_chain(f);
    let omegas: Vec<f64> = (0..count)
        .map(|i| w0 + (w1 - w0) * i as f64 / (count.max(2) - 1) as f64)
        .collect();
    let mut rows = Vec::new();
    let mut curves = Vec::new();
    // First order.
    let t = Instant::now();
    let calls = capi::counts().linearize;
    let mut a = vec![0.01; sys.elements.len()];
    let mut curve = Vec::new();
    let mut failed = 0;
    for &w in &omegas {
        match first_order::solve(&sys, w, &a) {
            Ok(x) => {
                a = sys
                    .elements
                    .iter()
                    .map(|e| (x[e.i] - e.j.map_or(Complex::new(0.0, 0.0), |j| x[j])).norm())
                    .collect();
                curve.push(x[2].norm());
            }
            Err(_) => {
                failed += 1;
                curve.push(f64::NAN);
            }
        }
    }
    rows.push(Row {
        label: "first order (jointlin_linearize)".into(),
        seconds: t.elapsed().as_secs_f64(),
        newton: 0,
        point_steps: capi::counts().linearize - calls,
        failed,
        peak: 0.0,
        peak_omega: 0.0,
        deviation: 0.0,
    });
    curves.push(curve);
    for &h in hs {
        let t = Instant::now();
        let steps = capi::point_steps();
        let mut hb = Hb::new(&sys, h, default_samples(h));
        let mut u = vec![0.0; hb.size()];
        let (mut newton, mut failed) = (0, 0);
        let mut curve = Vec::new();
        for &w in &omegas {
            match hb.solve(&u, w, NewtonOptions::default()) {
                Ok(s) => {
                    newton += s.iterations;
                    curve.push(hb.amplitude(&s.u, 2));
                    u = s.u;
                }
                Err(_) => {
                    failed += 1;
                    curve.push(f64::NAN);
                }
            }
        }
        rows.push(Row {
            label: format!("H = {h} (N = {})", default_samples(h)),
            seconds: t.elapsed().as_secs_f64(),
            newton,
            point_steps: capi::point_steps() - steps,
            failed,
            peak: 0.0,
            peak_omega: 0.0,
            deviation: 0.0,
        });
        curves.push(curve);
    }
    let reference = curves.last().cloned().unwrap_or_default();
    let ref_peak = reference.iter().cloned().fold(0.0f64, f64::max);
    for (row, c) in rows.iter_mut().zip(&curves) {
        let (i, p) = c
            .iter()
            .enumerate()
            .fold((0, f64::NEG_INFINITY), |(bi, bp), (i, &v)| {
                if v > bp {
                    (i, v)
                } else {
                    (bi, bp)
                }
            });
        row.peak = p;
        row.peak_omega = omegas[i];
        row.deviation = c
            .iter()
            .zip(&reference)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / ref_peak;
    }
    rows
}

/// The table as Markdown.
pub fn markdown(rows: &[Row], f: f64, w0: f64, w1: f64, count: usize) -> String {
    let mut s = format!(
        "3-DOF Jenkins chain (`mhb::bench::jenkins_chain`, f = {f}), {count} frequencies in \
         [{w0}, {w1}] rad/s, amplitude of m₃:\n\n\
         | method | wall time [s] | Newton iterations | C-API calls (linearize; point_step) | failed | peak | at ω | max deviation from the last row |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|\n"
    );
    for r in rows {
        s += &format!(
            "| {} | {:.3e} | {} | {} | {} | {:.5e} | {:.4} | {:.2e} |\n",
            r.label,
            r.seconds,
            r.newton,
            r.point_steps,
            r.failed,
            r.peak,
            r.peak_omega,
            r.deviation
        );
    }
    s
}
