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

use super::anderson::Anderson;
use super::bracket::Bracket;
use super::fast_coupled::{correlation, rho_consistent, CoupledPoints, Lin2};
use super::fast_update::{consistent, next_estimate, predict, updated_product};
use super::krylov::Gmres;
use super::modal_route::{LinearRoute, ModalRoute};
use super::posteriori::{self, Claim};
use super::receptance::Receptance;
use super::{Options, PassRecord, PointFreq, Setup, SweepError, SweepResult, C64};
use crate::capi::{self, Linearized, Tangential};
use crate::solve::contact::{area_average, tangential};
use crate::solve::dense::lu_solve_in_place;

/// Anderson history depth.
const DEPTH: usize = 5;
/// Condensation (m receptance solves, dense m × m iterations) up to this many contact
/// unknowns; above it the contact iterations use FGMRES preconditioned by the
/// frequency's factorization ([`super::krylov`]), whose cost does not grow with m³.
pub const CONDENSE_MAX: usize = 16;
/// FGMRES stops at ‖f − S u‖ ≤ GMRES_REL × rtol × ‖f‖ (1e-7 at the default rtol 1e-3:
/// far below the amplitude tolerance), or where that is below round-off, at the
/// residual's round-off floor ([`super::krylov::ROUNDOFF`]: as accurate as a direct solve
/// with the factorization); 1.1–1.3 solves per contact iteration on three-beams-coarse at
/// rtol 1e-3…1e-8. A fixed relative floor instead (1e-9) was out of reach near resonance,
/// where ‖S‖‖u‖/‖f‖ ≈ 4e7 there: those solves ran to GMRES_MAX and flagged their
/// frequencies not converged at rtol ≤ 1e-5 although the amplitudes had converged.
const GMRES_REL: f64 = 1e-4;
/// FGMRES restart length and most preconditioner applications per contact iteration.
const GMRES_RESTART: usize = 30;
const GMRES_MAX: usize = 300;
/// Amplitudes below this fraction of the largest one are round-off: handed to the
/// linearization as exactly 0 (k* = k_T0, d* = 0: the A → 0 limit; k* differs from it by
/// O(A/δ*)), floored there before taking logs, and equal to each other in the
/// convergence test. Without it a direction that is never excited (amplitude 0) would
/// drive ln a to −∞. Such directions come out of a solve as noise: up to 2.4e-11 of the
/// largest amplitude on three-beams-coarse (lateral directions of the bending modes),
/// with LU or FGMRES alike. A floor below the noise (1e-15 was) let FGMRES's noise,
/// different at each solve because each starts from the previous û, reach the Anderson
/// step as O(1) changes of ln a: 2–3× the condensed path's contact iterations, and two
/// frequencies near the second resonance that never converged at rtol ≤ 1e-6.
const ZERO_AMP_REL: f64 = 1e-9;
/// Timing key of the cubic springs' linearization calls.
pub const CUBIC_TIMING: &str = "cubic springs (C API)";

/// Runs the fast sweep.
pub fn sweep(
    setup: &mut Setup,
    freqs: &[f64],
    opts: &Options,
    progress: &dyn Fn(&str, usize, usize),
    cache: &mut Option<ModalRoute>,
) -> Result<SweepResult, SweepError> {
    let p = setup.problem;
    let eff = opts.effects;
    let it = opts.iteration;
    let na = setup.active.len();
    let springs = &p.cubic_springs;
    // Unknowns: 2 per active contact point (j < mc), then 1 per cubic spring.
    let mc = 2 * na;
    let m = mc + springs.len();
    let n = p.sys.dofs.n_free();
    let nout = p.outputs.len();
    let mut res = SweepResult {
        freqs: freqs.to_vec(),
        ..Default::default()
    };
    let tang: Vec<Tangential> = setup
        .active
        .iter()
        .map(|&i| {
            let c = &p.contacts[i];
            tangential(&p.interfaces[c.interface], setup.pressure[i])
        })
        .collect();
    let area: Vec<f64> = setup.active.iter().map(|&i| p.contacts[i].area).collect();
    // Area samples of sampled points: (tangential data at the sample's pressure, area
    // fraction), zero-pressure samples left out (they carry no friction).
    let samples: Vec<Vec<(Tangential, f64)>> = setup
        .active
        .iter()
        .map(|&i| {
            let itf = &p.interfaces[p.contacts[i].interface];
            setup.friction_samples[i]
                .iter()
                .filter(|(_, pr)| *pr > 0.0)
                .map(|&(f, pr)| (tangential(itf, pr), f))
                .collect()
        })
        .collect();
    // With coupled slip: the points' 2 × 2 describing functions (fast_coupled.rs).
    let coupled = eff
        .coupled_slip
        .then(|| CoupledPoints::new(&tang, &samples));
    // δ* per active point, only when macroslip is off or coupled slip reports A/δ*
    // (A = 0 gives δ* and k_T0).
    let t0 = Instant::now();
    let slip_limit: Vec<f64> = if eff.macroslip && coupled.is_none() {
        Vec::new()
    } else {
        tang.iter()
            .map(|t| capi::linearize(t, 0.0, 1.0).map(|l| l.slip_limit))
            .collect::<Result<_, _>>()?
    };
    res.time("linearization (C API)", t0);

    // Scratch, allocated once per sweep (G and O only when condensing).
    // The modal route always condenses: its G costs m × p × m, not m solves.
    let condensed = m <= opts.condense_max || opts.linear != LinearRoute::Direct;
    let mut rec = Receptance::new(n, if condensed { m } else { 0 }, nout);
    rec.r0 = vec![C64::new(0.0, 0.0); m];
    let mut u = vec![C64::new(0.0, 0.0); if condensed { 0 } else { n }];
    // The condensed path's full solution for the a-posteriori check, and its right side.
    let mut x_full = vec![C64::new(0.0, 0.0); if condensed { n } else { 0 }];
    let mut x_rhs = x_full.clone();
    let mut gmres = Gmres::<C64>::new(if condensed { 0 } else { n }, GMRES_RESTART);
    let mut work = vec![C64::new(0.0, 0.0); if condensed { m * m } else { 0 }];
    let mut r = vec![C64::new(0.0, 0.0); m];
    let mut delta = vec![C64::new(0.0, 0.0); m];
    let mut lin = vec![Linearized::default(); mc];
    let mut ks = vec![0.0; springs.len()];
    let mut ks0 = vec![0.0; springs.len()];
    let mut a = vec![it.initial_amplitude; m];
    // Converged estimates of the two previous frequencies, for the predictor.
    let mut hist: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut a_star = vec![0.0; m];
    let mut kappa0 = vec![[C64::new(0.0, 0.0); 2]; na];
    // Coupled slip: per point the phase cosine ρ (estimate and computed), the off-diagonal
    // of Δ (Δ₁₂ = Δ₂₁; the reference κ₀ is diagonal) and the describing function.
    let nc = if coupled.is_some() { na } else { 0 };
    let mut rho = vec![0.0; nc];
    let mut rho_star = vec![0.0; nc];
    let mut delta_off = vec![C64::new(0.0, 0.0); nc];
    let mut lin2 = vec![Lin2::default(); nc];
    let active = setup.active.clone();
    let row = |j: usize| {
        if j < mc {
            p.contacts[active[j / 2]].rows[1 + j % 2].as_slice()
        } else {
            springs[j - mc].row.as_slice()
        }
    };
    let weight = |j: usize| if j < mc { area[j / 2] } else { 1.0 };
    // ‖Bⱼ‖₂² per contact unknown: ‖Bⱼᵀ Δⱼ Bⱼ‖₂ = |Δⱼ|‖Bⱼ‖₂² bounds the update's norm.
    let row_norm2: Vec<f64> = (0..m)
        .map(|j| row(j).iter().map(|&(_, w)| w * w).sum())
        .collect();
    let zero_floor = |a: &[f64]| ZERO_AMP_REL * a.iter().fold(0.0f64, |x, &y| x.max(y));

    let linearize_all = |a: &[f64],
                         rho: &[f64],
                         omega: f64,
                         lin: &mut [Linearized],
                         lin2: &mut [Lin2],
                         caps: &mut usize|
     -> Result<(), capi::CapiError> {
        let floor = zero_floor(a);
        if let Some(cp) = &coupled {
            for q in 0..na {
                let mut amp = [a[2 * q], a[2 * q + 1]].map(|v| if v < floor { 0.0 } else { v });
                let major = amp[0].max(amp[1]);
                if !eff.macroslip && major > slip_limit[q] {
                    amp = amp.map(|v| v * slip_limit[q] / major);
                    *caps += 1;
                }
                let l = cp.linearize(q, amp, rho[q], omega)?;
                lin2[q] = l;
                // The diagonal as the thesis model's per-direction record (outputs, the
                // factorized reference); the energy is the point's, split evenly.
                for d in 0..2 {
                    let (k, dd) = (l.k[d][d], l.d[d][d]);
                    lin[2 * q + d] = Linearized {
                        k_star: k,
                        d_star: dd,
                        eta: if k > 0.0 { omega * dd / k } else { 0.0 },
                        energy_per_cycle: 0.5 * l.energy,
                        slip_limit: slip_limit[q],
                        amplitude_ratio: if slip_limit[q] > 0.0 {
                            amp[d] / slip_limit[q]
                        } else {
                            0.0
                        },
                        regime: l.regime,
                    };
                }
            }
            return Ok(());
        }
        for j in 0..mc {
            let mut amp = if a[j] < floor { 0.0 } else { a[j] };
            if !eff.macroslip && amp > slip_limit[j / 2] {
                amp = slip_limit[j / 2];
                *caps += 1;
            }
            lin[j] = capi::linearize(&tang[j / 2], amp, omega)?;
            if !p.contacts[active[j / 2]].samples.is_empty() {
                lin[j] = area_average(&lin[j], &samples[j / 2], amp, omega)?;
            }
        }
        Ok(())
    };
    // k* of every cubic spring (3.8) for its amplitude.
    let linearize_springs = |a: &[f64], ks: &mut [f64]| -> Result<(), capi::CapiError> {
        let floor = zero_floor(a);
        for (q, sp) in springs.iter().enumerate() {
            let amp = if a[mc + q] < floor { 0.0 } else { a[mc + q] };
            ks[q] = capi::linearize_cubic(sp.stiffness, sp.cubic, amp)?;
        }
        Ok(())
    };
    // κ = k* + iωd* of entry (i, j) of a coupled point's matrices.
    let kappa_of_2 = |l: &Lin2, i: usize, j: usize, omega: f64| {
        C64::new(
            l.k[i][j],
            if eff.contact_damping {
                omega * l.d[i][j]
            } else {
                0.0
            },
        )
    };
    let kappa_of = |l: &Linearized, omega: f64| {
        C64::new(
            l.k_star,
            if eff.contact_damping {
                omega * l.d_star
            } else {
                0.0
            },
        )
    };

    // Modal route: the reference is the stuck structure (κ₀ = κ at amplitude 0, the
    // springs' linear k) for every frequency, its modes and residual once (or from
    // `cache`, built by an earlier sweep of the same problem, with this sweep's load).
    let mut modal: Option<&mut ModalRoute> = None;
    if let LinearRoute::Modal { modes, residual } = opts.linear {
        let t = Instant::now();
        let omega = 2.0 * std::f64::consts::PI * freqs.first().copied().unwrap_or(0.0);
        let zeros = vec![0.0; m];
        linearize_all(&zeros, &rho, omega, &mut lin, &mut lin2, &mut 0)?;
        linearize_springs(&zeros, &mut ks0)?;
        for j in 0..mc {
            kappa0[j / 2][j % 2] = kappa_of(&lin[j], omega);
        }
        res.time("linearization (C API)", t);
        let t = Instant::now();
        match cache {
            Some(route) if route.serves((modes, residual), setup, &kappa0, &ks0) => {
                route
                    .set_load(&p.excitation, &row, &p.outputs)
                    .map_err(|source| SweepError::ModalField {
                        freq: freqs.first().copied().unwrap_or(0.0),
                        source,
                    })?;
            }
            _ => {
                *cache = Some(ModalRoute::new(
                    setup,
                    &kappa0,
                    &ks0,
                    (m, &row),
                    modes,
                    residual,
                )?)
            }
        }
        let route = cache.as_mut().expect("set above");
        res.modal = Some(route.summary.clone());
        modal = Some(route);
        res.time("modal basis (modes, residual)", t);
    }

    'freqs: for (fi, &f) in freqs.iter().enumerate() {
        progress("frequency", fi + 1, freqs.len());
        let omega = 2.0 * std::f64::consts::PI * f;
        // A library call or a solve that fails at this frequency fails this frequency
        // only (status `failed`, the message in run.json); the next one starts cold.
        macro_rules! per_freq {
            ($e:expr) => {
                match $e {
                    Ok(v) => v,
                    Err(e) => {
                        let e: SweepError = e.into();
                        res.push_failed(&e, nout, opts.point_results.then_some(p.contacts.len()));
                        hist.clear();
                        a.iter_mut().for_each(|v| *v = it.initial_amplitude);
                        rho.iter_mut().for_each(|v| *v = 0.0);
                        continue 'freqs;
                    }
                }
            };
        }
        // Predictor: linear extrapolation of ln a over frequency from the last two
        // converged frequencies (the start estimate; the factorized reference stays the
        // previous frequency's converged state).
        predict(&hist, f, &mut a);
        // The factorized reference is the start estimate's own state κ(a₀): the first
        // contact iteration then needs no Krylov step (Δ = 0, û = S₀⁻¹f exactly).
        let mut lin_fresh = false;
        if m > 0 {
            let t = Instant::now();
            per_freq!(linearize_all(
                &a,
                &rho,
                omega,
                &mut lin,
                &mut lin2,
                &mut res.macroslip_caps
            ));
            res.time("linearization (C API)", t);
            let t = Instant::now();
            per_freq!(linearize_springs(&a, &mut ks));
            res.time(CUBIC_TIMING, t);
            if modal.is_none() {
                for j in 0..mc {
                    kappa0[j / 2][j % 2] = kappa_of(&lin[j], omega);
                }
                ks0.copy_from_slice(&ks);
            }
            lin_fresh = true;
        }
        let umf = |e| SweepError::Umfpack { freq: f, source: e };
        let krylov = !condensed;
        let mut s0_norm = 0.0;
        let num = if let Some(route) = modal.as_mut() {
            let t = Instant::now();
            let regular = route.receptance(omega, &mut rec);
            res.time("modal receptance", t);
            if !regular {
                // An undamped eigenfrequency of the stuck structure: as below.
                res.push_singular(nout, opts.point_results.then_some(p.contacts.len()));
                hist.clear();
                continue;
            }
            None
        } else {
            let t = Instant::now();
            setup.fill(omega, &kappa0, &ks0);
            let num = per_freq!(setup.factor(f));
            res.factorizations += 1;
            res.time("factorization", t);
            let Some(num) = num else {
                // Singular dynamic stiffness (e.g. an undamped eigenfrequency with the
                // joint open): no response; the next frequency starts afresh.
                res.push_singular(nout, opts.point_results.then_some(p.contacts.len()));
                hist.clear();
                continue;
            };

            let t = Instant::now();
            // Upper bound of ‖S₀‖₂ for FGMRES's round-off floor.
            if krylov {
                s0_norm = setup.s.norm2_bound();
                per_freq!(num.solve_into(&p.excitation, &mut u).map_err(umf));
                for j in 0..m {
                    rec.r0[j] = row(j).iter().map(|&(i, w)| u[i] * w).sum();
                }
            } else {
                per_freq!(rec.load(&num, &p.excitation, &row, &p.outputs).map_err(umf));
            }
            // Singular by the bound of the load's solve (an undamped resonance that no
            // pivot shows): as above.
            let x0 = if krylov { &u } else { &rec.x };
            if setup.rcond_bound(&p.excitation, x0) < super::SINGULAR_RCOND {
                res.push_singular(nout, opts.point_results.then_some(p.contacts.len()));
                hist.clear();
                continue;
            }
            if !krylov {
                per_freq!(rec.condense(&num, &row, &p.outputs).map_err(umf));
            }
            res.time("receptance solves", t);
            Some(num)
        };

        let mut acc = Anderson::new(DEPTH);
        let mut bracket = Bracket::new();
        let mut gmres_ok = true;
        let mut iterations = 0;
        let mut converged = m == 0;
        r.copy_from_slice(&rec.r0);
        delta.iter_mut().for_each(|d| *d = C64::new(0.0, 0.0));
        // A start that is not the cold one may lie on a branch that ended at a fold
        // between this frequency and the last: then one more try from the cold start.
        let mut cold = a.iter().all(|&v| v == it.initial_amplitude);
        let mut budget = it.max_passes;
        let mut first = None;
        loop {
            while m > 0 && iterations < budget {
                iterations += 1;
                if !lin_fresh {
                    let t = Instant::now();
                    per_freq!(linearize_all(
                        &a,
                        &rho,
                        omega,
                        &mut lin,
                        &mut lin2,
                        &mut res.macroslip_caps
                    ));
                    res.time("linearization (C API)", t);
                    let t = Instant::now();
                    per_freq!(linearize_springs(&a, &mut ks));
                    res.time(CUBIC_TIMING, t);
                }
                lin_fresh = false;
                let t = Instant::now();
                for j in 0..m {
                    let (now, reference) = if j < mc {
                        (kappa_of(&lin[j], omega), kappa0[j / 2][j % 2])
                    } else {
                        (C64::new(ks[j - mc], 0.0), C64::new(ks0[j - mc], 0.0))
                    };
                    delta[j] = (now - reference) * weight(j);
                }
                for (q, l) in lin2.iter().enumerate() {
                    delta_off[q] = kappa_of_2(l, 0, 1, omega) * area[q];
                }
                if let Some(num) = num.as_ref().filter(|_| krylov) {
                    let s0 = &setup.s;
                    // ‖S₀ + BᵀΔB‖₂ ≤ ‖S₀‖₂ + Σⱼ |Δⱼ|‖Bⱼ‖₂².
                    // Coupled: ‖B₁ᵀΔ₁₂B₂ + B₂ᵀΔ₁₂B₁‖₂ ≤ 2|Δ₁₂|‖B₁‖₂‖B₂‖₂.
                    let anorm = s0_norm
                        + delta
                            .iter()
                            .zip(&row_norm2)
                            .map(|(d, b2)| d.norm() * b2)
                            .sum::<f64>()
                        + delta_off
                            .iter()
                            .enumerate()
                            .map(|(q, d)| {
                                2.0 * d.norm() * (row_norm2[2 * q] * row_norm2[2 * q + 1]).sqrt()
                            })
                            .sum::<f64>();
                    let stats = gmres.solve(
                        &mut |xv: &[C64], y: &mut [C64]| {
                            updated_product(s0, &delta, &delta_off, &row, xv, y)
                        },
                        &mut |xv: &[C64], y: &mut [C64]| num.solve_into(xv, y),
                        &p.excitation,
                        &mut u,
                        GMRES_REL * it.tolerance,
                        anorm,
                        GMRES_MAX,
                    );
                    let stats = per_freq!(stats.map_err(umf));
                    res.gmres_solves += stats.iterations;
                    // The amplitudes tested below (and the outputs) come from this solve.
                    gmres_ok = stats.converged;
                    for j in 0..m {
                        r[j] = row(j).iter().map(|&(i, w)| u[i] * w).sum();
                    }
                } else {
                    // I + GΔ; with coupled slip Δ has the 2 × 2 block of each point.
                    for jc in 0..m {
                        for k in 0..m {
                            work[k + m * jc] = rec.g[k + m * jc] * delta[jc];
                        }
                        if jc < nc * 2 {
                            let partner = jc ^ 1;
                            for k in 0..m {
                                work[k + m * jc] += rec.g[k + m * partner] * delta_off[jc / 2];
                            }
                        }
                        work[jc + m * jc] += C64::new(1.0, 0.0);
                    }
                    r.copy_from_slice(&rec.r0);
                    if !lu_solve_in_place(&mut work, m, &mut r) {
                        per_freq!(Err(SweepError::Condensed { freq: f }));
                    }
                }
                for j in 0..m {
                    a_star[j] = r[j].norm();
                }
                for (q, v) in rho_star.iter_mut().enumerate() {
                    *v = correlation(r[2 * q], r[2 * q + 1]);
                }
                let floor = ZERO_AMP_REL
                    * a.iter()
                        .chain(&a_star)
                        .fold(f64::MIN_POSITIVE, |x, &y| x.max(y));
                converged = consistent(&a, &a_star, floor, it.tolerance)
                    && rho_consistent(&a_star, &rho, &rho_star, it.tolerance);
                res.time("condensed iterations", t);
                if converged {
                    break;
                }
                (a, rho) = next_estimate(
                    (&a, &a_star),
                    (&rho, &rho_star),
                    floor,
                    &mut acc,
                    &mut bracket,
                );
                if a.iter().any(|v| !v.is_finite()) {
                    break;
                }
            }
            if converged || cold {
                break;
            }
            // Kept if the cold start does not converge either.
            first = Some((
                (a.clone(), a_star.clone(), rho.clone()),
                r.clone(),
                (delta.clone(), delta_off.clone()),
                (lin.clone(), lin2.clone()),
                ks.clone(),
                u.clone(),
                gmres_ok,
            ));
            cold = true;
            budget += it.max_passes;
            a.iter_mut().for_each(|v| *v = it.initial_amplitude);
            rho.iter_mut().for_each(|v| *v = 0.0);
            acc = Anderson::new(DEPTH);
            bracket = Bracket::new();
            lin_fresh = false;
        }
        if let (false, Some(f)) = (converged, first) {
            (
                (a, a_star, rho),
                r,
                (delta, delta_off),
                (lin, lin2),
                ks,
                u,
                gmres_ok,
            ) = f;
        }

        // (ΔBû)ⱼ: the diagonal, and with coupled slip the point's off-diagonal.
        let delta_r = |j: usize| {
            let off = if j < 2 * nc {
                delta_off[j / 2] * r[j ^ 1]
            } else {
                C64::new(0.0, 0.0)
            };
            delta[j] * r[j] + off
        };
        // Independent check of a converged frequency (posteriori.rs); the condensed path
        // forms x = S₀⁻¹(f̂ − Bᵀ Δ r) for it (one more solve).
        let mut check = None;
        if converged && gmres_ok {
            let t = Instant::now();
            if !krylov {
                x_rhs.copy_from_slice(&p.excitation);
                for j in 0..m {
                    let c = delta_r(j);
                    for &(i, w) in row(j) {
                        x_rhs[i] -= c * w;
                    }
                }
                if let Some(num) = &num {
                    per_freq!(num.solve_into(&x_rhs, &mut x_full).map_err(umf));
                } else if let Some(route) = modal.as_mut() {
                    per_freq!(route
                        .field(&x_rhs, &mut x_full)
                        .map_err(|source| SweepError::ModalField { freq: f, source }));
                }
            }
            let kappa: Vec<[C64; 2]> = (0..na)
                .map(|q| {
                    [
                        kappa_of(&lin[2 * q], omega),
                        kappa_of(&lin[2 * q + 1], omega),
                    ]
                })
                .collect();
            let amplitudes: Vec<[f64; 2]> = (0..na).map(|q| [a[2 * q], a[2 * q + 1]]).collect();
            let kappa_off: Vec<C64> = lin2.iter().map(|l| kappa_of_2(l, 0, 1, omega)).collect();
            let claim = Claim {
                kappa: &kappa,
                kappa_off: &kappa_off,
                correlation: &rho,
                amplitudes: &amplitudes,
                caps: &vec![f64::INFINITY; na],
                spring_k: &ks,
            };
            let scale = a.iter().chain(&a_star).fold(0.0f64, |x, &y| x.max(y));
            let x = if krylov { &u } else { &x_full };
            let v = posteriori::check(
                setup,
                omega,
                &claim,
                x,
                it.tolerance,
                super::ATOL_REL.min(it.tolerance) * scale,
            );
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
                res.fields.push((f, x.clone()));
            }
        }

        drop(num);
        // Outputs: ŷ = o₀ − O Δ r (condensed) or C u (Krylov).
        let outs: Vec<C64> = if krylov {
            p.outputs.iter().map(|o| o.value(&u)).collect()
        } else {
            (0..nout)
                .map(|k| {
                    rec.y0[k]
                        - (0..m)
                            .map(|j| rec.o[k + nout * j] * delta_r(j))
                            .sum::<C64>()
                })
                .collect()
        };
        res.outputs.push(outs);
        let mut power = 0.0;
        let t = Instant::now();
        let mut pts = Vec::new();
        if opts.point_results {
            pts = vec![PointFreq::default(); p.contacts.len()];
        }
        for q in 0..na {
            let e = if eff.contact_damping {
                (lin[2 * q].energy_per_cycle + lin[2 * q + 1].energy_per_cycle) * area[q]
            } else {
                0.0
            };
            power += e * f;
            if opts.point_results {
                let (l1, l2) = (&lin[2 * q], &lin[2 * q + 1]);
                pts[active[q]] = PointFreq {
                    amplitude: [a_star[2 * q], a_star[2 * q + 1]],
                    k_star: [l1.k_star, l2.k_star],
                    d_star: if eff.contact_damping {
                        [l1.d_star, l2.d_star]
                    } else {
                        [0.0; 2]
                    },
                    energy: e,
                    ratio: [l1.amplitude_ratio, l2.amplitude_ratio],
                    regime: [l1.regime, l2.regime],
                };
            }
        }
        if opts.point_results {
            res.points.push(pts);
            res.time("point outputs", t);
        }
        res.power.push(power);
        res.iterations.push(iterations);
        res.converged.push(converged && gmres_ok);
        res.singular.push(false);
        res.failed.push(None);
        res.checks.push(check);
        // The next frequency starts from this converged state (extrapolated).
        if converged && m > 0 {
            hist.push((f, a.clone()));
            if hist.len() > 2 {
                hist.remove(0);
            }
        } else {
            hist.clear();
        }
    }
    let nconv = res.converged.iter().filter(|&&c| c).count();
    res.passes.push(PassRecord {
        pass: 1,
        kind: "fast".into(),
        frequencies: freqs.to_vec(),
        converged: nconv,
    });
    Ok(res)
}
