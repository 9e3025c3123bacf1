//! Cycle statistics and the periodic-steady-state test.
//!
//! A cycle is N steps of h = T/N: samples x_k = x(t_k), t_k = t₀ + k h, k = 1..N. The first
//! harmonic û = (2/N) Σ x_k e^{−iωt_k} (the rectangle rule on one period, exact for
//! trigonometric polynomials of degree < N − 1), so x(t) ≈ x̄ + Re(û e^{iωt}); the peaks are
//! the largest and smallest sample; the energy a point dissipates in the cycle is the
//! increase of its accumulated dissipation (the library's ∮ F·dδ, per increment exact for
//! its law), cross-checked by a trapezoid sum of F·Δδ over the tangential components.
//!
//! Steady state: Δ_c = the largest change from the previous cycle of an output's first
//! harmonic (relative to the largest one, at least 1e-9 of the largest |sample|: below
//! that a harmonic is a static state's round-off) and of the total joint energy per cycle
//! (relative to itself). A transient that decays by a factor ρ per cycle leaves the distance
//! Δ_c ρ/(1 − ρ) to the periodic state; the test uses d_c = Δ_c · max(1, ρ/(1 − ρ)) with ρ
//! the larger of the last two ratios Δ_c/Δ_{c−1} (capped at 0.999).

use serde::Serialize;

use super::C64;

/// One output over one cycle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OutputCycle {
    /// First-harmonic complex amplitude û (u ≈ x̄ + Re(û e^{iωt})).
    #[serde(skip)]
    pub harmonic: C64,
    pub amplitude: f64,
    pub phase_deg: f64,
    pub mean: f64,
    pub max: f64,
    pub min: f64,
}

impl OutputCycle {
    /// Half the peak-to-peak range (the thesis's "mean amplitude" of a loop).
    pub fn half_range(&self) -> f64 {
        0.5 * (self.max - self.min)
    }
}

/// Everything measured over one cycle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CycleStats {
    pub outputs: Vec<OutputCycle>,
    /// Energy dissipated per point in the cycle (force·length).
    pub point_energy: Vec<f64>,
    /// Σ point_energy.
    pub energy: f64,
    /// Σ over points and tangential components of ½(F_old + F_new)·Δδ (check of `energy`).
    pub energy_trapezoid: f64,
}

/// Accumulates one cycle.
#[derive(Debug, Clone)]
pub struct Cycle {
    omega: f64,
    n: usize,
    k: usize,
    sum: Vec<C64>,
    mean: Vec<f64>,
    max: Vec<f64>,
    min: Vec<f64>,
    start_energy: Vec<f64>,
    trapezoid: f64,
}

impl Cycle {
    /// A cycle of `n` samples of `nout` outputs, starting with the points' accumulated
    /// dissipation `dissipated`.
    pub fn new(omega: f64, n: usize, nout: usize, dissipated: Vec<f64>) -> Self {
        Cycle {
            omega,
            n,
            k: 0,
            sum: vec![C64::new(0.0, 0.0); nout],
            mean: vec![0.0; nout],
            max: vec![f64::NEG_INFINITY; nout],
            min: vec![f64::INFINITY; nout],
            start_energy: dissipated,
            trapezoid: 0.0,
        }
    }

    /// Adds the sample at time t.
    pub fn push(&mut self, t: f64, x: &[f64]) {
        let e = C64::from_polar(1.0, -self.omega * t);
        for (o, &v) in x.iter().enumerate() {
            self.sum[o] += e * v;
            self.mean[o] += v;
            self.max[o] = self.max[o].max(v);
            self.min[o] = self.min[o].min(v);
        }
        self.k += 1;
    }

    /// Adds ½(F_old + F_new)·(δ_new − δ_old) over the tangential components of every point.
    pub fn add_work(
        &mut self,
        f_old: &[[f64; 3]],
        f_new: &[[f64; 3]],
        d_old: &[[f64; 3]],
        d_new: &[[f64; 3]],
    ) {
        for i in 0..f_old.len() {
            for k in 1..3 {
                self.trapezoid += 0.5 * (f_old[i][k] + f_new[i][k]) * (d_new[i][k] - d_old[i][k]);
            }
        }
    }

    /// Samples pushed so far.
    pub fn len(&self) -> usize {
        self.k
    }

    pub fn is_empty(&self) -> bool {
        self.k == 0
    }

    /// Whether the cycle has its N samples.
    pub fn full(&self) -> bool {
        self.k >= self.n
    }

    /// The statistics, given the points' accumulated dissipation now.
    pub fn finish(&self, dissipated: &[f64]) -> CycleStats {
        let n = self.k.max(1) as f64;
        let outputs = (0..self.sum.len())
            .map(|o| {
                let h = self.sum[o] * (2.0 / n);
                OutputCycle {
                    harmonic: h,
                    amplitude: h.norm(),
                    phase_deg: h.arg().to_degrees(),
                    mean: self.mean[o] / n,
                    max: self.max[o],
                    min: self.min[o],
                }
            })
            .collect();
        let point_energy: Vec<f64> = dissipated
            .iter()
            .zip(&self.start_energy)
            .map(|(a, b)| a - b)
            .collect();
        CycleStats {
            outputs,
            energy: point_energy.iter().sum(),
            point_energy,
            energy_trapezoid: self.trapezoid,
        }
    }
}

/// Energies below this fraction of the excitation work scale count as "no dissipation"
/// in the change measure (a stuck joint dissipates only round-off).
const ENERGY_FLOOR: f64 = 1e-300;

/// A first harmonic below this share of an output's magnitude (its largest |sample|) is
/// the round-off of a static state: the change is measured against this floor, so an
/// unloaded (or nearly unloaded) model is periodic at once instead of never.
const ROUND_OFF_SHARE: f64 = 1e-9;

/// Relative change of cycle `b` from cycle `a`.
pub fn change(a: &CycleStats, b: &CycleStats) -> f64 {
    let scale = b
        .outputs
        .iter()
        .fold(0.0f64, |m, o| {
            let magnitude = o.max.abs().max(o.min.abs());
            m.max(o.harmonic.norm()).max(ROUND_OFF_SHARE * magnitude)
        })
        .max(f64::MIN_POSITIVE);
    let mut d = a.outputs.iter().zip(&b.outputs).fold(0.0f64, |m, (x, y)| {
        m.max((x.harmonic - y.harmonic).norm() / scale)
    });
    if b.energy.abs() > ENERGY_FLOOR {
        d = d.max((b.energy - a.energy).abs() / b.energy.abs());
    }
    d
}

/// The steady-state test over the sequence of cycle changes.
#[derive(Debug, Clone, Default)]
pub struct SteadyTest {
    changes: Vec<f64>,
}

impl SteadyTest {
    /// Records the change Δ_c of the latest cycle; returns the estimated distance d_c.
    pub fn push(&mut self, delta: f64) -> f64 {
        self.changes.push(delta);
        self.distance()
    }

    /// d_c = Δ_c · max(1, ρ/(1 − ρ)) (module docs); ∞ before two changes exist.
    pub fn distance(&self) -> f64 {
        let n = self.changes.len();
        if n < 2 {
            return f64::INFINITY;
        }
        let last = self.changes[n - 1];
        if last == 0.0 {
            return 0.0;
        }
        let ratio = |i: usize| {
            let (a, b) = (self.changes[i - 1], self.changes[i]);
            if a > 0.0 {
                b / a
            } else {
                1.0
            }
        };
        let mut rho = ratio(n - 1);
        if n >= 3 {
            rho = rho.max(ratio(n - 2));
        }
        let rho = rho.min(0.999);
        last * (rho / (1.0 - rho)).max(1.0)
    }

    /// Changes recorded.
    pub fn changes(&self) -> &[f64] {
        &self.changes
    }
}
