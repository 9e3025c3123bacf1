//! Harmonic-balance mode of the sweep (`[iteration] mode = "harmonic_balance"`): per
//! frequency the per-harmonic condensation and Newton of [`super::harmonic_fe`], started from
//! the previous frequency's solution (from the stuck linear response at the first one and
//! after a failure; where neither converges, with the load raised in steps; a frequency that does not converge keeps its last iterate, finite,
//! and is flagged in `converged` like the other modes do). Outputs: first harmonic as in the other modes, all harmonics in
//! [`SweepResult::harmonics`]; per point the energy per cycle of its closed loops, the
//! first-harmonic amplitude and the balance's describing function F̂₁/r̂₁ = k* + iωd*.

use std::time::Instant;

use super::harmonic_fe::FeBalance;
use super::modal_route::LinearRoute;
use super::{Options, PassRecord, PointFreq, Setup, SweepError, SweepResult, C64};
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
    let active = setup.active.clone();
    let pressure = setup.pressure.clone();
    let newton = NewtonOptions {
        rtol: it.tolerance,
        max_iter: it.max_passes,
    };
    let mut res = SweepResult {
        freqs: freqs.to_vec(),
        ..Default::default()
    };
    let mut hb = FeBalance::new(setup, h, n);
    if let LinearRoute::Modal { modes, residual } = opts.linear {
        let t = Instant::now();
        hb.use_modal(modes, residual)?;
        res.modal = hb.modal.as_ref().map(|r| r.summary.clone());
        res.time("modal basis (modes, residual)", t);
    }
    let mut start: Option<Vec<f64>> = None;
    let nout = p.outputs.len();
    let npoints = opts.point_results.then_some(p.contacts.len());
    'freqs: for (fi, &f) in freqs.iter().enumerate() {
        progress("frequency", fi + 1, freqs.len());
        let omega = 2.0 * std::f64::consts::PI * f;
        // A solve or a library call that fails at this frequency fails this frequency
        // only (status `failed`, the message in run.json); the next one starts cold.
        macro_rules! per_freq {
            ($e:expr) => {
                match $e {
                    Ok(v) => v,
                    Err(e) => {
                        let e: SweepError = e;
                        res.push_failed(&e, nout, npoints);
                        res.harmonics
                            .push(vec![vec![C64::new(0.0, 0.0); h + 1]; nout]);
                        let _ = start.take();
                        continue 'freqs;
                    }
                }
            };
        }
        let regular = per_freq!(hb
            .condense(omega)
            .map_err(|source| SweepError::Umfpack { freq: f, source }));
        if !regular {
            // Singular dynamic stiffness (e.g. an undamped eigenfrequency with the joint
            // open): no response, as in the other modes; the next frequency starts afresh.
            res.push_singular(nout, npoints);
            res.harmonics
                .push(vec![vec![C64::new(0.0, 0.0); h + 1]; nout]);
            start = None;
            continue;
        }
        let from = start.take().unwrap_or_else(|| hb.linear_start());
        let balance = |source| SweepError::Balance { freq: f, source };
        let sol = match hb.solve(&from, newton) {
            Ok(s) if s.converged => s,
            // Not converged (or an AFT failure, e.g. a loop that did not close) from the
            // previous solution: once more from the stuck response, then with the load
            // raised in steps.
            first => {
                let second = if fi > 0 {
                    hb.solve(&hb.linear_start(), newton)
                } else {
                    first
                };
                match second {
                    Ok(s) if s.converged => s,
                    second => match (second, hb.solve_ramped(RAMP_STEPS, newton)) {
                        (_, Ok(c)) if c.converged => c,
                        (Ok(b), Ok(c)) if b.residual < c.residual => b,
                        (_, Ok(c)) => c,
                        (Ok(b), Err(_)) => b,
                        (Err(e), Err(_)) => per_freq!(Err(balance(e))),
                    },
                }
            }
        };
        // The uncondensed check of a converged frequency (harmonic_check.rs); one that
        // fails it is not converged.
        let check = if sol.converged {
            let t = Instant::now();
            let v = per_freq!(hb.check(&sol, it.tolerance, f));
            res.time("a-posteriori check", t);
            Some(v)
        } else {
            None
        };
        // Per point: the energy of its directions (a three-direction point holds its
        // whole energy on its first one).
        let mut energy = vec![0.0; active.len()];
        for (d, e) in hb.dirs.iter().zip(&sol.dissipated) {
            energy[d.point] += e;
        }
        if opts.point_results {
            let t = Instant::now();
            let nc = hb.tr.ncoef();
            let mut pts = vec![PointFreq::default(); p.contacts.len()];
            for (q, &i) in active.iter().enumerate() {
                let tg = tangential(&p.interfaces[p.contacts[i].interface], pressure[i]);
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
                    // A/δ* and the regime of the first-harmonic amplitude (library's).
                    let l = per_freq!(capi::linearize(&tg, amp, omega).map_err(SweepError::from));
                    pf.amplitude[d] = amp;
                    pf.k_star[d] = sol.describing[j].re;
                    pf.d_star[d] = sol.describing[j].im / omega;
                    pf.ratio[d] = l.amplitude_ratio;
                    pf.regime[d] = l.regime;
                }
                pts[i] = pf;
            }
            res.points.push(pts);
            res.time("point outputs", t);
        }
        res.outputs
            .push(sol.outputs.iter().map(|hs| hs[1.min(h)]).collect());
        res.harmonics.push(sol.outputs.clone());
        res.power.push(energy.iter().sum::<f64>() * f);
        // The modal route's field solves the truncated model: there the check is the
        // claim's consistency, the residual the truncation error (as in mode fast).
        let converged = sol.converged
            && check.is_some_and(|v| {
                if hb.modal.is_some() {
                    v.consistency <= 1.0
                } else {
                    v.passes(it.tolerance)
                }
            });
        res.iterations.push(sol.iterations);
        res.converged.push(converged);
        res.singular.push(false);
        res.failed.push(None);
        res.checks.push(check.filter(|_| converged));
        start = sol.converged.then_some(sol.r);
    }
    res.factorizations = hb.stats.factorizations;
    res.gmres_solves = hb.stats.gmres_iterations;
    *res.timings.entry("receptance solves".into()).or_default() += hb.stats.receptance_seconds;
    *res.timings
        .entry("harmonic balance (AFT + Newton)".into())
        .or_default() += hb.stats.contact_seconds;
    // CPU seconds beside the wall ones: on a shared machine the wall split is noise.
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
