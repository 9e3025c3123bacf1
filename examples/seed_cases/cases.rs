//! The seed thesis's single-point cases, computed by us: the Duffing oscillator (4.1,
//! Appendix B) and the block on a plane in the stick case (4.2, Appendix C, model.md §8).
//!
//! Shared by `examples/seed_cases/main.rs` (the table and `--json`) and
//! `tests/seed_cases.rs` (the same numbers asserted), so both report the same code's output.

#![allow(dead_code)] // each includer uses its own subset

use jointlin::hysteresis::{Point, PointState, Rule};
use jointlin::iterate::{solve_point, IterateError, Options, PointProblem};
use jointlin::law::TangentialLaw;
use jointlin::linearize::Contact;
use std::f64::consts::PI;

// ------------------------------------------------------------------------ thesis figures

/// 4.1: first-order harmonic balance amplitude of the Duffing oscillator.
pub const THESIS_DUFFING_HBM: f64 = 0.395;
/// 4.1: Runge–Kutta steady-state maximum (the thesis's rounded figure, model.md §8).
pub const THESIS_DUFFING_RK: f64 = 0.393;
/// The steady maximum of an independent integration (adaptive Dormand–Prince 5(4),
/// tolerance 1e-12, no code shared with the library): `python3 scripts/duffing_reference.py`
/// prints it (tests/seed_cases.rs runs it and compares).
pub const INDEPENDENT_DUFFING_RK: f64 = 0.395574;
/// 4.2.4, stick case F̂ = 0.5 N (mm): first positive peak, next negative peak, their mean
/// half-width, and the linearized amplitude.
pub const THESIS_BLOCK_PEAK_POS: f64 = 4.904e-4;
pub const THESIS_BLOCK_PEAK_NEG: f64 = -3.899e-4;
pub const THESIS_BLOCK_MEAN: f64 = 4.401e-4;
pub const THESIS_BLOCK_LINEARIZED: f64 = 4.267e-4;
/// 4.2.4, slip case: linearized maximum displacement (mm), F̂ = 0.75 N in model.md's reading.
pub const THESIS_BLOCK_SLIP_LINEARIZED: f64 = 40.86;

// ------------------------------------------------------------------------ Runge–Kutta

/// One classical Runge–Kutta step (D.2) of x' = f(t, x) with step h.
pub fn rk4_step<const N: usize>(
    f: &impl Fn(f64, &[f64; N]) -> [f64; N],
    t: f64,
    x: &[f64; N],
    h: f64,
) -> [f64; N] {
    let add = |a: &[f64; N], b: &[f64; N], s: f64| -> [f64; N] {
        std::array::from_fn(|i| a[i] + s * b[i])
    };
    let k1 = f(t, x); // (D.2)
    let k2 = f(t + 0.5 * h, &add(x, &k1, 0.5 * h));
    let k3 = f(t + 0.5 * h, &add(x, &k2, 0.5 * h));
    let k4 = f(t + h, &add(x, &k3, h));
    std::array::from_fn(|i| x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
}

/// Refines an extremum of x₀ inside the step [t, t + h] where x₁ = ẋ changes sign: Newton
/// on the step fraction τ, each trial a fresh RK4 step of size τh from the step's start
/// (so the extremum carries RK4 accuracy), d ẋ/dτ = h ẍ. Returns x₀ there.
fn refine_extremum(
    f: &impl Fn(f64, &[f64; 2]) -> [f64; 2],
    t: f64,
    start: &[f64; 2],
    end: &[f64; 2],
    h: f64,
) -> f64 {
    // Linear guess from the velocities at both ends.
    let mut tau = (start[1] / (start[1] - end[1])).clamp(0.0, 1.0);
    for _ in 0..20 {
        let x = rk4_step(f, t, start, tau * h);
        let acc = f(t + tau * h, &x)[1];
        if acc == 0.0 {
            break;
        }
        let next = (tau - x[1] / (h * acc)).clamp(0.0, 1.0);
        let done = (next - tau).abs() < 1e-13;
        tau = next;
        if done {
            break;
        }
    }
    rk4_step(f, t, start, tau * h)[0]
}

// ------------------------------------------------------------------------ Duffing

/// ẍ + d ẋ + k x + α x³ = F sin(ω t) (4.1).
#[derive(Debug, Clone, Copy)]
pub struct Duffing {
    pub d: f64,
    pub k: f64,
    pub alpha: f64,
    pub force: f64,
    pub omega: f64,
}

impl Duffing {
    /// (B.1): ẍ + ẋ + 20x + 40x³ = 30 sin(10t), x(0) = 0.2, ẋ(0) = 0.
    pub fn appendix_b() -> Self {
        Self {
            d: 1.0,
            k: 20.0,
            alpha: 40.0,
            force: 30.0,
            omega: 10.0,
        }
    }

    /// All first-order harmonic balance amplitudes, ascending.
    ///
    /// With x = A sin(ωt − φ), (3.8) applied to αx³ gives the equivalent stiffness 3αA²/4;
    /// balancing the sine and cosine parts, [(k − ω² + 3αA²/4)² + (dω)²] A² = F². In
    /// u = A² that is the cubic c₃u³ + c₂u² + c₁u + c₀ = 0 with c₃ = (3α/4)²,
    /// c₂ = 2(k − ω²)(3α/4), c₁ = (k − ω²)² + (dω)², c₀ = −F², solved in closed form.
    pub fn hbm_amplitudes(&self) -> Vec<f64> {
        let b = 0.75 * self.alpha;
        let detune = self.k - self.omega * self.omega;
        let c = [
            -self.force * self.force,
            detune * detune + (self.d * self.omega).powi(2),
            2.0 * detune * b,
            b * b,
        ];
        let mut amps: Vec<f64> = cubic_real_roots(c)
            .into_iter()
            .filter(|&u| u > 0.0)
            .map(f64::sqrt)
            .collect();
        amps.sort_by(f64::total_cmp);
        amps
    }

    /// ẋ = f(t, x) in first-order form (x, ẋ).
    pub fn rhs(&self) -> impl Fn(f64, &[f64; 2]) -> [f64; 2] + '_ {
        move |t, s| {
            let [x, v] = *s;
            [
                v,
                self.force * (self.omega * t).sin()
                    - self.d * v
                    - self.k * x
                    - self.alpha * x * x * x, // (4.1)
            ]
        }
    }

    /// Steady-state maximum by RK4 (Appendix D) from x(0) = x0, ẋ(0) = 0 with step h: the
    /// largest refined maximum over `periods` forcing periods after `settle` time units.
    /// Also returns the spread (largest − smallest) of those per-period maxima, a check that
    /// the motion is periodic with the forcing period.
    pub fn rk4_steady_max(&self, x0: f64, h: f64, settle: f64, periods: usize) -> (f64, f64) {
        let f = self.rhs();
        let end = settle + periods as f64 * 2.0 * PI / self.omega;
        let steps = (end / h).ceil() as usize;
        let mut s = [x0, 0.0];
        let mut peaks = Vec::new();
        for n in 0..steps {
            let t = n as f64 * h;
            let next = rk4_step(&f, t, &s, h);
            if t >= settle && s[1] > 0.0 && next[1] <= 0.0 {
                peaks.push(refine_extremum(&f, t, &s, &next, h));
            }
            s = next;
        }
        let max = peaks.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min = peaks.iter().copied().fold(f64::INFINITY, f64::min);
        (max, max - min)
    }
}

/// Real roots of c[3]u³ + c[2]u² + c[1]u + c[0] = 0 (c[3] ≠ 0): Viète's trigonometric form
/// for three real roots, Cardano's for one; each polished by one Newton step (a rounding
/// clean-up: the closed form is exact, its evaluation loses a few digits to cancellation).
pub fn cubic_real_roots(c: [f64; 4]) -> Vec<f64> {
    let (a2, a1, a0) = (c[2] / c[3], c[1] / c[3], c[0] / c[3]);
    // u = y − a2/3: y³ + p y + q = 0.
    let p = a1 - a2 * a2 / 3.0;
    let q = 2.0 * a2.powi(3) / 27.0 - a2 * a1 / 3.0 + a0;
    let shift = -a2 / 3.0;
    let disc = (q / 2.0).powi(2) + (p / 3.0).powi(3);
    let ys: Vec<f64> = if disc < 0.0 {
        let r = 2.0 * (-p / 3.0).sqrt();
        let phi = ((3.0 * q / (p * r)).clamp(-1.0, 1.0)).acos() / 3.0;
        (0..3)
            .map(|k| r * (phi - 2.0 * PI * k as f64 / 3.0).cos())
            .collect()
    } else {
        let sq = disc.sqrt();
        vec![(-q / 2.0 + sq).cbrt() + (-q / 2.0 - sq).cbrt()]
    };
    ys.into_iter()
        .map(|y| {
            let u = y + shift;
            let val = ((c[3] * u + c[2]) * u + c[1]) * u + c[0];
            let der = (3.0 * c[3] * u + 2.0 * c[2]) * u + c[1];
            if der != 0.0 {
                u - val / der
            } else {
                u
            }
        })
        .collect()
}

// ------------------------------------------------------------------------ block

/// The block of Appendix C in N, mm, s, t (model.md §8): μ = 0.3, k_T0 = 1282.7 N/mm,
/// F_N = 2 N, m = 2 kg = 0.002 t, ω = 1.3 rad/s, thesis unloading rule.
pub fn block(forcing: f64) -> PointProblem {
    PointProblem {
        contact: Contact {
            law: TangentialLaw::Mindlin,
            rule: Rule::Thesis,
            mu: 0.3,
            normal_force: 2.0,
            k_t0: 1282.7,
        },
        mass: 0.002,
        forcing,
        omega: 1.3,
        ground_stiffness: 0.0,
        ground_damping: 0.0,
    }
}

/// Time-domain response of the block from rest (mm).
#[derive(Debug, Clone, Copy)]
pub struct BlockPeaks {
    /// Largest displacement during the first positive force half-period (0, π/ω).
    pub first_pos: f64,
    /// Smallest displacement during the next half-period (π/ω, 2π/ω).
    pub next_neg: f64,
    /// Largest displacement during the second positive half-period (2π/ω, 3π/ω).
    pub second_pos: f64,
    /// Time steps taken.
    pub steps: usize,
}

impl BlockPeaks {
    /// Half the loop width, (first_pos − next_neg)/2, as the thesis averages its peaks.
    pub fn mean_amplitude(&self) -> f64 {
        0.5 * (self.first_pos - self.next_neg)
    }
}

/// Steps per period of the contact's own vibration 2π/√(k_T0/m) (7.85 ms for the block):
/// the RK4 step is that period over this number.
pub const BLOCK_STEPS_PER_CONTACT_PERIOD: f64 = 200.0;

/// m ẍ = F̂ sin ωt − F_T(x) with the library's stateful hysteresis point (ground fixed, so
/// the slip is x), integrated by RK4 from rest. Stages evaluate the contact force on trial
/// states (`Point::step` is pure); the state is committed once per accepted step.
/// Returns the peaks over 1.5 forcing periods. `refine` multiplies the steps per contact
/// period (1 for the default, 2 for the step-halving check).
pub fn block_time_domain(problem: &PointProblem, refine: f64) -> BlockPeaks {
    let c = &problem.contact;
    let point = Point::new(
        jointlin::law::Backbone::new(c.law, c.mu * c.normal_force, c.k_t0)
            .expect("valid block backbone"),
        c.rule,
    );
    let (m, f_hat, w) = (problem.mass, problem.forcing, problem.omega);
    let contact_period = 2.0 * PI / (c.k_t0 / m).sqrt();
    let half = PI / w;
    let steps_per_half = (half / contact_period * BLOCK_STEPS_PER_CONTACT_PERIOD * refine).ceil();
    let h = half / steps_per_half;
    let steps = 3 * steps_per_half as usize;
    let mut committed = PointState::virgin(c.rule, 0.0);
    let mut s = [0.0, 0.0];
    let mut extremes = [f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
    for n in 0..steps {
        let t = n as f64 * h;
        let state = committed;
        let rhs = |t: f64, y: &[f64; 2]| -> [f64; 2] {
            let force = point.step(&state, y[0]).expect("finite slip").1.force;
            [y[1], (f_hat * (w * t).sin() - force) / m] // (4.2) with the nonlinear contact
        };
        let next = rk4_step(&rhs, t, &s, h);
        let window = n / steps_per_half as usize; // 0: (0, T/2), 1: (T/2, T), 2: (T, 3T/2)
                                                  // Extremum inside the step: ẋ turns + → − (a maximum, windows 0 and 2) or − → +
                                                  // (a minimum, window 1); refined to RK4 accuracy.
        let turns = if window == 1 {
            s[1] < 0.0 && next[1] >= 0.0
        } else {
            s[1] > 0.0 && next[1] <= 0.0
        };
        let x = if turns {
            refine_extremum(&rhs, t, &s, &next, h)
        } else {
            next[0]
        };
        extremes[window] = if window == 1 {
            extremes[window].min(x)
        } else {
            extremes[window].max(x)
        };
        committed = point.step(&state, next[0]).expect("finite slip").0;
        s = next;
    }
    BlockPeaks {
        first_pos: extremes[0],
        next_neg: extremes[1],
        second_pos: extremes[2],
        steps,
    }
}

/// The linearized block amplitude (mm) from `solve_point` with the default method.
pub fn block_linearized(problem: &PointProblem) -> Result<f64, IterateError> {
    solve_point(problem, &Options::default()).map(|s| s.amplitude)
}

// ------------------------------------------------------------------------ all together

/// Every number of the table, computed once.
#[derive(Debug, Clone)]
pub struct SeedResults {
    pub duffing_hbm_roots: Vec<f64>,
    /// The lower-branch root, the one the thesis reports (see `main.rs`).
    pub duffing_hbm_amplitude: f64,
    pub duffing_rk_amplitude: f64,
    /// |max(h) − max(h/2)|: the step-halving check of the RK4 maximum.
    pub duffing_rk_halving_change: f64,
    pub duffing_rk_step: f64,
    pub block: BlockPeaks,
    /// Largest change of the three block peaks when the step is halved (mm).
    pub block_halving_change: f64,
    pub block_linearized: f64,
    /// The slip case F̂ = 0.75 N: what `solve_point` says.
    pub block_slip: Result<f64, IterateError>,
}

/// RK4 step for the Duffing case: 1/400 of the forcing period (measured: the maximum then
/// changes by < 1e-10 when the step is halved).
pub const DUFFING_STEPS_PER_PERIOD: f64 = 400.0;
/// Settling time for the Duffing case: the free transient decays like e^{−d t/2}, so after
/// 60 time units it is below e^{−30} ≈ 1e-13 of its start.
pub const DUFFING_SETTLE: f64 = 60.0;

pub fn compute() -> SeedResults {
    let duffing = Duffing::appendix_b();
    let roots = duffing.hbm_amplitudes();
    let h = 2.0 * PI / duffing.omega / DUFFING_STEPS_PER_PERIOD;
    let (rk, _) = duffing.rk4_steady_max(0.2, h, DUFFING_SETTLE, 5);
    let (rk_half, _) = duffing.rk4_steady_max(0.2, 0.5 * h, DUFFING_SETTLE, 5);
    let stick = block(0.5);
    let peaks = block_time_domain(&stick, 1.0);
    let fine = block_time_domain(&stick, 2.0);
    let block_halving_change = [
        (peaks.first_pos - fine.first_pos).abs(),
        (peaks.next_neg - fine.next_neg).abs(),
        (peaks.second_pos - fine.second_pos).abs(),
    ]
    .into_iter()
    .fold(0.0, f64::max);
    SeedResults {
        duffing_hbm_amplitude: roots[0],
        duffing_hbm_roots: roots,
        duffing_rk_amplitude: rk_half,
        duffing_rk_halving_change: (rk - rk_half).abs(),
        duffing_rk_step: 0.5 * h,
        block: fine,
        block_halving_change,
        block_linearized: block_linearized(&stick).expect("stick case converges"),
        block_slip: block_linearized(&block(0.75)),
    }
}

/// Deviation of ours from the thesis in percent of the thesis's value.
pub fn deviation_percent(ours: f64, thesis: f64) -> f64 {
    100.0 * (ours - thesis) / thesis.abs()
}
