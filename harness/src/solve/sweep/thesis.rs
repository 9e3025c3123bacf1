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
use crate::model::CubicSpring;
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
    if opts.point_results {
        res.points = vec![vec![PointFreq::default(); p.contacts.len()]; nf];
    }
    let props: Vec<[f64; 12]> = p.interfaces.iter().map(interface_props).collect();
    // Without varying contact or cubic springs there is nothing to iterate: one linear
    // sweep.
    if na == 0 && springs.is_empty() {
        linear_sweep(setup, freqs, &mut res, progress)?;
        return Ok(res);
    }
    let statev = statev_at_rest(setup, stat, eff.normal_contact_nonlinearity);
    let slip_limit = if eff.macroslip {
        Vec::new()
    } else {
        slip_limits(setup, stat)?
    };

    // atol from the stuck response's scale (one factorization per frequency), not from
    // the start estimate.
    let t = Instant::now();
    let atol = super::ATOL_REL * super::scale::stuck_scale(setup, freqs)?;
    res.time("amplitude scale (stuck response)", t);
    let t = Instant::now();
    let (store, spring_ids) = open_store(opts, atol, springs)?;
    res.time("store (C API)", t);
    let mut work = Increments {
        setup,
        stat,
        opts,
        store: &store,
        freqs,
        atol,
        props,
        statev,
        slip_limit,
        ids: vec![0i64; na],
        outs: vec![capi::UinterOut::default(); na],
        kappa: vec![[C64::new(0.0, 0.0); 2]; na],
        spring_ids,
        ks: springs.iter().map(|sp| sp.stiffness).collect(),
        spring_estimate: vec![0.0; springs.len()],
        x: vec![C64::new(0.0, 0.0); p.sys.dofs.n_free()],
        checked: vec![true; nf],
    };
    loop {
        let t = Instant::now();
        let (action, pass) = store.next_action()?;
        res.time("store (C API)", t);
        let Some((kind, list)) = next_pass(action, &mut res) else {
            break;
        };
        store.external_db(0, 0, 0)?;
        store.external_db(5, SWEEP_STEP, 0)?;
        for (li, &kinc) in list.iter().enumerate() {
            progress(&format!("pass {pass} ({kind})"), li + 1, list.len());
            let fi = kinc as usize - 1;
            store.external_db(1, SWEEP_STEP, kinc)?;
            // A library call or a solve that fails in this increment fails this frequency
            // only (status `failed`, the message in run.json): its points stay
            // unreported, so the store counts the increment not converged and re-runs it
            // in the next pass (a later estimate may succeed), as a failed UINTER
            // increment would be in an FE job.
            res.failed[fi] = None;
            if let Err(e) = work.increment(&mut res, fi, kinc) {
                failed(&mut res, fi, &e, p.outputs.len());
            }
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
    settle(&mut res, &work.checked);
    Ok(res)
}

/// The sweep of a model with no varying contact and no cubic spring: one linear solve
/// per frequency, one pass.
fn linear_sweep(
    setup: &mut Setup,
    freqs: &[f64],
    res: &mut SweepResult,
    progress: &dyn Fn(&str, usize, usize),
) -> Result<(), SweepError> {
    let p = setup.problem;
    let mut x = vec![C64::new(0.0, 0.0); p.sys.dofs.n_free()];
    for (fi, &f) in freqs.iter().enumerate() {
        progress("frequency", fi + 1, freqs.len());
        let omega = 2.0 * std::f64::consts::PI * f;
        res.singular[fi] = !solve_one(setup, omega, &[], &[], &mut x, res, f)?;
        res.converged[fi] = !res.singular[fi];
        res.outputs[fi] = p.outputs.iter().map(|o| o.value(&x)).collect();
    }
    res.passes.push(PassRecord {
        pass: 1,
        kind: "linear".into(),
        frequencies: freqs.to_vec(),
        converged: freqs.len(),
    });
    Ok(())
}

/// The library's store for the sweep step with the scene's iteration settings and
/// absolute tolerance `atol` (length), and the store ids of the cubic springs.
fn open_store(
    opts: &Options,
    atol: f64,
    springs: &[CubicSpring],
) -> Result<(Store, Vec<i64>), SweepError> {
    let it = opts.iteration;
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
    Ok((store, spring_ids))
}

/// The pass the store's `action` asks for: its kind and its increments (KINC), or
/// `None` when the analysis ends (`Failed`: the increments the store gave up on are
/// marked not converged in `res`).
fn next_pass(action: Action, res: &mut SweepResult) -> Option<(&'static str, Vec<i32>)> {
    match action {
        Action::RunSweep => Some(("first", (1..=res.freqs.len() as i32).collect())),
        Action::RunPass(l) => Some(("rerun", l)),
        Action::RunFinal(l) => Some(("final", l)),
        Action::Done => None,
        Action::Failed(l) => {
            res.converged.iter_mut().for_each(|c| *c = true);
            for k in l {
                res.converged[k as usize - 1] = false;
            }
            None
        }
        Action::Running => unreachable!("no pass is open between analyses"),
    }
}

/// Row `fi` of `res` failed with `e`: no outputs (`n_outputs` zeros), power or point
/// results, the message kept.
fn failed(res: &mut SweepResult, fi: usize, e: &SweepError, n_outputs: usize) {
    res.failed[fi] = Some(e.to_string());
    res.outputs[fi] = vec![C64::new(0.0, 0.0); n_outputs];
    res.power[fi] = 0.0;
    if let Some(points) = res.points.get_mut(fi) {
        points.fill(PointFreq::default());
    }
}

/// STATEV of the active points after the static step. A host that never ran LINPER = 0
/// (`normal_nonlinearity` off) hands p0 in STATEV as the library reads it: closed flag
/// and base pressure.
fn statev_at_rest(
    setup: &Setup,
    stat: &StaticState,
    normal_nonlinearity: bool,
) -> Vec<[f64; NSTATV]> {
    let mut statev: Vec<[f64; NSTATV]> = setup.active.iter().map(|&i| stat.statev[i]).collect();
    if !normal_nonlinearity {
        for (sv, &i) in statev.iter_mut().zip(&setup.active) {
            sv[1] = stat.pressure[i];
            sv[3] = 1.0;
        }
    }
    statev
}

/// The slip limit δ* (length) of each active point at its static pressure (2.46),
/// docs/model.md.
fn slip_limits(setup: &Setup, stat: &StaticState) -> Result<Vec<f64>, SweepError> {
    let p = setup.problem;
    let limits = setup
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
        .collect::<Result<_, _>>()?;
    Ok(limits)
}

/// Final convergence of each frequency: a final pass that found an increment out of
/// tolerance turned into a re-run; what the store left unconverged was marked; a
/// singular, failed or a-posteriori-rejected (`checked` false) frequency is not
/// converged and keeps no check.
fn settle(res: &mut SweepResult, checked: &[bool]) {
    for (((c, &s), &ok), e) in res
        .converged
        .iter_mut()
        .zip(&res.singular)
        .zip(checked)
        .zip(&res.failed)
    {
        *c &= !s && ok && e.is_none();
    }
    for (b, &c) in res.checks.iter_mut().zip(&res.converged) {
        if !c {
            *b = None;
        }
    }
}

/// What the increments of a thesis sweep share and carry from one to the next.
struct Increments<'a, 'p> {
    setup: &'a mut Setup<'p>,
    stat: &'a StaticState,
    opts: &'a Options,
    store: &'a Store,
    freqs: &'a [f64],
    /// Absolute amplitude tolerance (length).
    atol: f64,
    /// UINTER PROPS per interface.
    props: Vec<[f64; 12]>,
    /// Per active point: STATEV, the slip limit δ* (length; empty with macroslip), the
    /// store's point id, the last UINTER output and κ = k* + iωd* per direction.
    statev: Vec<[f64; NSTATV]>,
    slip_limit: Vec<f64>,
    ids: Vec<i64>,
    outs: Vec<capi::UinterOut>,
    kappa: Vec<[C64; 2]>,
    /// Per cubic spring: the store's point id, k* and the amplitude estimate (length).
    spring_ids: Vec<i64>,
    ks: Vec<f64>,
    spring_estimate: Vec<f64>,
    /// The response (free DOFs) of the last increment.
    x: Vec<C64>,
    /// Per frequency: the last solve passed the a-posteriori check (posteriori.rs).
    checked: Vec<bool>,
}

impl Increments<'_, '_> {
    /// Increment `kinc` (frequency `fi`): UINTER per active point, the cubic springs'
    /// k*, the solve, the a-posteriori check and the amplitudes reported to the store,
    /// into row `fi` of `res`. An error fails this frequency only.
    fn increment(&mut self, res: &mut SweepResult, fi: usize, kinc: i32) -> Result<(), SweepError> {
        let p = self.setup.problem;
        let (store, opts) = (self.store, self.opts);
        let (eff, it) = (opts.effects, opts.iteration);
        let springs = &p.cubic_springs;
        let na = self.setup.active.len();
        let f = self.freqs[fi];
        let omega = 2.0 * std::f64::consts::PI * f;
        let t = Instant::now();
        for (j, &i) in self.setup.active.iter().enumerate() {
            let c = &p.contacts[i];
            let pt = uinter_point(p, c, &self.props[c.interface]);
            let o = capi::uinter_linear(store, &pt, &mut self.statev[j], f, SWEEP_STEP, kinc)?;
            self.ids[j] = o.report.point;
            self.kappa[j] = std::array::from_fn(|d| {
                let damp = if eff.contact_damping {
                    omega * o.dviscous[1 + d][1 + d]
                } else {
                    0.0
                };
                C64::new(o.ddsddr[1 + d][1 + d], damp)
            });
            self.outs[j] = o;
        }
        res.time("linearization (C API)", t);
        let t = Instant::now();
        for (q, (sp, &id)) in springs.iter().zip(&self.spring_ids).enumerate() {
            let [a, _] = store.estimate(id, kinc)?;
            self.spring_estimate[q] = a;
            self.ks[q] = capi::linearize_cubic(sp.stiffness, sp.cubic, a)?;
        }
        res.time(super::fast::CUBIC_TIMING, t);
        res.singular[fi] = !solve_one(
            self.setup,
            omega,
            &self.kappa,
            &self.ks,
            &mut self.x,
            res,
            f,
        )?;
        if res.singular[fi] && opts.point_results {
            res.points[fi].fill(PointFreq::default());
        }
        if !res.singular[fi] {
            let t = Instant::now();
            let amplitudes: Vec<[f64; 2]> = self.outs.iter().map(|o| o.report.amplitude).collect();
            let caps: Vec<f64> = if eff.macroslip {
                vec![f64::INFINITY; na]
            } else {
                self.slip_limit.clone()
            };
            let claim = Claim {
                kappa_off: &[],
                correlation: &[],
                kappa: &self.kappa,
                amplitudes: &amplitudes,
                caps: &caps,
                spring_k: &self.ks,
            };
            let v = posteriori::check(self.setup, omega, &claim, &self.x, it.tolerance, self.atol);
            res.checks[fi] = Some(v);
            self.checked[fi] = v.passes(it.tolerance);
            res.time("a-posteriori check", t);
        }
        self.report(res, fi, kinc)
    }

    /// The response of increment `kinc` (frequency `fi`) reported to the store: each
    /// point's amplitude (capped at δ* without macroslip), its energy and outputs, the
    /// cubic springs' amplitudes; row `fi` of `res` gets power and outputs.
    fn report(&mut self, res: &mut SweepResult, fi: usize, kinc: i32) -> Result<(), SweepError> {
        let p = self.setup.problem;
        let (store, stat, opts) = (self.store, self.stat, self.opts);
        let eff = opts.effects;
        let springs = &p.cubic_springs;
        let f = self.freqs[fi];
        let omega = 2.0 * std::f64::consts::PI * f;
        let t = Instant::now();
        if self.x.iter().any(|v| !v.is_finite()) {
            return Err(SweepError::NotFinite { freq: f });
        }
        let mut power = 0.0;
        for (j, &i) in self.setup.active.iter().enumerate() {
            let d = self.setup.tangential(j, &self.x);
            // Singular: no response (x = 0); the store gets its own estimate back so
            // the pass moves on, and the frequency is marked singular below.
            let mut amp = if res.singular[fi] {
                self.outs[j].report.amplitude
            } else {
                [d[0].norm(), d[1].norm()]
            };
            if !eff.macroslip {
                for v in amp.iter_mut() {
                    if *v > self.slip_limit[j] {
                        *v = self.slip_limit[j];
                        res.macroslip_caps += 1;
                    }
                }
            }
            store.report(self.ids[j], kinc, amp)?;
            let c = &p.contacts[i];
            let e = if eff.contact_damping {
                self.outs[j].report.energy_per_cycle * c.area
            } else {
                0.0
            };
            if res.singular[fi] {
                continue;
            }
            power += e * f;
            if opts.point_results {
                let rep = &self.outs[j].report;
                // A/δ* is not in the UINTER report: one jointlin_linearize per
                // direction, only because per-point output was asked for.
                let tg = tangential(&p.interfaces[c.interface], stat.pressure[i]);
                let ratio = [
                    capi::linearize(&tg, rep.amplitude[0], omega)?.amplitude_ratio,
                    capi::linearize(&tg, rep.amplitude[1], omega)?.amplitude_ratio,
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
        for (q, (sp, &id)) in springs.iter().zip(&self.spring_ids).enumerate() {
            // Singular: the estimate back, as for the contact points.
            let amp = if res.singular[fi] {
                self.spring_estimate[q]
            } else {
                sp.row
                    .iter()
                    .map(|&(i, w)| self.x[i] * w)
                    .sum::<C64>()
                    .norm()
            };
            store.report(id, kinc, [amp, 0.0])?;
        }
        res.time("reporting and point outputs", t);
        res.power[fi] = power;
        res.outputs[fi] = p.outputs.iter().map(|o| o.value(&self.x)).collect();
        Ok(())
    }
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
