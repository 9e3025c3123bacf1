//! Harmonic-balance mode of the sweep (`[iteration] mode = "harmonic_balance"`): per
//! frequency the per-harmonic condensation and Newton of [`super::harmonic_fe`], started from
//! the previous frequency's solution (from the stuck linear response at the first one and
//! after a failure; where neither converges, with the load raised in steps; a frequency that does not converge keeps its last iterate, finite,
//! and is flagged in `converged` like the other modes do). Outputs: first harmonic as in the other modes, all harmonics in
//! [`SweepResult::harmonics`]; per point the energy per cycle of its closed loops, the
//! first-harmonic amplitude and the balance's describing function F̂₁/r̂₁ = k* + iωd*.

use std::time::Instant;

use super::driver::{drive, FrequencySolver, Outcome, Row, Shape};
use super::harmonic_fe::{FeBalance, FeSolution};
use super::modal_route::LinearRoute;
use super::{Options, PassRecord, PointFreq, Setup, SweepError, SweepResult};
use crate::capi;
use crate::mhb::{default_samples, NewtonOptions};
use crate::solve::contact::tangential;

/// Load steps of the last attempt at a frequency ([`FeBalance::solve_ramped`]).
const RAMP_STEPS: usize = 10;

/// Runs the sweep; H and N from the scene (validated: H ≥ 1, N ≥ 2H + 2).
pub fn sweep(
    setup: &mut Setup,
    freqs: &[f64],
    opts: &Options,
    progress: &dyn Fn(&str, usize, usize),
) -> Result<SweepResult, SweepError> {
    let it = opts.iteration;
    let h = it.harmonics.unwrap_or(1).max(1);
    let n = it.samples.unwrap_or_else(|| default_samples(h));
    let p = setup.problem;
    let mut res = SweepResult::default();
    let mut hb = FeBalance::new(setup, h, n);
    if let LinearRoute::Modal { modes, residual } = opts.linear {
        let t = Instant::now();
        hb.use_modal(modes, residual)?;
        res.modal = hb.modal.as_ref().map(|r| r.summary.clone());
        res.time("modal basis (modes, residual)", t);
    }
    let shape = Shape::of(p, opts);
    let mut solver = Harmonic {
        hb,
        opts,
        h,
        start: None,
        index: 0,
        largest: None,
    };
    drive(&mut solver, freqs, shape, progress, &mut res);
    let mut hb = solver.hb;
    if let Some((_, f, r)) = solver.largest {
        let t = Instant::now();
        let loops = hb
            .loops(&r, f)
            .map_err(|source| SweepError::Balance { freq: f, source })?;
        res.loops = Some(loops);
        res.time("contact loops", t);
    }
    res.factorizations = hb.stats.factorizations;
    res.gmres_solves = hb.stats.gmres_iterations;
    *res.timings.entry("receptance solves".into()).or_default() += hb.stats.receptance_seconds;
    *res.timings
        .entry("harmonic balance (AFT + Newton)".into())
        .or_default() += hb.stats.contact_seconds;
    res.timings
        .insert("CPU: receptance solves".into(), hb.stats.receptance_cpu);
    res.timings.insert(
        "CPU: harmonic balance (AFT + Newton)".into(),
        hb.stats.contact_cpu,
    );
    res.passes.push(PassRecord {
        pass: 1,
        kind: format!("harmonic balance H = {h}, N = {n}"),
        frequencies: freqs.to_vec(),
        converged: res.converged.iter().filter(|&&c| c).count(),
    });
    Ok(res)
}

/// The harmonic balance of one frequency after another, each started from the last
/// converged solution.
struct Harmonic<'s, 'a> {
    hb: FeBalance<'s, 'a>,
    opts: &'s Options,
    /// Harmonics H.
    h: usize,
    /// The last converged solution (the next frequency's start), `None`: start linear.
    start: Option<Vec<f64>>,
    /// Frequencies solved so far.
    index: usize,
    /// The converged solution of the largest response so far: (first output's
    /// first-harmonic amplitude, or the energy per cycle without outputs; frequency; r).
    largest: Option<(f64, f64, Vec<f64>)>,
}

impl FrequencySolver for Harmonic<'_, '_> {
    fn solve(&mut self, f: f64, res: &mut SweepResult) -> Result<Outcome, SweepError> {
        let first = self.index == 0;
        self.index += 1;
        let it = self.opts.iteration;
        let omega = 2.0 * std::f64::consts::PI * f;
        let hb = &mut self.hb;
        let regular = hb
            .condense(omega)
            .map_err(|source| SweepError::Umfpack { freq: f, source })?;
        if !regular {
            self.start = None;
            return Ok(Outcome::Singular);
        }
        let newton = NewtonOptions {
            rtol: it.tolerance,
            max_iter: it.max_passes,
        };
        let from = self.start.take().unwrap_or_else(|| hb.linear_start());
        let balance = |source| SweepError::Balance { freq: f, source };
        let sol = match hb.solve(&from, newton) {
            Ok(s) if s.converged => s,
            first_try => {
                let second = if first {
                    first_try
                } else {
                    hb.solve(&hb.linear_start(), newton)
                };
                match second {
                    Ok(s) if s.converged => s,
                    second => match (second, hb.solve_ramped(RAMP_STEPS, newton)) {
                        (_, Ok(c)) if c.converged => c,
                        (Ok(b), Ok(c)) if b.residual < c.residual => b,
                        (_, Ok(c)) => c,
                        (Ok(b), Err(_)) => b,
                        (Err(e), Err(_)) => return Err(balance(e)),
                    },
                }
            }
        };
        let check = if sol.converged {
            let t = Instant::now();
            let v = hb.check(&sol, it.tolerance, f)?;
            res.time("a-posteriori check", t);
            Some(v)
        } else {
            None
        };
        let mut energy = vec![0.0; hb.setup.active.len()];
        for (d, e) in hb.dirs.iter().zip(&sol.dissipated) {
            energy[d.point] += e;
        }
        let points = if self.opts.point_results {
            let t = Instant::now();
            let pts = self.points(&sol, &energy, omega)?;
            res.time("point outputs", t);
            Some(pts)
        } else {
            None
        };
        let hb = &self.hb;
        let converged = sol.converged
            && check.is_some_and(|v| {
                if hb.modal.is_some() {
                    v.consistency <= 1.0
                } else {
                    v.passes(it.tolerance)
                }
            });
        let size = sol
            .outputs
            .first()
            .map_or(energy.iter().sum(), |hs| hs[1.min(self.h)].norm());
        if converged && self.largest.as_ref().is_none_or(|l| size > l.0) {
            self.largest = Some((size, f, sol.r.clone()));
        }
        self.start = sol.converged.then(|| sol.r.clone());
        Ok(Outcome::Solved(Row {
            outputs: sol.outputs.iter().map(|hs| hs[1.min(self.h)]).collect(),
            harmonics: Some(sol.outputs.clone()),
            power: energy.iter().sum::<f64>() * f,
            points,
            iterations: sol.iterations,
            converged,
            check: check.filter(|_| converged),
            field: None,
        }))
    }

    fn restart(&mut self) {
        self.start = None;
    }

    fn harmonics(&self) -> Option<usize> {
        Some(self.h + 1)
    }
}

impl Harmonic<'_, '_> {
    /// Per contact point: the balance's first-harmonic amplitude and describing function,
    /// the regime and A/δ* from the library at that amplitude, the energy per cycle.
    fn points(
        &self,
        sol: &FeSolution,
        energy: &[f64],
        omega: f64,
    ) -> Result<Vec<PointFreq>, SweepError> {
        let hb = &self.hb;
        let p = hb.setup.problem;
        let nc = hb.tr.ncoef();
        let mut pts = vec![PointFreq::default(); p.contacts.len()];
        for (q, &i) in hb.setup.active.iter().enumerate() {
            let tg = tangential(&p.interfaces[p.contacts[i].interface], hb.setup.pressure[i]);
            let mut pf = PointFreq {
                energy: energy[q],
                ..Default::default()
            };
            for d in 0..2 {
                let j = hb
                    .dirs
                    .iter()
                    .position(|x| x.point == q && x.comp == 1 + d)
                    .expect("every active point has both tangential directions");
                let amp = sol.r[j * nc + 1].hypot(sol.r[j * nc + 2]);
                let l = capi::linearize(&tg, amp, omega)?;
                pf.amplitude[d] = amp;
                pf.k_star[d] = sol.describing[j].re;
                pf.d_star[d] = sol.describing[j].im / omega;
                pf.ratio[d] = l.amplitude_ratio;
                pf.regime[d] = l.regime;
            }
            pts[i] = pf;
        }
        Ok(pts)
    }
}
