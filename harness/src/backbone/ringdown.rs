//! Free decay (ring-down) of a lumped system, integrated in time by the harness's RK4
//! ([`crate::time::rk4::rk4_step_slice`], thesis (D.2)) with every contact force from the
//! library's stateful point (`jointlin_point_step`, trial forces from the committed
//! state, committed once per step: [`crate::time::lumped`]), and its cycle by cycle
//! frequency and damping ratio: the reference a backbone is checked against.

use crate::mhb::contact3d::System3;
use crate::mhb::{MhbError, System};
use crate::time::lumped::{derivative, inverse_mass, Elements};
use crate::time::rk4::rk4_step_slice;

/// Samples of one DOF of a free decay.
#[derive(Debug, Clone)]
pub struct Decay {
    pub t: Vec<f64>,
    pub x: Vec<f64>,
}

/// Integrates M ẍ + D ẋ + K x + Σ Pᵀ F(P x) = 0 from (x0, v0) (virgin elements) for
/// `steps` steps of length `dt`, recording DOF `dof`.
pub fn free_decay(
    sys: &System,
    x0: &[f64],
    v0: &[f64],
    dt: f64,
    steps: usize,
    dof: usize,
) -> Result<Decay, MhbError> {
    let sys = System3 {
        linear: sys.clone(),
        elements: Vec::new(),
    };
    let n = sys.linear.n();
    let minv = inverse_mass(&sys.linear, 0.0)?;
    let mut elements = Elements::virgin(&sys);
    let mut y: Vec<f64> = x0.iter().chain(v0).copied().collect();
    let unloaded = vec![0.0; n];
    let mut out = Decay {
        t: vec![0.0],
        x: vec![y[dof]],
    };
    for step in 1..=steps {
        let rhs = |_t: f64, y: &[f64]| {
            derivative(&sys, &minv, &elements, y, &unloaded)
                .unwrap_or_else(|_| vec![f64::NAN; 2 * n])
        };
        y = rk4_step_slice(&rhs, 0.0, &y, dt);
        if y.iter().any(|v| !v.is_finite()) {
            derivative(&sys, &minv, &elements, &y, &unloaded)?;
            return Err(MhbError::Continuation(format!(
                "free decay not finite after {step} steps"
            )));
        }
        elements.commit(&sys, &y[..n])?;
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
