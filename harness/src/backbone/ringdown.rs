//! Free decay (ring-down) of a lumped system, integrated in time by the harness's RK4
//! ([`crate::time::rk4::rk4_step`], thesis (D.2)) with every contact force from the
//! library's stateful point (`jointlin_point_step`, trial forces from the committed
//! state, committed once per step, as [`crate::time::mhb_reference`] does), and its cycle by
//! cycle frequency and damping ratio: the reference a backbone is checked against.

use crate::capi::{self, POINT_STATE_LEN};
use crate::mhb::{AftError, Law, MhbError, System};
use crate::time::mhb_reference::{element_forces, element_slip};
use crate::time::rk4::rk4_step;

/// Samples of one DOF of a free decay.
#[derive(Debug, Clone)]
pub struct Decay {
    pub t: Vec<f64>,
    pub x: Vec<f64>,
}

/// Integrates M ẍ + D ẋ + K x + Σ Pᵀ F(P x) = 0 from (x0, v0) for `steps` steps of
/// length `dt` (S = 2n), recording DOF `dof`.
pub fn free_decay<const S: usize>(
    sys: &System,
    x0: &[f64],
    v0: &[f64],
    dt: f64,
    steps: usize,
    dof: usize,
) -> Result<Decay, MhbError> {
    let n = sys.n();
    assert_eq!(S, 2 * n, "state size");
    let minv = sys
        .m
        .clone()
        .try_inverse()
        .ok_or(MhbError::Singular { omega: 0.0 })?;
    let mut states = vec![[0.0; POINT_STATE_LEN]; sys.elements.len()];
    let mut y = [0.0; S];
    y[..n].copy_from_slice(x0);
    y[n..].copy_from_slice(v0);
    // Element forces from the committed states (the trial does not change them).
    let forces = |y: &[f64; S], states: &[[f64; POINT_STATE_LEN]]| element_forces(sys, y, states);
    let mut out = Decay {
        t: vec![0.0],
        x: vec![y[dof]],
    };
    for step in 1..=steps {
        let rhs = |_t: f64, y: &[f64; S]| -> [f64; S] {
            let Ok(fe) = forces(y, &states) else {
                return [f64::NAN; S];
            };
            let mut r = vec![0.0; n];
            for a in 0..n {
                for b in 0..n {
                    r[a] -= sys.k[(a, b)] * y[b] + sys.d[(a, b)] * y[n + b];
                }
            }
            for (e, f) in sys.elements.iter().zip(&fe) {
                r[e.i] -= f;
                if let Some(j) = e.j {
                    r[j] += f;
                }
            }
            let mut dy = [0.0; S];
            for a in 0..n {
                dy[a] = y[n + a];
                dy[n + a] = (0..n).map(|b| minv[(a, b)] * r[b]).sum();
            }
            dy
        };
        y = rk4_step(&rhs, 0.0, &y, dt);
        if y.iter().any(|v| !v.is_finite()) {
            forces(&y, &states)?;
            return Err(MhbError::Continuation(format!(
                "free decay not finite after {step} steps"
            )));
        }
        for (e, st) in sys.elements.iter().zip(states.iter_mut()) {
            if let Law::Point(tg) = e.law {
                let mut next = [0.0; POINT_STATE_LEN];
                capi::point_step(&tg, st, element_slip(&y, e.i, e.j), &mut next)
                    .map_err(AftError::from)?;
                *st = next;
            }
        }
        out.t.push(step as f64 * dt);
        out.x.push(y[dof]);
    }
    Ok(out)
}

/// One cycle of a decay, between consecutive upward zero crossings.
#[derive(Debug, Clone, Copy)]
pub struct CycleEstimate {
    /// First-harmonic amplitude over the cycle (length).
    pub amplitude: f64,
    /// Damped frequency 2π/period (rad/time).
    pub omega_d: f64,
    /// Damping ratio δ/√(4π² + δ²) from the logarithmic decrement δ to the next cycle.
    pub damping_ratio: f64,
}

/// Cycle estimates of a decay about a zero mean (the last cycle has no successor and is
/// dropped).
pub fn cycles(d: &Decay) -> Vec<CycleEstimate> {
    let mut cross = Vec::new();
    for k in 1..d.x.len() {
        let (a, b) = (d.x[k - 1], d.x[k]);
        if a < 0.0 && b >= 0.0 {
            let f = a / (a - b);
            cross.push((k - 1, d.t[k - 1] + f * (d.t[k] - d.t[k - 1])));
        }
    }
    // (amplitude, ω_d) per cycle.
    let per: Vec<(f64, f64)> = cross
        .windows(2)
        .map(|c| {
            let ((k0, t0), (k1, t1)) = (c[0], c[1]);
            let w = 2.0 * std::f64::consts::PI / (t1 - t0);
            // (2/T) ∫ x e^{−iωt} dt by the trapezoid rule over the cycle's samples.
            let (mut re, mut im) = (0.0, 0.0);
            for k in k0 + 1..=k1 {
                let dt = d.t[k] - d.t[k - 1];
                for (kk, wgt) in [(k - 1, 0.5 * dt), (k, 0.5 * dt)] {
                    let ph = w * (d.t[kk] - t0);
                    re += wgt * d.x[kk] * ph.cos();
                    im -= wgt * d.x[kk] * ph.sin();
                }
            }
            let amp = 2.0 / (t1 - t0) * re.hypot(im);
            (amp, w)
        })
        .collect();
    per.windows(2)
        .map(|p| {
            let delta = (p[0].0 / p[1].0).ln();
            CycleEstimate {
                amplitude: (p[0].0 * p[1].0).sqrt(),
                omega_d: 0.5 * (p[0].1 + p[1].1),
                damping_ratio: delta / (4.0 * std::f64::consts::PI.powi(2) + delta * delta).sqrt(),
            }
        })
        .collect()
}
