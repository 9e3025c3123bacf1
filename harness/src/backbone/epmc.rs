//! Extended periodic motion concept (Krack, "Nonlinear modal analysis of nonconservative
//! systems: extension of the periodic motion concept", Computers & Structures 154, 2015):
//! the free system with an artificial term −ξMẋ,
//!
//!   M ẍ + (D − ξM) ẋ + K x + Σ_e Pₑᵀ Fₑ(Pₑ x) = 0,
//!
//! has periodic solutions; ξ is the energy the mode loses per cycle. With x = q ψ
//! (harmonic balance at H harmonics, forces by the AFT of [`crate::mhb::aft`]), the
//! unknowns (ψ, ω, ξ) solve R(qψ, ω, ξ)/q = 0 with the normalization ψ₁ᴴMψ₁ = 1 (first
//! harmonic, so q is the modal amplitude of [`super`]) and the phase φ_rᵀMb₁ = 0 (the
//! sine part of the first harmonic orthogonal to the stuck mode's real shape φ_r).
//! Damping ratio ζ = ξ/(2ω) (Krack 2015, eq. 14). At H = 1 with the loop's own first
//! harmonic this is the first-order backbone up to the O(ζ²) difference between |λ| and
//! the frequency of the damping-compensated motion.
//!
//! Continuation in the modal amplitude: each requested q starts from the previous
//! solution (a secant predictor in log q after two); where Newton fails the interval
//! is halved in log q (at most [`MAX_HALVINGS`] times).

use nalgebra::{DMatrix, DVector};

use super::first_order::{stick_limit, stuck_mode};
use super::{BackboneError, BackbonePoint, C64};
use crate::mhb::{default_samples, Hb, System};

/// Newton tolerance on the scaled residual.
const RTOL: f64 = 1e-9;
const MAX_NEWTON: usize = 40;
/// Full Newton steps that raise |R| (at most tenfold) allowed per solve.
const MAX_NONMONOTONE: usize = 5;
/// Interval halvings in log q before a requested amplitude counts as not reached.
pub const MAX_HALVINGS: usize = 10;

/// An EPMC point: the backbone point and the full solution.
#[derive(Debug, Clone)]
pub struct EpmcPoint {
    pub point: BackbonePoint,
    /// Artificial damping ξ (1/time).
    pub xi: f64,
    /// Coefficients of x = qψ, DOF-major (layout of [`crate::mhb::aft`]).
    pub u: Vec<f64>,
}

/// Residual, Jacobian and energy dissipated per element at one state.
type Evaluated = (DVector<f64>, DMatrix<f64>, Vec<f64>);

/// State of the continuation: ψ, ω, ξ.
#[derive(Debug, Clone)]
struct State {
    psi: Vec<f64>,
    omega: f64,
    xi: f64,
}

struct Epmc<'a> {
    hb: Hb<'a>,
    /// M·φ_r (phase condition row).
    m_ref: Vec<f64>,
    /// Residual scale ω₀² (ψ is mass-normalized).
    scale: f64,
}

impl Epmc<'_> {
    /// Residual F and Jacobian of (ψ, ω, ξ) at modal amplitude q.
    fn eval(&mut self, st: &State, q: f64) -> Result<Evaluated, BackboneError> {
        let s = self.hb.sys;
        let (n, m) = (s.n(), self.hb.tr.ncoef());
        let dim = n * m;
        let x: Vec<f64> = st.psi.iter().map(|v| v * q).collect();
        let ev = self.hb.eval(&x, st.omega)?;
        let mut f = DVector::zeros(dim + 2);
        let mut jac = DMatrix::zeros(dim + 2, dim + 2);
        f.rows_mut(0, dim).copy_from(&(&ev.r / q));
        jac.view_mut((0, 0), (dim, dim)).copy_from(&ev.j);
        for i in 0..dim {
            jac[(i, dim)] = ev.r_omega[i] / q;
        }
        // The −ξM ẋ term, per harmonic h: [0, −hωξM; hωξM, 0] on (cos, sin).
        let (w, xi) = (st.omega, st.xi);
        for h in 1..=self.hb.h() {
            let hh = h as f64;
            for a in 0..n {
                let (ca, sa) = (a * m + 2 * h - 1, a * m + 2 * h);
                for b in 0..n {
                    let mab = s.m[(a, b)];
                    if mab == 0.0 {
                        continue;
                    }
                    let (cb, sb) = (b * m + 2 * h - 1, b * m + 2 * h);
                    let (pc, ps) = (st.psi[cb], st.psi[sb]);
                    f[ca] -= hh * w * xi * mab * ps;
                    f[sa] += hh * w * xi * mab * pc;
                    jac[(ca, sb)] -= hh * w * xi * mab;
                    jac[(sa, cb)] += hh * w * xi * mab;
                    jac[(ca, dim)] -= hh * xi * mab * ps;
                    jac[(sa, dim)] += hh * xi * mab * pc;
                    jac[(ca, dim + 1)] -= hh * w * mab * ps;
                    jac[(sa, dim + 1)] += hh * w * mab * pc;
                }
            }
        }
        // Normalization ψ₁ᴴMψ₁ = 1 and phase φ_rᵀMb₁ = 0.
        let mut norm = -1.0;
        for a in 0..n {
            for b in 0..n {
                let mab = s.m[(a, b)];
                let (ca, sa, cb, sb) = (a * m + 1, a * m + 2, b * m + 1, b * m + 2);
                norm += mab * (st.psi[ca] * st.psi[cb] + st.psi[sa] * st.psi[sb]);
                jac[(dim, ca)] += 2.0 * mab * st.psi[cb];
                jac[(dim, sa)] += 2.0 * mab * st.psi[sb];
            }
            jac[(dim + 1, a * m + 2)] = self.m_ref[a];
        }
        f[dim] = norm;
        f[dim + 1] = (0..n).map(|a| self.m_ref[a] * st.psi[a * m + 2]).sum();
        Ok((f, jac, ev.dissipated))
    }

    fn scaled(&self, f: &DVector<f64>) -> f64 {
        let dim = f.len() - 2;
        (f.rows(0, dim).norm() / self.scale).max(f[dim].abs().max(f[dim + 1].abs()))
    }

    /// Newton from `st` at q.
    fn solve(&mut self, mut st: State, q: f64) -> Result<(State, Vec<f64>), f64> {
        let dim = st.psi.len();
        let Ok((mut f, mut jac, mut diss)) = self.eval(&st, q) else {
            return Err(f64::INFINITY);
        };
        let mut res = self.scaled(&f);
        let mut nonmonotone = 0;
        for _ in 0..MAX_NEWTON {
            if res <= RTOL {
                return Ok((st, diss));
            }
            let Some(dy) = jac.clone().lu().solve(&f) else {
                return Err(res);
            };
            let mut lambda = 1.0;
            let mut accepted = false;
            let mut full = None;
            for _ in 0..8 {
                let trial = State {
                    psi: (0..dim).map(|i| st.psi[i] - lambda * dy[i]).collect(),
                    omega: st.omega - lambda * dy[dim],
                    xi: st.xi - lambda * dy[dim + 1],
                };
                if trial.omega > 0.0 {
                    if let Ok((f2, j2, d2)) = self.eval(&trial, q) {
                        let r2 = self.scaled(&f2);
                        if r2 < res {
                            (st, f, jac, diss, res) = (trial, f2, j2, d2, r2);
                            accepted = true;
                            break;
                        }
                        if lambda == 1.0 && r2 < 10.0 * res {
                            full = Some((trial, f2, j2, d2, r2));
                        }
                    }
                }
                lambda *= 0.5;
            }
            // The AFT forces of contact elements are piecewise smooth (a sample changes
            // between sticking and sliding): where no shortened step lowers |R|, a few
            // full steps that raise it less than tenfold are taken (non-monotone Newton).
            if !accepted {
                match full {
                    Some(fs) if nonmonotone < MAX_NONMONOTONE => {
                        nonmonotone += 1;
                        (st, f, jac, diss, res) = fs;
                    }
                    _ => return Err(res),
                }
            }
        }
        if res <= RTOL {
            Ok((st, diss))
        } else {
            Err(res)
        }
    }
}

/// The EPMC backbone of mode `mode` (1-based) at H harmonics (N samples by
/// [`default_samples`]) at the modal amplitudes `q`.
pub fn backbone(
    sys: &System,
    mode: usize,
    h: usize,
    q: &[f64],
) -> Result<Vec<EpmcPoint>, BackboneError> {
    backbone_sampled(sys, mode, h.max(1), default_samples(h.max(1)), q)
}

/// [`backbone`] with N samples per period (at least 2H + 2).
pub fn backbone_sampled(
    sys: &System,
    mode: usize,
    h: usize,
    samples: usize,
    q: &[f64],
) -> Result<Vec<EpmcPoint>, BackboneError> {
    let n = sys.n();
    let free = System {
        f0: vec![0.0; n],
        f1: vec![C64::new(0.0, 0.0); n],
        ..sys.clone()
    };
    let stuck = stuck_mode(sys, mode)?;
    let h = h.max(1);
    let samples = samples.max(2 * h + 2);
    let m = 2 * h + 1;
    let mut psi = vec![0.0; n * m];
    for d in 0..n {
        psi[d * m + 1] = stuck.shape[d].re;
        psi[d * m + 2] = -stuck.shape[d].im;
    }
    let phi_r: Vec<f64> = stuck.shape.iter().map(|v| v.re).collect();
    let m_ref: Vec<f64> = (0..n)
        .map(|a| (0..n).map(|b| sys.m[(a, b)] * phi_r[b]).sum())
        .collect();
    let w0 = stuck.omega();
    let mut ep = Epmc {
        hb: Hb::new(&free, h, samples),
        m_ref,
        scale: (w0 * w0).max(f64::MIN_POSITIVE),
    };
    let mut st = State {
        psi,
        omega: w0,
        xi: 2.0 * stuck.damping_ratio() * w0,
    };
    // (log q, state) of the last two converged points, for the secant predictor.
    let mut last: Vec<(f64, State)> = Vec::new();
    let mut out = Vec::with_capacity(q.len());
    for &target in q {
        if !(target.is_finite() && target > 0.0) {
            return Err(BackboneError::Amplitude(target));
        }
        // The first amplitude is approached from where every contact still sticks.
        let mut from = match last.last() {
            Some(l) => l.0,
            None => target.min(0.5 * stick_limit(sys, &stuck.shape)?).ln(),
        };
        let mut halvings = 0;
        let (sol, diss) = loop {
            let lq = if halvings == 0 {
                target.ln()
            } else {
                from + (target.ln() - from) * 0.5f64.powi(halvings as i32)
            };
            let guess = predict(&last, &st, lq);
            match ep.solve(guess, lq.exp()) {
                Ok((s, d)) => {
                    push_last(&mut last, lq, s.clone());
                    st = s.clone();
                    if halvings == 0 {
                        break (s, d);
                    }
                    from = lq;
                    halvings = 0;
                }
                Err(res) => {
                    halvings += 1;
                    if halvings > MAX_HALVINGS {
                        return Err(BackboneError::NotConverged {
                            modal_amplitude: target,
                            residual: res,
                        });
                    }
                }
            }
        };
        out.push(point(&ep.hb, sys, &sol, target, diss));
    }
    Ok(out)
}

fn push_last(last: &mut Vec<(f64, State)>, lq: f64, s: State) {
    last.push((lq, s));
    if last.len() > 2 {
        last.remove(0);
    }
}

/// Secant extrapolation in log q from the last two points (or the last state).
fn predict(last: &[(f64, State)], st: &State, lq: f64) -> State {
    let [(l0, s0), (l1, s1)] = last else {
        return st.clone();
    };
    if (l1 - l0).abs() < 1e-14 {
        return st.clone();
    }
    let c = (lq - l1) / (l1 - l0);
    State {
        psi: s1
            .psi
            .iter()
            .zip(&s0.psi)
            .map(|(b, a)| b + c * (b - a))
            .collect(),
        omega: s1.omega + c * (s1.omega - s0.omega),
        xi: s1.xi + c * (s1.xi - s0.xi),
    }
}

fn point(hb: &Hb, sys: &System, st: &State, q: f64, diss: Vec<f64>) -> EpmcPoint {
    let m = hb.tr.ncoef();
    let u: Vec<f64> = st.psi.iter().map(|v| v * q).collect();
    let shape: Vec<C64> = (0..sys.n())
        .map(|d| C64::new(u[d * m + 1], -u[d * m + 2]))
        .collect();
    EpmcPoint {
        point: BackbonePoint {
            modal_amplitude: q,
            omega: st.omega,
            damping_ratio: st.xi / (2.0 * st.omega),
            element_amplitudes: super::first_order::relative(sys, &shape),
            shape,
            energy_per_cycle: diss,
        },
        xi: st.xi,
        u,
    }
}
