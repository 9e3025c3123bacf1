//! Alternating frequency–time (AFT) evaluation of one nonlinear element (Cameron & Griffin
//! 1989): harmonic coefficients of its relative displacement → N time samples (inverse
//! real FFT) → forces and tangents in time → force coefficients (forward real FFT), and the
//! Jacobian ∂F̂/∂δ̂ by the same transforms of the tangent-weighted basis.
//!
//! Coefficient layout (H harmonics, zeroth included, 2H + 1 reals):
//! δ(τ) = c₀ + Σ_{h=1}^{H} (c_{2h−1} cos hτ + c_{2h} sin hτ), τ = ωt.
//!
//! Hysteretic points (the library's `jointlin_point_step`, LINPER = 0 physics) are marched
//! from a virgin state over the periodic δ repeatedly until the loop closes (the forces
//! of two consecutive periods agree to [`CLOSE_TOL`] of the force scale); the last
//! period is transformed. The thesis rule drifts to its closed loop geometrically, by a
//! ratio q ≈ 1 − A/δ* per period (hundreds of periods at small amplitudes); after every
//! two periods of shrinking differences the period-end state is extrapolated to its limit
//! (Aitken: s_∞ = s_p + (s_p − s_{p−1}) q/(1 − q), component by component, q the ratio of
//! the last two force differences), which closes such loops in 5–11 periods; the
//! closure test after the jump is the same, so the jump is verified, never assumed; a
//! state the library rejects is not used (plain marching goes on).
//!
//! Jacobian: for an elastic element F = f(δ) the derivative of sample k is f'(δ_k)·∂δ_k,
//! exact ("diagonal" rule). For a Jenkins point the force depends on the path, so the
//! derivative is propagated along the period: ∂F_k = ∂F_{k−1} + t_k (∂δ_k − ∂δ_{k−1}),
//! reset to 0 where the point slides (F = ±μF_N, fixed), started from the end of a first
//! pass round the closed loop; Jenkins is piecewise linear (k_T0 or sliding), so this is
//! the exact derivative of the marched map (test: central differences to 1e-7). For
//! Mindlin's curved microslip branch that rule omits how the branch origin moves with
//! δ̂ (measured 10–50 % off, Newton stalled near resonance), so Mindlin points carry
//! the exact derivatives through the library's tangent-linear step
//! (`jointlin_point_step_derivatives`) over one period from the closed loop's state, with
//! 2H + 1 columns for δ̂ and one per state slot for the start state; the closed loop's
//! start derivative D₀ then follows from periodicity, D₀ = Φ D₀ + G (Φ the period's
//! derivative in its start state, G in δ̂). A slot the period never assigns (an anchor
//! the loop keeps, e.g. the reversal point of a point that stays on its elastic line)
//! keeps its start value: its derivative is taken as zero, the loop's memory fixed, as a
//! forward difference marched from the closed state gives. One period of steps replaces
//! the 2H + 1 marches of forward differences (kept as the fallback where I − Φ is
//! singular).

use std::sync::Arc;

use nalgebra::DMatrix;

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};

use super::aitken::Aitken;
use crate::capi::{self, CapiError, Tangential, POINT_STATE_LEN};
pub use crate::model::lumped_system::Law;
use crate::names::LawName;

/// Loop closure: consecutive periods' forces agree to this fraction of the force scale
/// (max |F| over the period, at least [`CLOSE_FLOOR`]·μF_N). Jenkins and Masing loops
/// forget their history at each reversal, so closure is reached after 2–3 periods and
/// the tolerance only guards round-off; thesis-rule loops drift (module docs).
pub const CLOSE_TOL: f64 = 1e-11;
/// Floor of the closure scale relative to μF_N: loops of nearly stuck points (A/δ* ~ 1e-7)
/// under the thesis rule drift by ~2e-15 μF_N per period for ~1e7 periods (q = 1 − A/δ*);
/// with the floor 1e-2 they count as closed at 1e-13 μF_N, still 1e-6 of the smallest
/// perturbation of the forward-difference Jacobian (k_T0·1e-7·δ* = 1.5e-7 μF_N).
const CLOSE_FLOOR: f64 = 1e-2;
/// Periods marched at most before the loop counts as not closed. Jenkins and Masing
/// loops close after 2–3 periods; the thesis rule (elastic unloading, then Mindlin from
/// the zero-force point) is not symmetric under a prescribed periodic slip and drifts to
/// its closed loop geometrically (ratio ≈ 1 − A/δ* per period), which the Aitken jump
/// (module docs) shortcuts; without it A/δ* = 0.3 needed ~70 periods.
pub const MAX_PERIODS: usize = 200;

/// FFT plans and scratch for N samples.
pub struct Transforms {
    pub n: usize,
    pub h: usize,
    fwd: Arc<dyn RealToComplex<f64>>,
    inv: Arc<dyn ComplexToReal<f64>>,
    spec: Vec<Complex<f64>>,
    buf: Vec<f64>,
}

impl Transforms {
    /// Plans for N samples per period and H harmonics (N ≥ 2H + 2, so no harmonic aliases
    /// onto another inside the retained set).
    pub fn new(n: usize, h: usize) -> Self {
        assert!(n >= 2 * h + 2, "N = {n} too small for H = {h}");
        let mut p = RealFftPlanner::<f64>::new();
        let fwd = p.plan_fft_forward(n);
        let inv = p.plan_fft_inverse(n);
        Transforms {
            n,
            h,
            spec: fwd.make_output_vec(),
            buf: fwd.make_input_vec(),
            fwd,
            inv,
        }
    }

    /// Number of real coefficients 2H + 1.
    pub fn ncoef(&self) -> usize {
        2 * self.h + 1
    }

    /// Samples x_k = x(2πk/N) of the coefficient vector `c` into `out`.
    pub fn synthesize(&mut self, c: &[f64], out: &mut [f64]) {
        // realfft's inverse: x_k = Σ_{j=0}^{N−1} X_j e^{2πijk/N} with Hermitian X, so
        // X₀ = c₀ and X_h = (a_h − i b_h)/2 give a_h cos + b_h sin.
        for s in self.spec.iter_mut() {
            *s = Complex::new(0.0, 0.0);
        }
        self.spec[0] = Complex::new(c[0], 0.0);
        for h in 1..=self.h {
            self.spec[h] = Complex::new(0.5 * c[2 * h - 1], -0.5 * c[2 * h]);
        }
        self.inv
            .process(&mut self.spec, out)
            .expect("realfft inverse: sizes fixed at planning");
    }

    /// Coefficients (c₀, a_h, b_h) of the samples `x` (the discrete Fourier series; exact
    /// for trigonometric polynomials of degree < N/2).
    pub fn analyse(&mut self, x: &[f64], c: &mut [f64]) {
        self.buf.copy_from_slice(x);
        self.fwd
            .process(&mut self.buf, &mut self.spec)
            .expect("realfft forward: sizes fixed at planning");
        let n = self.n as f64;
        c[0] = self.spec[0].re / n;
        for h in 1..=self.h {
            c[2 * h - 1] = 2.0 * self.spec[h].re / n;
            c[2 * h] = -2.0 * self.spec[h].im / n;
        }
    }
}

/// One period of an element's force.
#[derive(Debug, Clone, Default)]
pub struct Period {
    pub force: Vec<f64>,
    pub tangent: Vec<f64>,
    /// Energy dissipated over the closed period (force × length).
    pub dissipated: f64,
    /// Periods marched until the loop closed.
    pub periods: usize,
    /// A point's state at the end of the closed period (= at its start); zeros for
    /// elastic elements.
    pub end_state: [f64; POINT_STATE_LEN],
}

/// Forces of `law` over the periodic samples `delta` (closed loop for points), marched
/// from a virgin point.
pub fn march(law: &Law, delta: &[f64]) -> Result<Period, AftError> {
    march_from(law, delta, &[0.0; POINT_STATE_LEN])
}

/// [`march`] from a point's `start` state, e.g. the closed loop of a nearby δ: a
/// perturbed loop then closes in two or three periods where a virgin start takes up to
/// eleven. Jenkins and Masing loops are the same from any start, and so are the
/// thesis rule's with its fading memory of shallow excursions (`mhb::tests::thesis_loops`;
/// docs/model.md §4).
pub fn march_from(
    law: &Law,
    delta: &[f64],
    start: &[f64; POINT_STATE_LEN],
) -> Result<Period, AftError> {
    let n = delta.len();
    match law {
        Law::Cubic(k3) => {
            let mut cur = Period {
                periods: 1,
                ..Period::default()
            };
            for &d in delta {
                let (force, tangent) = capi::cubic_force(0.0, *k3, d)?;
                cur.force.push(force);
                cur.tangent.push(tangent);
            }
            Ok(cur)
        }
        Law::Point(t) => {
            let mut state = *start;
            let mut next = [0.0; POINT_STATE_LEN];
            let mut prev: Vec<f64> = vec![0.0; n];
            let mut cur = Period {
                force: vec![0.0; n],
                tangent: vec![0.0; n],
                ..Period::default()
            };
            let floor = CLOSE_FLOOR * t.mu * t.normal.abs();
            let mut aitken = Aitken::new(0..POINT_STATE_LEN);
            for p in 1..=MAX_PERIODS {
                let mut diss = 0.0;
                for k in 0..n {
                    let s = capi::point_step(t, &state, delta[k], &mut next)?;
                    state = next;
                    cur.force[k] = s.force;
                    cur.tangent[k] = s.tangent;
                    diss += s.dissipated;
                }
                let scale = cur.force.iter().fold(floor, |m, f| m.max(f.abs()));
                let diff = cur
                    .force
                    .iter()
                    .zip(&prev)
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                cur.dissipated = diss;
                cur.periods = p;
                prev.copy_from_slice(&cur.force);
                // The first period, and the first after a jump, starts the record.
                if aitken.starting() {
                    aitken.first(&state);
                    continue;
                }
                if diff <= CLOSE_TOL * scale {
                    cur.end_state = state;
                    return Ok(cur);
                }
                if let Some(x) = aitken.after(&state, diff) {
                    // The state is the library's: if it rejects the extrapolated one
                    // (a discrete slot changed between the periods), march on plainly
                    // and try again after the next two periods.
                    match <[f64; POINT_STATE_LEN]>::try_from(x.as_slice()) {
                        Ok(x) if capi::point_step(t, &x, delta[0], &mut next).is_ok() => state = x,
                        _ => aitken.rejected(&state),
                    }
                }
            }
            Err(AftError::NotClosed {
                periods: MAX_PERIODS,
            })
        }
    }
}

/// Errors of the AFT evaluation.
#[derive(Debug, thiserror::Error)]
pub enum AftError {
    #[error(transparent)]
    Capi(#[from] CapiError),
    #[error("the hysteresis loop did not close within {periods} periods")]
    NotClosed { periods: usize },
}

/// Force coefficients and their Jacobian for one element.
pub struct ElementEval {
    pub force: Vec<f64>,
    /// ∂F̂/∂δ̂, row-major (2H+1)².
    pub jac: Vec<f64>,
    pub period: Period,
}

/// Force coefficients of one element at relative-displacement coefficients `dc`, and the
/// closed period they come from (no Jacobian).
pub fn forces(tr: &mut Transforms, law: &Law, dc: &[f64]) -> Result<(Vec<f64>, Period), AftError> {
    let mut delta = vec![0.0; tr.n];
    tr.synthesize(dc, &mut delta);
    let period = march(law, &delta)?;
    let mut force = vec![0.0; tr.ncoef()];
    tr.analyse(&period.force, &mut force);
    Ok((force, period))
}

/// AFT of one element at relative-displacement coefficients `dc`.
pub fn evaluate(tr: &mut Transforms, law: &Law, dc: &[f64]) -> Result<ElementEval, AftError> {
    evaluate_with(tr, law, dc, Jacobian::Exact)
}

/// How the Jacobian of a Mindlin point is formed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Jacobian {
    /// The closed loop's derivative by the tangent-linear step (module docs).
    Exact,
    /// Forward differences of the whole AFT map: perturbations of 1e-7 δ* straddle the
    /// kinks of sampled loops, which can let Newton settle where the exact derivative of
    /// a piecewise smooth balance makes it cycle (the backbones' fixed-q fallback).
    Differences,
}

/// [`evaluate`] with the Jacobian of Mindlin points formed as `jacobian` says.
pub fn evaluate_with(
    tr: &mut Transforms,
    law: &Law,
    dc: &[f64],
    jacobian: Jacobian,
) -> Result<ElementEval, AftError> {
    let (n, m) = (tr.n, tr.ncoef());
    let (force, period) = forces(tr, law, dc)?;
    let mut jac = vec![0.0; m * m];
    if let Law::Point(t) = law {
        if t.law != LawName::Jenkins {
            if jacobian == Jacobian::Differences
                || !closed_loop_jacobian(tr, t, dc, &period.end_state, &mut jac)?
            {
                fd_jacobian(tr, law, t, dc, (&force, &period.end_state), &mut jac)?;
            }
            return Ok(ElementEval { force, jac, period });
        }
    }
    let incremental = matches!(law, Law::Point(_));
    let mut basis = vec![0.0; m];
    let mut b = vec![0.0; n];
    let mut df = vec![0.0; n];
    let mut col = vec![0.0; m];
    for j in 0..m {
        basis.iter_mut().for_each(|x| *x = 0.0);
        basis[j] = 1.0;
        tr.synthesize(&basis, &mut b);
        if let (true, Law::Point(t)) = (incremental, law) {
            propagate(
                &period.force,
                &period.tangent,
                t.mu * t.normal.abs(),
                &b,
                &mut df,
            );
        } else {
            for k in 0..n {
                df[k] = period.tangent[k] * b[k];
            }
        }
        tr.analyse(&df, &mut col);
        for i in 0..m {
            jac[i * m + j] = col[i];
        }
    }
    Ok(ElementEval { force, jac, period })
}

/// The exact Jacobian ∂F̂/∂δ̂ at coefficients `dc` of the closed loop from `start` (its
/// state) by the tangent-linear step (module docs) into `jac`; false where I − Φ is
/// singular.
fn closed_loop_jacobian(
    tr: &mut Transforms,
    t: &Tangential,
    dc: &[f64],
    start: &[f64; POINT_STATE_LEN],
    jac: &mut [f64],
) -> Result<bool, AftError> {
    const L: usize = POINT_STATE_LEN;
    let (n, m) = (tr.n, tr.ncoef());
    let cols = m + L;
    // ∂δ_k/∂ĉ_j: the basis functions' samples, sample-major.
    let mut basis = vec![0.0; n * m];
    let (mut unit, mut samples) = (vec![0.0; m], vec![0.0; n]);
    for j in 0..m {
        unit.iter_mut().for_each(|x| *x = 0.0);
        unit[j] = 1.0;
        tr.synthesize(&unit, &mut samples);
        for k in 0..n {
            basis[k * m + j] = samples[k];
        }
    }
    let mut delta = vec![0.0; n];
    tr.synthesize(dc, &mut delta);
    // Start: D₀ = [0 | I].
    let (mut state, mut next) = (*start, [0.0; L]);
    let (mut d, mut d_next) = (vec![0.0; L * cols], vec![0.0; L * cols]);
    for i in 0..L {
        d[i * cols + m + i] = 1.0;
    }
    let mut d_slip = vec![0.0; cols];
    let mut d_force = vec![0.0; n * cols];
    for k in 0..n {
        d_slip[..m].copy_from_slice(&basis[k * m..(k + 1) * m]);
        capi::point_step_derivatives(
            t,
            (&state, &d),
            (delta[k], &d_slip),
            (&mut next, &mut d_next),
            &mut d_force[k * cols..(k + 1) * cols],
        )?;
        state = next;
        std::mem::swap(&mut d, &mut d_next);
    }
    // Periodicity: (I − Φ) D₀ = G; a never-assigned slot keeps D₀ = 0.
    let mut a = DMatrix::<f64>::identity(L, L);
    let mut g = DMatrix::<f64>::zeros(L, m);
    for i in 0..L {
        let phi = &d[i * cols + m..(i + 1) * cols];
        let kept = (0..L).all(|r| phi[r] == f64::from(u8::from(r == i)))
            && d[i * cols..i * cols + m].iter().all(|v| *v == 0.0);
        if kept {
            continue;
        }
        for r in 0..L {
            a[(i, r)] -= phi[r];
        }
        for j in 0..m {
            g[(i, j)] = d[i * cols + j];
        }
    }
    let Some(d0) = a.lu().solve(&g) else {
        return Ok(false);
    };
    if !d0.iter().all(|v| v.is_finite()) {
        return Ok(false);
    }
    // ∂F_k/∂ĉ_j = dF_k[j] + Σ_i dF_k[m + i] D₀[i, j], transformed per column.
    let (mut column, mut col) = (vec![0.0; n], vec![0.0; m]);
    for j in 0..m {
        for k in 0..n {
            let row = &d_force[k * cols..(k + 1) * cols];
            column[k] = row[j] + (0..L).map(|i| row[m + i] * d0[(i, j)]).sum::<f64>();
        }
        tr.analyse(&column, &mut col);
        for i in 0..m {
            jac[i * m + j] = col[i];
        }
    }
    Ok(true)
}

/// Forward differences of the whole AFT map (one march per column, from the closed
/// loop's state `base.1` whose force coefficients are `base.0`), step 1e-7 of the
/// larger of max|δ̂| and the slip limit δ* = 1.5 μF_N/k_T0 (2.46): truncation ~1e-7 on the
/// smooth Mindlin branches, round-off ~1e-9 (the march is deterministic).
fn fd_jacobian(
    tr: &mut Transforms,
    law: &Law,
    t: &Tangential,
    dc: &[f64],
    base: (&[f64], &[f64; POINT_STATE_LEN]),
    jac: &mut [f64],
) -> Result<(), AftError> {
    let (n, m) = (tr.n, tr.ncoef());
    let dstar = 1.5 * t.mu * t.normal.abs() / t.k_t0;
    let eps = 1e-7 * dc.iter().fold(dstar, |a, v| a.max(v.abs()));
    let mut p = dc.to_vec();
    let mut delta = vec![0.0; n];
    let mut col = vec![0.0; m];
    for j in 0..m {
        p[j] = dc[j] + eps;
        tr.synthesize(&p, &mut delta);
        let per = march_from(law, &delta, base.1)?;
        tr.analyse(&per.force, &mut col);
        for i in 0..m {
            jac[i * m + j] = (col[i] - base.0[i]) / eps;
        }
        p[j] = dc[j];
    }
    Ok(())
}

/// The incremental derivative rule (module docs) round the closed period, two passes.
/// A sample counts as sliding when the tangent is 0 or the force is at the Coulomb limit
/// μ|F_N| (to 1e-12 relative): the library's Jenkins point returns the tangent k_T0 for
/// some samples while the force stays at ±μF_N, so the force is the reliable sign.
fn propagate(f: &[f64], t: &[f64], limit: f64, b: &[f64], df: &mut [f64]) {
    let n = t.len();
    let at_limit = |k: usize| t[k] == 0.0 || f[k].abs() >= limit * (1.0 - 1e-12);
    let mut last = t[n - 1] * b[n - 1];
    for _pass in 0..2 {
        let mut prev_b = b[n - 1];
        for k in 0..n {
            let d = if at_limit(k) {
                0.0
            } else {
                last + t[k] * (b[k] - prev_b)
            };
            df[k] = d;
            last = d;
            prev_b = b[k];
        }
    }
}

/// Whether a law is Jenkins (exact incremental Jacobian).
pub fn is_jenkins(law: &Law) -> bool {
    matches!(law, Law::Point(t) if t.law == LawName::Jenkins)
}
