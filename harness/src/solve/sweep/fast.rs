//! Fast mode: per frequency one numeric factorization; the contact iterations reuse it,
//! either condensed onto the contact unknowns (m ≤ [`CONDENSE_MAX`]) or with FGMRES
//! preconditioned by it ([`super::krylov`], m larger).
//!
//! With S₀ = S(ω, κ₀) for a reference contact state κ₀ = κ(a₀) of the start estimate a₀
//! (the previous frequencies' converged amplitudes, extrapolated in ln a) and
//! the contact map B (rows: tangential relative displacements of the active points, then
//! the elongations of the cubic springs, whose κ is their k* and whose "area" is 1),
//! S(ω, κ) = S₀ + Bᵀ Δ B with Δ = diag((κ − κ₀)·area). Then r = B û solves
//!
//!   (I + G Δ) r = r₀,   G = B S₀⁻¹ Bᵀ (receptance, m × m),  r₀ = B S₀⁻¹ f̂,
//!
//! and outputs are ŷ = C S₀⁻¹ f̂ − (C S₀⁻¹ Bᵀ) Δ r. G comes from m solves with the one
//! factorization (column by column into scratch: memory O(n + m²)); every contact
//! iteration is then a dense m × m solve plus m `jointlin_linearize` calls. With FGMRES
//! each contact iteration solves (S₀ + BᵀΔB) û = f̂ from the previous û (measured 1–2
//! solves with the factorization per iteration, none in the first). Amplitudes
//! a = |r| are iterated to consistency with Anderson acceleration in ln a, or, for a single
//! amplitude, with a bracketed scalar root search ([`super::bracket`], global: it follows
//! the start's branch and jumps only where that branch ends); convergence is the store's
//! test |a − a*| ≤ rtol·max(a, a*) + atol per point and direction.

use std::time::Instant;

use super::driver::{drive, FrequencySolver, Outcome, Row, Shape};
use super::fast_unknowns::Unknowns;
use super::fast_update::predict;
use super::fast_workspace::Workspace;
use super::modal_route::{LinearRoute, ModalRoute};
use super::{Options, PassRecord, Setup, SweepError, SweepResult};
use crate::model::Problem;
use crate::solve::static_step::StaticState;

/// Condensation (m receptance solves, dense m × m iterations) up to this many contact
/// unknowns; above it the contact iterations use FGMRES preconditioned by the
/// frequency's factorization ([`super::krylov`]), whose cost does not grow with m³.
pub const CONDENSE_MAX: usize = 16;

pub use super::fast_unknowns::CUBIC_TIMING;

/// Runs the fast sweep.
pub fn sweep(
    setup: &mut Setup,
    freqs: &[f64],
    opts: &Options,
    progress: &dyn Fn(&str, usize, usize),
    cache: &mut Option<ModalRoute>,
) -> Result<SweepResult, SweepError> {
    let mut res = SweepResult::default();
    let t = Instant::now();
    let un = Unknowns::new(setup, opts.effects)?;
    res.time("linearization (C API)", t);
    let p = setup.problem;
    // The modal route always condenses: its G costs m × p × m, not m solves.
    let condensed = un.m <= opts.condense_max || opts.linear != LinearRoute::Direct;
    let mut ws = Workspace::new(&un, p.sys.dofs.n_free(), p.outputs.len(), condensed, opts);
    let modal = match opts.linear {
        LinearRoute::Modal { modes, residual } => {
            let f0 = freqs.first().copied().unwrap_or(0.0);
            Some(ws.modal_basis(setup, &un, (modes, residual), f0, cache, &mut res)?)
        }
        LinearRoute::Direct => None,
    };
    let shape = Shape::of(p, opts);
    let mut solver = Fast {
        setup,
        un,
        ws,
        modal,
        opts,
    };
    drive(&mut solver, freqs, shape, progress, &mut res);
    let nconv = res.converged.iter().filter(|&&c| c).count();
    res.passes.push(PassRecord {
        pass: 1,
        kind: "fast".into(),
        frequencies: freqs.to_vec(),
        converged: nconv,
    });
    Ok(res)
}

/// The fast sweep's modal basis of `problem` after `stat` with `opts` (whose route is
/// modal), built before any sweep: a study that divides its range at the stuck
/// eigenfrequencies takes them from it, and hands it to [`super::run_cached`], which uses it
/// as the sweep would have built it. `f0` (1/time) is the sweep's first frequency.
pub fn modal_basis(
    problem: &Problem,
    stat: &StaticState,
    opts: &Options,
    f0: f64,
) -> Result<ModalRoute, SweepError> {
    let LinearRoute::Modal { modes, residual } = opts.linear else {
        return Err(SweepError::ModalBasisNeedsModalRoute);
    };
    let mut setup = Setup::new(problem, stat, &opts.effects)
        .map_err(|source| SweepError::Umfpack { freq: f0, source })?;
    let un = Unknowns::new(&setup, opts.effects)?;
    let (n, nout) = (problem.sys.dofs.n_free(), problem.outputs.len());
    let mut ws = Workspace::new(&un, n, nout, true, opts);
    let mut cache = None;
    let mut res = SweepResult::default();
    ws.modal_basis(&mut setup, &un, (modes, residual), f0, &mut cache, &mut res)?;
    Ok(cache.expect("modal_basis fills the cache"))
}

/// The fast mode as a per-frequency solver.
struct Fast<'s, 'a> {
    setup: &'s mut Setup<'a>,
    un: Unknowns<'a>,
    ws: Workspace,
    /// The modal route's basis, when the linear part is modal.
    modal: Option<&'s mut ModalRoute>,
    opts: &'s Options,
}

impl FrequencySolver for Fast<'_, '_> {
    fn solve(&mut self, f: f64, res: &mut SweepResult) -> Result<Outcome, SweepError> {
        let Fast {
            setup,
            un,
            ws,
            modal,
            opts,
        } = self;
        let it = opts.iteration;
        let omega = 2.0 * std::f64::consts::PI * f;
        // Predictor: linear extrapolation of ln a over frequency from the last two
        // converged frequencies (the start estimate).
        predict(&ws.hist, f, &mut ws.a);
        // The factorized reference is the start estimate's own state κ(a₀): the first
        // contact iteration then needs no Krylov step (Δ = 0, û = S₀⁻¹f exactly).
        let fresh = un.m > 0;
        if fresh {
            ws.linearize(un, omega, res)?;
            if modal.is_none() {
                ws.take_reference(un, omega);
            }
        }
        let t = Instant::now();
        if modal.is_none() {
            let (kappa0, ks0) = ws.reference_state();
            setup.fill(omega, kappa0, ks0);
        }
        let setup: &Setup = setup;
        let num = match modal.as_deref_mut() {
            Some(route) => {
                let t = Instant::now();
                let regular = ws.modal_reference(route, omega);
                res.time("modal receptance", t);
                if !regular {
                    // An undamped eigenfrequency of the stuck structure.
                    return Ok(ws.singular());
                }
                None
            }
            // Singular dynamic stiffness (e.g. an undamped eigenfrequency with the joint
            // open): no response; the next frequency starts afresh.
            None => match ws.reference(setup, un, f, t, res)? {
                Some(num) => Some(num),
                None => return Ok(ws.singular()),
            },
        };
        let s0 = (&setup.s, num.as_ref());
        let (iterations, mut converged, gmres_ok) = ws.iterate(un, s0, f, fresh, it, res)?;
        let mut check = None;
        let mut field = None;
        if converged && gmres_ok {
            let t = Instant::now();
            let v = ws.check(
                setup,
                un,
                (num.as_ref(), modal.as_deref_mut()),
                omega,
                f,
                it,
            )?;
            check = Some(v);
            // The modal route solves the truncated model: its residual in the full
            // equations is the truncation error (reported), not a convergence test.
            converged = if modal.is_some() {
                v.consistency <= 1.0
            } else {
                v.passes(it.tolerance)
            };
            res.time("a-posteriori check", t);
            if converged && opts.keep_fields {
                field = Some(ws.field().to_vec());
            }
        }
        drop(num);
        let row = ws.row(un, f, opts.point_results, res);
        // The next frequency starts from this converged state (extrapolated).
        if converged && un.m > 0 {
            ws.hist.push((f, ws.a.clone()));
            if ws.hist.len() > 2 {
                ws.hist.remove(0);
            }
        } else {
            ws.hist.clear();
        }
        Ok(Outcome::Solved(Row {
            iterations,
            converged: converged && gmres_ok,
            check,
            field,
            ..row
        }))
    }

    fn restart(&mut self) {
        let ws = &mut self.ws;
        ws.hist.clear();
        ws.a.iter_mut()
            .for_each(|v| *v = self.opts.iteration.initial_amplitude);
        ws.rho.iter_mut().for_each(|v| *v = 0.0);
    }
}
