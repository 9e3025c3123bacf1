//! A lumped system in the time domain (M ẍ + D ẋ + K x + g(x) = f₀ + s(t)·Re(f̂ e^{iωt})):
//! the harness's RK4 ([`rk4_step_slice`], thesis (D.2)) on the first-order form, g the
//! system's elements — cubic springs k₃δ³, the one-direction joints through the library's
//! point (`jointlin_point_step`), the three-direction points through
//! `jointlin_point3d_step` ([`crate::mhb::contact3d::step`]) — every stage evaluated from
//! the committed states (a trial), the states committed once per accepted step; until the
//! harness's cycle test ([`crate::time::periodic`]) finds the motion periodic.
//!
//! Per cycle: the first harmonic and peaks of every DOF and of the given outputs, the
//! energy each element dissipates (the library's accumulated dissipation), a trapezoid
//! sum of F·Δδ over the tangential components as its check, every point's normal force
//! range, and the element loops (displacement and force at each step of the cycle).

use std::time::Instant;

use nalgebra::DMatrix;

use super::periodic::{change, Cycle, CycleStats, SteadyTest};
use super::ramp;
use super::rk4::rk4_step_slice;
use crate::capi::{self, POINT_STATE_LEN};
use crate::mhb::contact3d::{step as point3_step, States, System3, VIRGIN};
pub use crate::mhb::loops::{element_slip, LoopSample};
use crate::mhb::{AftError, Law, MhbError, System};

/// Committed element states with what they did so far.
#[derive(Debug, Clone)]
pub struct Elements {
    /// The library's state per one-direction element (unused by cubic springs).
    pub one_d: Vec<[f64; POINT_STATE_LEN]>,
    /// The states per three-direction point.
    pub points: Vec<States>,
    /// Energy dissipated since the start per element (one-direction elements, then
    /// points; force·length).
    pub dissipated: Vec<f64>,
    /// The committed sample per element (one-direction elements, then points).
    pub sample: Vec<LoopSample>,
}

impl Elements {
    /// Virgin states of `sys`'s elements (nothing dissipated).
    pub fn virgin(sys: &System3) -> Self {
        let count = sys.linear.elements.len() + sys.elements.len();
        Elements {
            one_d: vec![[0.0; POINT_STATE_LEN]; sys.linear.elements.len()],
            points: vec![VIRGIN; sys.elements.len()],
            dissipated: vec![0.0; count],
            sample: vec![LoopSample::default(); count],
        }
    }

    /// The samples of every element at displacements `y` from the committed states and,
    /// per element, the energy the increment dissipates and its new state (a trial when
    /// the result is dropped).
    fn evaluate(&self, sys: &System3, y: &[f64]) -> Result<Trial, MhbError> {
        let mut t = Trial {
            samples: Vec::with_capacity(self.sample.len()),
            dissipated: Vec::with_capacity(self.sample.len()),
            one_d: self.one_d.clone(),
            points: self.points.clone(),
        };
        for ((e, from), to) in sys
            .linear
            .elements
            .iter()
            .zip(&self.one_d)
            .zip(&mut t.one_d)
        {
            let d = element_slip(y, e.i, e.j);
            let (force, dissipated) = match e.law {
                Law::Cubic(k3) => (
                    capi::cubic_force(0.0, k3, d).map_err(AftError::from)?.0,
                    0.0,
                ),
                Law::Point(tg) => {
                    let s = capi::point_step(&tg, from, d, to).map_err(AftError::from)?;
                    (s.force, s.dissipated)
                }
            };
            t.samples.push(LoopSample {
                displacement: [d, 0.0, 0.0],
                force: [force, 0.0, 0.0],
            });
            t.dissipated.push(dissipated);
        }
        for ((e, from), to) in sys.elements.iter().zip(&self.points).zip(&mut t.points) {
            let disp = e.displacement(y);
            let (force, dissipated) =
                point3_step(&e.contact, e.coupled, from, disp, to).map_err(AftError::from)?;
            t.samples.push(LoopSample {
                displacement: disp,
                force,
            });
            t.dissipated.push(dissipated);
        }
        Ok(t)
    }

    /// The internal force vector g at `y` (a trial from the committed states).
    fn internal(&self, sys: &System3, y: &[f64]) -> Result<Vec<f64>, MhbError> {
        let t = self.evaluate(sys, y)?;
        let mut g = vec![0.0; sys.linear.n()];
        let one_d = sys.linear.elements.len();
        for (e, s) in sys.linear.elements.iter().zip(&t.samples) {
            g[e.i] += s.force[0];
            if let Some(j) = e.j {
                g[j] -= s.force[0];
            }
        }
        for (e, s) in sys.elements.iter().zip(&t.samples[one_d..]) {
            e.add_internal(s.force, &mut g);
        }
        Ok(g)
    }

    /// Moves the states to `y` (one increment from the committed ones).
    pub fn commit(&mut self, sys: &System3, y: &[f64]) -> Result<(), MhbError> {
        let t = self.evaluate(sys, y)?;
        for (acc, d) in self.dissipated.iter_mut().zip(&t.dissipated) {
            *acc += d;
        }
        self.one_d = t.one_d;
        self.points = t.points;
        self.sample = t.samples;
        Ok(())
    }
}

/// One evaluation of every element.
struct Trial {
    samples: Vec<LoopSample>,
    dissipated: Vec<f64>,
    one_d: Vec<[f64; POINT_STATE_LEN]>,
    points: Vec<States>,
}

/// The dynamic state of a lumped system.
#[derive(Debug, Clone)]
pub struct LumpedState {
    pub x: Vec<f64>,
    pub v: Vec<f64>,
    pub elements: Elements,
}

impl LumpedState {
    /// At x0, v0 with virgin elements (the first step loads them from there).
    pub fn virgin(sys: &System3, x0: &[f64], v0: &[f64]) -> Self {
        LumpedState {
            x: x0.to_vec(),
            v: v0.to_vec(),
            elements: Elements::virgin(sys),
        }
    }

    /// At rest at the static displacement `xs`, the elements loaded there from virgin in
    /// one increment (the static step's load path: stuck from a virgin contact) and their
    /// dissipation counted from there.
    pub fn at_rest(sys: &System3, xs: &[f64]) -> Result<Self, MhbError> {
        let mut st = LumpedState::virgin(sys, xs, &vec![0.0; xs.len()]);
        st.elements.commit(sys, xs)?;
        st.elements.dissipated.fill(0.0);
        Ok(st)
    }
}

/// How to integrate at one frequency.
#[derive(Debug, Clone, Copy)]
pub struct Integration {
    /// ω (rad/time).
    pub omega: f64,
    /// RK4 steps per period 2π/ω.
    pub steps: usize,
    /// Excitation ramp length in periods (0: full excitation at once).
    pub ramp_cycles: f64,
    /// Periodic when the estimated distance to the periodic state is below this.
    pub tolerance: f64,
    pub min_cycles: usize,
    pub max_cycles: usize,
}

/// What one frequency's integration found.
#[derive(Debug, Clone)]
pub struct Settled {
    pub cycles: usize,
    pub steady: bool,
    /// Estimated relative distance to the periodic state after the last cycle.
    pub distance: f64,
    /// The last cycle: per DOF, then per output, its first harmonic and peaks; per
    /// element (one-direction, then points) its dissipated energy.
    pub last: CycleStats,
    /// Per point: the smallest and largest normal force over the last cycle (force).
    pub normal_range: Vec<(f64, f64)>,
    /// Per step of the last cycle, per element: its sample.
    pub loops: Vec<Vec<LoopSample>>,
    pub steps: usize,
    pub seconds: f64,
}

/// M⁻¹ of `s` (dense: lumped systems are small), or an error naming ω.
pub fn inverse_mass(s: &System, omega: f64) -> Result<DMatrix<f64>, MhbError> {
    s.m.clone()
        .try_inverse()
        .ok_or(MhbError::Singular { omega })
}

/// The first-order form's derivative (ẋ, M⁻¹(f − K x − D ẋ − g(x))) at y = (x, ẋ) under
/// the load `f`, g from the committed element states `el` (a trial).
pub fn derivative(
    sys: &System3,
    minv: &DMatrix<f64>,
    el: &Elements,
    y: &[f64],
    f: &[f64],
) -> Result<Vec<f64>, MhbError> {
    let s = &sys.linear;
    let n = s.n();
    let g = el.internal(sys, &y[..n])?;
    let r: Vec<f64> = (0..n)
        .map(|a| {
            let lin: f64 = (0..n)
                .map(|b| s.k[(a, b)] * y[b] + s.d[(a, b)] * y[n + b])
                .sum();
            f[a] - lin - g[a]
        })
        .collect();
    let mut out = y[n..].to_vec();
    out.extend((0..n).map(|a| (0..n).map(|b| minv[(a, b)] * r[b]).sum::<f64>()));
    Ok(out)
}

/// Integrates `sys` from `st` (time 0) as `run` says, the outputs given by their weights
/// over the DOFs; leaves `st` at the end state.
pub fn settle(
    sys: &System3,
    st: &mut LumpedState,
    run: &Integration,
    outputs: &[Vec<f64>],
) -> Result<Settled, MhbError> {
    let clock = Instant::now();
    let s = &sys.linear;
    let (n, omega) = (s.n(), run.omega);
    let minv = inverse_mass(s, omega)?;
    let period = std::f64::consts::TAU / omega;
    let h = period / run.steps as f64;
    let ramp_length = run.ramp_cycles * period;
    let load = |t: f64| -> Vec<f64> {
        let (sn, cs) = (omega * t).sin_cos();
        let sr = ramp(t, ramp_length);
        (0..n)
            .map(|a| s.f0[a] + sr * (s.f1[a].re * cs - s.f1[a].im * sn))
            .collect()
    };
    let rhs = |t: f64, y: &[f64], el: &Elements| derivative(sys, &minv, el, y, &load(t));
    let sample = |x: &[f64]| -> Vec<f64> {
        let mut v = x.to_vec();
        v.extend(
            outputs
                .iter()
                .map(|w| w.iter().zip(x).map(|(w, x)| w * x).sum::<f64>()),
        );
        v
    };
    let mut y: Vec<f64> = st.x.iter().chain(&st.v).copied().collect();
    let mut test = SteadyTest::default();
    let mut prev: Option<CycleStats> = None;
    let (mut distance, mut steady, mut cycles) = (f64::INFINITY, false, 0);
    let mut loops = Vec::new();
    let mut t = 0.0;
    let ramp_end = run.ramp_cycles.ceil() as usize;
    while cycles < run.max_cycles.max(1) {
        let mut cyc = Cycle::new(
            omega,
            run.steps,
            n + outputs.len(),
            st.elements.dissipated.clone(),
        );
        loops.clear();
        for k in 1..=run.steps {
            // A failed library call in a stage makes that stage's derivative NaN; the step
            // is then re-evaluated below for the call's own error.
            let f = |tt: f64, yy: &[f64]| {
                rhs(tt, yy, &st.elements).unwrap_or_else(|_| vec![f64::NAN; 2 * n])
            };
            y = rk4_step_slice(&f, t, &y, h);
            t = (cycles * run.steps + k) as f64 * h;
            if y.iter().any(|v| !v.is_finite()) {
                rhs(t, &y, &st.elements)?;
                return Err(MhbError::Continuation(format!(
                    "time integration not finite at t = {t:.6e}"
                )));
            }
            let f_old = st.elements.sample.clone();
            st.elements.commit(sys, &y[..n])?;
            cyc.add_work(
                &tangential(&f_old, true),
                &tangential(&st.elements.sample, true),
                &tangential(&f_old, false),
                &tangential(&st.elements.sample, false),
            );
            cyc.push(t, &sample(&y[..n]));
            loops.push(st.elements.sample.clone());
        }
        cycles += 1;
        let stats = cyc.finish(&st.elements.dissipated);
        if cycles > ramp_end {
            if let Some(p) = &prev {
                distance = test.push(change(p, &stats));
            }
        }
        prev = Some(stats);
        if run.tolerance > 0.0 && cycles >= run.min_cycles && distance <= run.tolerance {
            steady = true;
            break;
        }
    }
    st.x = y[..n].to_vec();
    st.v = y[n..].to_vec();
    let one_d = sys.linear.elements.len();
    let normal_range = (0..sys.elements.len())
        .map(|p| {
            loops
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                    let nf = s[one_d + p].force[2];
                    (lo.min(nf), hi.max(nf))
                })
        })
        .collect();
    Ok(Settled {
        cycles,
        steady,
        distance,
        last: prev.expect("max_cycles ≥ 1"),
        normal_range,
        loops,
        steps: cycles * run.steps,
        seconds: clock.elapsed().as_secs_f64(),
    })
}

/// The samples in the layout of [`Cycle::add_work`] (components 1 and 2 tangential):
/// forces (`force`) or displacements.
fn tangential(samples: &[LoopSample], force: bool) -> Vec<[f64; 3]> {
    samples
        .iter()
        .map(|s| {
            let v = if force { s.force } else { s.displacement };
            [0.0, v[0], v[1]]
        })
        .collect()
}
