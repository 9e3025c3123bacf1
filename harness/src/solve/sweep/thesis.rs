//! Thesis mode: the UEXTERNALDB-style multi-pass scheme of §4.3.2 (Fig. 4.27, 4.33), run
//! through the library's store exactly as Abaqus would drive UINTER and UEXTERNALDB.
//!
//! Each pass is one "analysis" (LOP 0 … LOP 3) whose step 2 (LOP 5/6) is the steady-state
//! step; every frequency increment KINC is LOP 1, one UINTER call (LINPER = 1) per closed
//! point — k* in DDSDDR, d* in DVISCOUS for the store's amplitude estimate — one
//! factorization and solve, the computed amplitudes reported to the store, LOP 2. The
//! store decides what runs next: pass 1 all frequencies (the first with the initial
//! estimate, each later one with the previous increment's amplitude), then re-runs of the
//! increments out of tolerance, then one final pass over all of them. Cubic springs are
//! points of the same store, registered by the host and linearized through
//! `jointlin_linearize_cubic` for the store's estimate (amplitude in direction 1; 0 is
//! reported in direction 2). The static step
//! (step 1) is solved once before the first pass and reused by the re-runs, as an Abaqus
//! restart from the end of step 1 would.

use std::time::Instant;

use super::posteriori::{self, Claim};
use super::{Options, PassRecord, PointFreq, Setup, SweepError, SweepResult, C64};
use crate::capi::{self, Action, Store, NSTATV};
use crate::solve::contact::{interface_props, tangential};
use crate::solve::static_step::{uinter_point, StaticState};

/// KSTEP of the steady-state step (step 1 is the static preload).
pub const SWEEP_STEP: i32 = 2;

/// Runs the thesis sweep.
pub fn sweep(
    setup: &mut Setup,
    stat: &StaticState,
    freqs: &[f64],
    opts: &Options,
    progress: &dyn Fn(&str, usize, usize),
) -> Result<SweepResult, SweepError> {
    let p = setup.problem;
    let eff = opts.effects;
    let it = opts.iteration;
    let na = setup.active.len();
    let springs = &p.cubic_springs;
    let nf = freqs.len();
    let mut res = SweepResult {
        freqs: freqs.to_vec(),
        outputs: vec![Vec::new(); nf],
        power: vec![0.0; nf],
        iterations: vec![0; nf],
        converged: vec![na == 0 && springs.is_empty(); nf],
        singular: vec![false; nf],
        checks: vec![None; nf],
        failed: vec![None; nf],
        ..Default::default()
    };
    // Per frequency: the last solve passed the a-posteriori check (posteriori.rs).
    let mut checked = vec![true; nf];
    if opts.point_results {
        res.points = vec![vec![PointFreq::default(); p.contacts.len()]; nf];
    }
    let props: Vec<[f64; 12]> = p.interfaces.iter().map(interface_props).collect();
    let mut statev: Vec<[f64; NSTATV]> = setup.active.iter().map(|&i| stat.statev[i]).collect();
    // A host that never ran LINPER = 0 (normal nonlinearity off) hands p0 in STATEV as
    // the library reads it: closed flag and base pressure.
    if !eff.normal_contact_nonlinearity {
        for (sv, &i) in statev.iter_mut().zip(&setup.active) {
            sv[1] = stat.pressure[i];
            sv[3] = 1.0;
        }
    }
    let slip_limit: Vec<f64> = if eff.macroslip {
        Vec::new()
    } else {
        setup
            .active
            .iter()
            .map(|&i| {
                let c = &p.contacts[i];
                capi::linearize(
                    &tangential(&p.interfaces[c.interface], stat.pressure[i]),
                    0.0,
                    1.0,
                )
                .map(|l| l.slip_limit)
            })
            .collect::<Result<_, _>>()?
    };

    let mut x = vec![C64::new(0.0, 0.0); p.sys.dofs.n_free()];
    let mut kappa = vec![[C64::new(0.0, 0.0); 2]; na];
    let mut ks: Vec<f64> = springs.iter().map(|sp| sp.stiffness).collect();
    let mut spring_estimate = vec![0.0; springs.len()];
    let mut ids = vec![0i64; na];
    let mut outs = vec![capi::UinterOut::default(); na];

    // Without varying contact or cubic springs there is nothing to iterate: one linear
    // sweep.
    if na == 0 && springs.is_empty() {
        for (fi, &f) in freqs.iter().enumerate() {
            progress("frequency", fi + 1, nf);
            let omega = 2.0 * std::f64::consts::PI * f;
            res.singular[fi] = !solve_one(setup, omega, &kappa, &ks, &mut x, &mut res, f)?;
            res.converged[fi] = !res.singular[fi];
            res.outputs[fi] = p.outputs.iter().map(|o| o.value(&x)).collect();
        }
        res.passes.push(PassRecord {
            pass: 1,
            kind: "linear".into(),
            frequencies: freqs.to_vec(),
            converged: nf,
        });
        return Ok(res);
    }

    // atol from the stuck response's scale (one factorization per frequency), not from
    // the start estimate.
    let t = Instant::now();
    let atol = super::ATOL_REL * super::scale::stuck_scale(setup, freqs)?;
    res.time("amplitude scale (stuck response)", t);
    let t = Instant::now();
    let store = Store::new(
        it.initial_amplitude,
        it.tolerance,
        atol,
        it.scheme,
        it.max_passes,
        SWEEP_STEP,
    )?;
    let spring_ids = springs
        .iter()
        .map(|sp| {
            let name = format!("cubic spring {}", sp.spring + 1);
            store.register_point(&name, sp.node as i32, sp.position)
        })
        .collect::<Result<Vec<_>, _>>()?;
    res.time("store (C API)", t);
    loop {
        let t = Instant::now();
        let (action, pass) = store.next_action()?;
        res.time("store (C API)", t);
        let (kind, list): (&str, Vec<i32>) = match action {
            Action::RunSweep => ("first", (1..=nf as i32).collect()),
            Action::RunPass(l) => ("rerun", l),
            Action::RunFinal(l) => ("final", l),
            Action::Done => break,
            Action::Failed(l) => {
                res.converged.iter_mut().for_each(|c| *c = true);
                for k in l {
                    res.converged[k as usize - 1] = false;
                }
                break;
            }
            Action::Running => unreachable!("no pass is open between analyses"),
        };
        store.external_db(0, 0, 0)?;
        store.external_db(5, SWEEP_STEP, 0)?;
        'increments: for (li, &kinc) in list.iter().enumerate() {
            progress(&format!("pass {pass} ({kind})"), li + 1, list.len());
            let fi = kinc as usize - 1;
            let f = freqs[fi];
            let omega = 2.0 * std::f64::consts::PI * f;
            store.external_db(1, SWEEP_STEP, kinc)?;
            // A library call or a solve that fails in this increment fails this frequency
            // only (status `failed`, the message in run.json): its points stay
            // unreported, so the store counts the increment not converged and re-runs it
            // in the next pass (a later estimate may succeed), as a failed UINTER
            // increment would be in an FE job.
            macro_rules! per_freq {
                ($e:expr) => {
                    match $e {
                        Ok(v) => v,
                        Err(e) => {
                            let e: SweepError = e.into();
                            res.failed[fi] = Some(e.to_string());
                            res.outputs[fi] = vec![C64::new(0.0, 0.0); p.outputs.len()];
                            res.power[fi] = 0.0;
                            if opts.point_results {
                                res.points[fi].fill(PointFreq::default());
                            }
                            res.iterations[fi] += 1;
                            store.external_db(2, SWEEP_STEP, kinc)?;
                            continue 'increments;
                        }
                    }
                };
            }
            res.failed[fi] = None;
            let t = Instant::now();
            for (j, &i) in setup.active.iter().enumerate() {
                let c = &p.contacts[i];
                let pt = uinter_point(p, c, &props[c.interface]);
                let o = per_freq!(capi::uinter_linear(
                    &store,
                    &pt,
                    &mut statev[j],
                    f,
                    SWEEP_STEP,
                    kinc
                ));
                ids[j] = o.report.point;
                kappa[j] = std::array::from_fn(|d| {
                    let damp = if eff.contact_damping {
                        omega * o.dviscous[1 + d][1 + d]
                    } else {
                        0.0
                    };
                    C64::new(o.ddsddr[1 + d][1 + d], damp)
                });
                outs[j] = o;
            }
            res.time("linearization (C API)", t);
            let t = Instant::now();
            for (q, (sp, &id)) in springs.iter().zip(&spring_ids).enumerate() {
                let [a, _] = per_freq!(store.estimate(id, kinc));
                spring_estimate[q] = a;
                ks[q] = per_freq!(capi::linearize_cubic(sp.stiffness, sp.cubic, a));
            }
            res.time(super::fast::CUBIC_TIMING, t);
            res.singular[fi] =
                !per_freq!(solve_one(setup, omega, &kappa, &ks, &mut x, &mut res, f));
            if res.singular[fi] && opts.point_results {
                res.points[fi].fill(PointFreq::default());
            }
            if !res.singular[fi] {
                let t = Instant::now();
                let amplitudes: Vec<[f64; 2]> = outs.iter().map(|o| o.report.amplitude).collect();
                let caps: Vec<f64> = if eff.macroslip {
                    vec![f64::INFINITY; na]
                } else {
                    slip_limit.clone()
                };
                let claim = Claim {
                    kappa_off: &[],
                    correlation: &[],
                    kappa: &kappa,
                    amplitudes: &amplitudes,
                    caps: &caps,
                    spring_k: &ks,
                };
                let v = posteriori::check(setup, omega, &claim, &x, it.tolerance, atol);
                res.checks[fi] = Some(v);
                checked[fi] = v.passes(it.tolerance);
                res.time("a-posteriori check", t);
            }
            let t = Instant::now();
            if x.iter().any(|v| !v.is_finite()) {
                per_freq!(Err(SweepError::NotFinite { freq: f }));
            }
            let mut power = 0.0;
            for (j, &i) in setup.active.iter().enumerate() {
                let d = setup.tangential(j, &x);
                // Singular: no response (x = 0); the store gets its own estimate back so
                // the pass moves on, and the frequency is marked singular below.
                let mut amp = if res.singular[fi] {
                    outs[j].report.amplitude
                } else {
                    [d[0].norm(), d[1].norm()]
                };
                if !eff.macroslip {
                    for v in amp.iter_mut() {
                        if *v > slip_limit[j] {
                            *v = slip_limit[j];
                            res.macroslip_caps += 1;
                        }
                    }
                }
                per_freq!(store.report(ids[j], kinc, amp));
                let c = &p.contacts[i];
                let e = if eff.contact_damping {
                    outs[j].report.energy_per_cycle * c.area
                } else {
                    0.0
                };
                if res.singular[fi] {
                    continue;
                }
                power += e * f;
                if opts.point_results {
                    let rep = &outs[j].report;
                    // A/δ* is not in the UINTER report: one jointlin_linearize per
                    // direction, only because per-point output was asked for.
                    let tg = tangential(&p.interfaces[c.interface], stat.pressure[i]);
                    let ratio = [
                        per_freq!(capi::linearize(&tg, rep.amplitude[0], omega)).amplitude_ratio,
                        per_freq!(capi::linearize(&tg, rep.amplitude[1], omega)).amplitude_ratio,
                    ];
                    res.points[fi][i] = PointFreq {
                        amplitude: amp,
                        k_star: rep.k_star,
                        d_star: if eff.contact_damping {
                            rep.d_star
                        } else {
                            [0.0; 2]
                        },
                        energy: e,
                        ratio,
                        regime: rep.regime,
                    };
                }
            }
            for (q, (sp, &id)) in springs.iter().zip(&spring_ids).enumerate() {
                // Singular: the estimate back, as for the contact points.
                let amp = if res.singular[fi] {
                    spring_estimate[q]
                } else {
                    sp.row.iter().map(|&(i, w)| x[i] * w).sum::<C64>().norm()
                };
                per_freq!(store.report(id, kinc, [amp, 0.0]));
            }
            res.time("reporting and point outputs", t);
            res.power[fi] = power;
            res.outputs[fi] = p.outputs.iter().map(|o| o.value(&x)).collect();
            res.iterations[fi] += 1;
            store.external_db(2, SWEEP_STEP, kinc)?;
        }
        store.external_db(6, SWEEP_STEP, 0)?;
        store.external_db(3, SWEEP_STEP, 0)?;
        let stats = store.pass_stats(pass)?;
        if kind == "final" {
            // The final pass confirms convergence increment by increment.
            for &k in &list {
                res.converged[k as usize - 1] = true;
            }
        }
        res.passes.push(PassRecord {
            pass,
            kind: kind.into(),
            frequencies: list.iter().map(|&k| freqs[k as usize - 1]).collect(),
            converged: stats.increments_converged as usize,
        });
    }
    // A final pass that found an increment out of tolerance turns into a re-run; what
    // the store left unconverged was marked above. A singular frequency has no response.
    for (((c, &s), &ok), e) in res
        .converged
        .iter_mut()
        .zip(&res.singular)
        .zip(&checked)
        .zip(&res.failed)
    {
        *c &= !s && ok && e.is_none();
    }
    for (b, &c) in res.checks.iter_mut().zip(&res.converged) {
        if !c {
            *b = None;
        }
    }
    Ok(res)
}

/// Fills S(ω, κ, k* of the cubic springs), factors it and solves for the excitation into
/// `x`; false (and x = 0) when S is singular ([`super::SINGULAR_RCOND`]).
fn solve_one(
    setup: &mut Setup,
    omega: f64,
    kappa: &[[C64; 2]],
    spring_k: &[f64],
    x: &mut [C64],
    res: &mut SweepResult,
    f: f64,
) -> Result<bool, SweepError> {
    let t = Instant::now();
    setup.fill(omega, kappa, spring_k);
    let num = setup.factor(f)?;
    res.factorizations += 1;
    res.time("factorization", t);
    let Some(num) = num else {
        x.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        return Ok(false);
    };
    let t = Instant::now();
    num.solve_into(&setup.problem.excitation, x)
        .map_err(|source| SweepError::Umfpack { freq: f, source })?;
    res.time("solves", t);
    // Singular by the bound of this solve too (an undamped resonance no pivot shows).
    if setup.rcond_bound(&setup.problem.excitation, x) < super::SINGULAR_RCOND {
        x.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
        return Ok(false);
    }
    Ok(true)
}
