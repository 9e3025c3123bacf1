//! Steady state of one Jenkins cell (stiffness 1, stretch at the limit x = 1) driven on the
//! ellipse u(θ) = (a cos θ, b sin θ), from a virgin start at the centre and a straight ramp
//! to u(0) (docs/contact3d.md §4). The rate equations of [`super::cell`] (stick: ė = u̇;
//! slip: ė = u̇ − (ê·u̇)ê, slider speed ê·u̇) are integrated in θ by the classical
//! Runge–Kutta method, independent of the stepping code, with the stick→slip (|e| = 1)
//! and slip→stick (ê·u̇ = 0) switches located by bisection on the step length. The first
//! harmonics and the dissipated energy ride along as extra components of the ODE. Cycles
//! are repeated until the state at θ = 0 repeats.

use std::f64::consts::PI;

/// First-harmonic coefficients of the cell force τ = e (unit stiffness) over one steady
/// cycle, (1/π)∮τⱼ·{cos θ, sin θ} dθ, and the energy dissipated per cycle (unit k x²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellHarmonics {
    pub c1: f64,
    pub s1: f64,
    pub c2: f64,
    pub s2: f64,
    pub energy: f64,
}

/// Steps per cycle at least; the step also stays below STEP_BOUND·x/|u̇|.
const STEPS: usize = 2048;
const MAX_CYCLES: usize = 400;
/// Largest step times |u̇|/x: the slip relaxation (rate |u̇|/x per radian) must stay inside
/// the Runge–Kutta stability interval (|λh| < 2.78). 0.5, 1 and 2 gave the same
/// describing functions to 12 digits (32 Mindlin cells, four ellipses); 2 is 4× faster.
const STEP_BOUND: f64 = 2.0;

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Stick,
    Slip,
}

/// y = (e₁, e₂, ∫e₁cos, ∫e₁sin, ∫e₂cos, ∫e₂sin, dissipation).
type Y = [f64; 7];

struct Path {
    a: f64,
    b: f64,
}

impl Path {
    fn velocity(&self, th: f64) -> [f64; 2] {
        [-self.a * th.sin(), self.b * th.cos()]
    }

    fn rhs(&self, th: f64, y: &Y, mode: Mode) -> Y {
        let (s, c) = th.sin_cos();
        let v = [-self.a * s, self.b * c];
        let (mut de, mut diss) = (v, 0.0);
        if mode == Mode::Slip {
            let m = y[0].hypot(y[1]);
            let n = [y[0] / m, y[1] / m];
            let rate = n[0] * v[0] + n[1] * v[1];
            de = [v[0] - rate * n[0], v[1] - rate * n[1]];
            diss = rate;
        }
        [de[0], de[1], y[0] * c, y[0] * s, y[1] * c, y[1] * s, diss]
    }

    fn rk4(&self, th: f64, y: &Y, h: f64, mode: Mode) -> Y {
        let add = |y: &Y, k: &Y, f: f64| -> Y { std::array::from_fn(|i| y[i] + f * k[i]) };
        let k1 = self.rhs(th, y, mode);
        let k2 = self.rhs(th + h / 2.0, &add(y, &k1, h / 2.0), mode);
        let k3 = self.rhs(th + h / 2.0, &add(y, &k2, h / 2.0), mode);
        let k4 = self.rhs(th + h, &add(y, &k3, h), mode);
        std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }

    /// Switch function: < 0 while the mode holds, ≥ 0 when it must change.
    fn switch(&self, th: f64, y: &Y, mode: Mode) -> f64 {
        match mode {
            Mode::Stick => y[0] * y[0] + y[1] * y[1] - 1.0,
            Mode::Slip => {
                let v = self.velocity(th);
                -(y[0] * v[0] + y[1] * v[1])
            }
        }
    }

    /// One cycle from θ = 0: returns the state at 2π and the mode there.
    fn cycle(&self, mut y: Y, mut mode: Mode) -> (Y, Mode) {
        let speed = self.a.max(self.b);
        let n = STEPS.max((2.0 * PI * speed / STEP_BOUND).ceil() as usize);
        let h = 2.0 * PI / n as f64;
        for j in 0..n {
            let (mut th, end) = (j as f64 * h, (j + 1) as f64 * h);
            let mut guard = 0;
            while th < end && guard < 8 {
                guard += 1;
                let step = end - th;
                let trial = self.rk4(th, &y, step, mode);
                if self.switch(th + step, &trial, mode) < 0.0 {
                    y = trial;
                    if mode == Mode::Slip {
                        // Stay on |e| = 1 (the Runge–Kutta step drifts off at O(h⁵)).
                        let m = y[0].hypot(y[1]);
                        y[0] /= m;
                        y[1] /= m;
                    }
                    break;
                }
                // Locate the switch: largest σ with the mode still holding.
                let (mut lo, mut hi) = (0.0, step);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if self.switch(th + mid, &self.rk4(th, &y, mid, mode), mode) < 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                y = self.rk4(th, &y, hi, mode);
                th += hi;
                mode = match mode {
                    Mode::Stick => {
                        let m = y[0].hypot(y[1]);
                        y[0] /= m;
                        y[1] /= m;
                        Mode::Slip
                    }
                    Mode::Slip => Mode::Stick,
                };
            }
        }
        (y, mode)
    }
}

/// Steady-state harmonics of a unit cell on the ellipse (a, b ≥ 0 in units of the cell's
/// stretch at the limit). Returns the coefficients of the last cycle and whether the state
/// at θ = 0 repeated to 1e-12 within the cycle limit.
pub fn cell_on_ellipse(a: f64, b: f64) -> (CellHarmonics, bool) {
    let path = Path { a, b };
    // Virgin ramp from the centre to (a, 0): e = (min(a, 1), 0).
    let mut y: Y = [a.min(1.0), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let mut mode = if a >= 1.0 { Mode::Slip } else { Mode::Stick };
    let mut converged = false;
    let mut last = y;
    // Starts of consecutive cycles, s_{i+1} = P(s_i), for Aitken's Δ² extrapolation: a cell
    // that slips on a short arc per cycle forgets its sideways state slowly (contraction
    // close to 1 per cycle), so plain iteration would need thousands of cycles.
    // Aitken is used only while the contraction ratio is steady (a real dominant
    // eigenvalue); a spiralling approach is iterated plainly.
    let mut starts: Vec<[f64; 2]> = Vec::new();
    let mut changes: Vec<f64> = Vec::new();
    for _ in 0..MAX_CYCLES {
        let start = [y[0], y[1]];
        let (end, m) = path.cycle([y[0], y[1], 0.0, 0.0, 0.0, 0.0, 0.0], mode);
        last = end;
        mode = m;
        y = end;
        let change = (end[0] - start[0]).abs().max((end[1] - start[1]).abs());
        if change < 1e-12 {
            converged = true;
            break;
        }
        starts.push(start);
        changes.push(change);
        if changes.len() < 3 {
            continue;
        }
        let n = changes.len();
        let (r1, r2) = (
            changes[n - 2] / changes[n - 3],
            changes[n - 1] / changes[n - 2],
        );
        let steady = (r2 - r1).abs() < 0.01 * r2 && r2 < 0.9999;
        if steady && change * r2 / (1.0 - r2) < 1e-12 {
            converged = true;
            break;
        }
        if steady {
            let (s0, s1, s2) = (starts[n - 2], starts[n - 1], [end[0], end[1]]);
            let mut jump = s2;
            for i in 0..2 {
                let den = (s2[i] - s1[i]) - (s1[i] - s0[i]);
                if den != 0.0 {
                    jump[i] = s2[i] - (s2[i] - s1[i]).powi(2) / den;
                }
            }
            let m = jump[0].hypot(jump[1]);
            if m >= 1.0 {
                jump = [jump[0] / m, jump[1] / m];
            }
            y[0] = jump[0];
            y[1] = jump[1];
            mode = if m >= 1.0 { Mode::Slip } else { Mode::Stick };
            starts.clear();
            changes.clear();
        }
    }
    let h = CellHarmonics {
        c1: last[2] / PI,
        s1: last[3] / PI,
        c2: last[4] / PI,
        s2: last[5] / PI,
        energy: last[6],
    };
    (h, converged)
}
