//! Harmonic balance on FE scenes: the linear part condensed onto the
//! contact directions per harmonic, the contacts by AFT through the C API, Newton on the
//! condensed system.
//!
//! Per harmonic h = 0..H one factorization of
//!
//!   S_h = K + K_N + k_T0·BᵀAB − (hω)²M + i·hω·D
//!
//! (normal springs k_N of the static step, the stuck tangential springs k_T0 as the
//! reference; the sweep's one symbolic analysis) gives the receptances G_h = B S_h⁻¹ Bᵀ and
//! O_h = C S_h⁻¹ Bᵀ ([`Receptance`], m solves). With r the relative tangential
//! displacements of the m contact directions (two per closed point) as Fourier
//! coefficients ([`crate::mhb::aft`] layout, direction-major) and ĝ_j = A_j (F̂_j(r_j) − k_T0 r_j)
//! the contact force beyond the reference spring (F̂ the stress coefficients of the
//! library's point marched over r_j, A_j the tributary area), the balance is
//!
//!   R(r) = r − r₀ + Ĝ ĝ(r) = 0,     y = y₀ − Ô ĝ(r),
//!
//! Ĝ applying G_h to each harmonic's (cos, sin) pair as the complex amplitude a − ib, and
//! r₀, y₀ the stuck linear response to the first-harmonic load. h = 0 is the static
//! problem around the static step's preloaded state: the zeroth harmonic is the mean
//! deviation from it. By default (the thesis's model) the normal load of every point is
//! held at its static value and each tangential direction is its own point; with
//! `[effects] normal_load_variation` or `coupled_slip` a point's directions (its normal
//! one too with the former) are marched together by the library's three-direction point
//! ([`super::harmonic_fe_point3d`]). Newton's steps (I + Ĝ Γ) Δ = R, Γ = blockdiag
//! ∂ĝ_p/∂r_p over the points' groups of coupled directions, are solved by FGMRES
//! preconditioned with I + Ĝ Γ_d, Γ_d the harmonic-diagonal part of Γ (H + 1 dense LUs
//! of order m or 2m). Cost per frequency: (H + 1) × (one factorization + m solves) on
//! the mesh, everything else on the m(2H + 1) contact unknowns.

mod newton;

use std::time::Instant;

use super::harmonic_fe_point3d::{self as point3d, Point3};
use crate::capi::Tangential;
use crate::mhb::aft::{self, Law, Transforms};
use crate::mhb::MhbError;
use crate::solve::contact::tangential;
use crate::solve::sweep::modal_route::{ModalRoute, ModalRouteError, ModeChoice};
use crate::solve::sweep::receptance::Receptance;
use crate::solve::sweep::{Setup, C64};
use crate::solve::umfpack::UmfpackError;
use crate::util::rusage::cpu_seconds;

/// FGMRES restart length and most iterations per Newton step; the tolerance relative to
/// ‖R‖ (the step's own error is then far below the Newton tolerance).
const GMRES_RESTART: usize = 40;
const GMRES_MAX: usize = 400;
const GMRES_TOL: f64 = 1e-8;
/// Preconditioner blocks whose smallest LU pivot is below this fraction of the largest
/// are pseudo-inverted (singular values below this fraction of the largest dropped).
const PINV_RCOND: f64 = 1e-12;
/// Halvings in a row of a load step of [`FeBalance::solve_ramped`].
const RAMP_HALVINGS: usize = 6;

/// Counters and timings of a balance.
#[derive(Debug, Clone, Default)]
pub struct Stats {
    pub factorizations: usize,
    /// Solves with the factorizations (receptance columns and loads).
    pub solves: usize,
    pub newton_iterations: usize,
    pub gmres_iterations: usize,
    /// Seconds in factorizations and receptance solves (grows with the mesh), wall and
    /// CPU (the process's: the balance is single-threaded).
    pub receptance_seconds: f64,
    pub receptance_cpu: f64,
    /// Seconds in AFT (C-API marches) and the condensed Newton (grows with m·H), wall
    /// and CPU.
    pub contact_seconds: f64,
    pub contact_cpu: f64,
}

/// A converged periodic solution at one frequency.
#[derive(Debug, Clone)]
pub struct FeSolution {
    /// Relative tangential displacement coefficients, direction-major.
    pub r: Vec<f64>,
    /// Output coefficients `[output][h]` as complex amplitudes (h = 0: the mean, real).
    pub outputs: Vec<Vec<C64>>,
    /// Energy dissipated per cycle by each contact direction (force·length).
    pub dissipated: Vec<f64>,
    /// First-harmonic stress over displacement F̂₁/r̂₁ per direction (per area): the
    /// balance's own k* + iωd* (describing function); 0 for an unmoved direction.
    pub describing: Vec<C64>,
    pub iterations: usize,
    /// ‖R‖ / ‖r₀‖ at the end.
    pub residual: f64,
    /// ‖R‖ / ‖r₀‖ ≤ rtol reached within the iteration limit (else: the last iterate).
    pub converged: bool,
    /// ĝ(r): the contact forces beyond the reference spring, direction-major like r.
    pub ghat: Vec<f64>,
}

/// One unknown direction of the balance: a point (index into `Setup::active`) and its
/// local component (0 normal, 1 and 2 tangential).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dir {
    pub point: usize,
    pub comp: usize,
}

/// Directions marched together: `len` consecutive ones from `first`, by the
/// one-direction law (`point3` none, len 1) or the three-direction point.
#[derive(Debug, Clone, Copy)]
pub(super) struct Group {
    pub(super) first: usize,
    pub(super) len: usize,
    pub(super) point3: Option<Point3>,
    /// Offset of the group's Γ block ((len·(2H+1))² doubles) in `Forces::gamma`.
    gamma_at: usize,
}

/// Contact forces at one r.
struct Forces {
    /// ĝ, direction-major like r.
    ghat: Vec<f64>,
    /// Γ_g = ∂ĝ_g/∂r_g row-major per group (offsets `Group::gamma_at`); empty without
    /// Jacobian.
    gamma: Vec<f64>,
    dissipated: Vec<f64>,
    describing: Vec<C64>,
}

/// The harmonic balance of an FE problem (its closed, microslip-active points).
pub struct FeBalance<'s, 'a> {
    pub(super) setup: &'s mut Setup<'a>,
    pub tr: Transforms,
    pub(super) tang: Vec<Tangential>,
    pub(super) area: Vec<f64>,
    /// The unknown directions in the order of r.
    pub dirs: Vec<Dir>,
    pub(super) groups: Vec<Group>,
    rec: Vec<Receptance>,
    /// The modal route's basis ([`FeBalance::use_modal`]); `None`: a factorization per
    /// harmonic.
    pub(super) modal: Option<ModalRoute>,
    /// Factor on the first-harmonic load (1 but inside [`FeBalance::solve_ramped`]).
    load: f64,
    pub(super) omega: f64,
    pub stats: Stats,
}

impl<'s, 'a> FeBalance<'s, 'a> {
    /// H harmonics, N samples per period.
    pub fn new(setup: &'s mut Setup<'a>, h: usize, n: usize) -> Self {
        let p = setup.problem;
        let tang: Vec<Tangential> = setup
            .active
            .iter()
            .map(|&i| tangential(&p.interfaces[p.contacts[i].interface], setup.pressure[i]))
            .collect();
        let area: Vec<f64> = setup.active.iter().map(|&i| p.contacts[i].area).collect();
        let model = setup.point_model;
        let nc = 2 * h + 1;
        let (mut dirs, mut groups) = (Vec::new(), Vec::new());
        let mut gamma_at = 0;
        for (q, &i) in setup.active.iter().enumerate() {
            let t: &Tangential = &tang[q];
            let comps: &[usize] = if model.is_thesis() {
                &[1, 2]
            } else {
                model.components()
            };
            let point3 = (!model.is_thesis()).then(|| {
                let k_n =
                    crate::solve::contact::normal_stiffness(&p.interfaces[p.contacts[i].interface]);
                Point3::new(t, k_n, setup.normal_k[i], area[q], model)
            });
            // The three-direction point couples its directions; the thesis's points are
            // one direction each.
            let sizes: Vec<usize> = if point3.is_some() {
                vec![comps.len()]
            } else {
                vec![1; comps.len()]
            };
            let mut first = dirs.len();
            for len in sizes {
                groups.push(Group {
                    first,
                    len,
                    point3,
                    gamma_at,
                });
                first += len;
                gamma_at += (len * nc).pow(2);
            }
            dirs.extend(comps.iter().map(|&comp| Dir { point: q, comp }));
        }
        let m = dirs.len();
        let nf = p.sys.dofs.n_free();
        FeBalance {
            tr: Transforms::new(n, h),
            tang,
            area,
            dirs,
            groups,
            rec: (0..=h)
                .map(|_| Receptance::new(nf, m, p.outputs.len()))
                .collect(),
            load: 1.0,
            omega: 0.0,
            stats: Stats::default(),
            modal: None,
            setup,
        }
    }

    /// The stuck reference k_T0 per active point (both tangential directions).
    pub(super) fn reference(&self) -> Vec<[C64; 2]> {
        self.tang
            .iter()
            .map(|t| [C64::new(t.k_t0, 0.0); 2])
            .collect()
    }

    /// Condenses through the stuck structure's modes ([`ModalRoute`]) instead of a
    /// factorization per harmonic: G_h, O_h at h·ω from one basis for the whole sweep.
    pub fn use_modal(&mut self, modes: ModeChoice, residual: bool) -> Result<(), ModalRouteError> {
        let kref = self.reference();
        let rows = self.rows();
        let row = |j: usize| rows[j];
        let route = ModalRoute::new(self.setup, &kref, &[], (rows.len(), &row), modes, residual)?;
        self.modal = Some(route);
        Ok(())
    }

    /// Contact directions m.
    pub fn m(&self) -> usize {
        self.dirs.len()
    }

    /// Sparse rows of the directions' relative displacements on the free DOFs.
    pub(super) fn rows(&self) -> Vec<&'a [(usize, f64)]> {
        let p: &'a crate::model::Problem = self.setup.problem;
        self.dirs
            .iter()
            .map(|d| p.contacts[self.setup.active[d.point]].rows[d.comp].as_slice())
            .collect()
    }

    /// Doubles of Γ over all groups.
    fn gamma_len(&self) -> usize {
        let nc = self.tr.ncoef();
        self.groups
            .last()
            .map_or(0, |g| g.gamma_at + (g.len * nc).pow(2))
    }

    /// Unknowns m(2H + 1).
    pub fn size(&self) -> usize {
        self.m() * self.tr.ncoef()
    }

    /// The per-harmonic factorizations and receptances at ω (rad/time). `Ok(false)` when
    /// a harmonic's dynamic stiffness (stuck joint) is singular ([`Setup::factor_regular`],
    /// as in the other modes): no balance at this ω.
    pub fn condense(&mut self, omega: f64) -> Result<bool, UmfpackError> {
        let (t, cpu) = (Instant::now(), cpu_seconds());
        self.omega = omega;
        let p = self.setup.problem;
        let rows = self.rows();
        let row = |j: usize| rows[j];
        let kref = self.reference();
        if let Some(route) = self.modal.as_mut() {
            let mut regular = true;
            for (h, rec) in self.rec.iter_mut().enumerate() {
                regular &= route.receptance(h as f64 * omega, rec);
            }
            self.stats.receptance_seconds += t.elapsed().as_secs_f64();
            self.stats.receptance_cpu += cpu_seconds() - cpu;
            return Ok(regular);
        }
        for (h, rec) in self.rec.iter_mut().enumerate() {
            // No cubic springs here: sweep::run refuses them in this mode.
            self.setup.fill(h as f64 * omega, &kref, &[]);
            self.stats.factorizations += 1;
            let num = match self.setup.factor_regular()? {
                Some(num) => num,
                None => {
                    self.stats.receptance_seconds += t.elapsed().as_secs_f64();
                    self.stats.receptance_cpu += cpu_seconds() - cpu;
                    return Ok(false);
                }
            };
            if h == 1 {
                rec.load(&num, &p.excitation, &row, &p.outputs)?;
                self.stats.solves += 1;
            }
            rec.condense(&num, &row, &p.outputs)?;
            self.stats.solves += rec.m;
        }
        self.stats.receptance_seconds += t.elapsed().as_secs_f64();
        self.stats.receptance_cpu += cpu_seconds() - cpu;
        Ok(true)
    }

    /// r₀: the stuck linear response (first harmonic only), the cold start.
    pub fn linear_start(&self) -> Vec<f64> {
        let nc = self.tr.ncoef();
        let mut r = vec![0.0; self.size()];
        for (j, z) in self.rec[1].r0.iter().enumerate() {
            r[j * nc + 1] = z.re;
            r[j * nc + 2] = -z.im;
        }
        r
    }

    /// out = Ĝ v (module docs).
    fn apply_g(&self, v: &[f64], out: &mut [f64]) {
        let (m, nc) = (self.m(), self.tr.ncoef());
        for (h, rec) in self.rec.iter().enumerate() {
            for k in 0..m {
                if h == 0 {
                    out[k * nc] = (0..m).map(|j| rec.g[k + m * j].re * v[j * nc]).sum();
                } else {
                    let (ca, sa) = (2 * h - 1, 2 * h);
                    let y: C64 = (0..m)
                        .map(|j| rec.g[k + m * j] * C64::new(v[j * nc + ca], -v[j * nc + sa]))
                        .sum();
                    out[k * nc + ca] = y.re;
                    out[k * nc + sa] = -y.im;
                }
            }
        }
    }

    /// ĝ (and Γ when `jac`) at r by AFT through the C API.
    fn forces(&mut self, r: &[f64], jac: bool) -> Result<Forces, MhbError> {
        let (m, nc) = (self.m(), self.tr.ncoef());
        let mut f = Forces {
            ghat: vec![0.0; m * nc],
            gamma: if jac {
                vec![0.0; self.gamma_len()]
            } else {
                Vec::new()
            },
            dissipated: vec![0.0; m],
            describing: vec![C64::new(0.0, 0.0); m],
        };
        for gi in 0..self.groups.len() {
            let g = self.groups[gi];
            let span = g.first * nc..(g.first + g.len) * nc;
            let dc = &r[span.clone()];
            if let Some(p3) = &g.point3 {
                let pf = point3d::forces(&mut self.tr, p3, dc, jac)?;
                f.ghat[span].copy_from_slice(&pf.ghat);
                if jac {
                    f.gamma[g.gamma_at..g.gamma_at + pf.gamma.len()].copy_from_slice(&pf.gamma);
                }
                // The point's energy on its first direction (points sum their directions).
                f.dissipated[g.first] = pf.dissipated;
                f.describing[g.first..g.first + g.len].copy_from_slice(&pf.describing);
                continue;
            }
            let j = g.first;
            let t = self.tang[self.dirs[j].point];
            let (a, k0) = (self.area[self.dirs[j].point], t.k_t0);
            let law = Law::Point(t);
            let (force, period) = if jac {
                let ev = aft::evaluate(&mut self.tr, &law, dc)?;
                let gam = &mut f.gamma[g.gamma_at..g.gamma_at + nc * nc];
                for (g, &e) in gam.iter_mut().zip(&ev.jac) {
                    *g = a * e;
                }
                for c in 0..nc {
                    gam[c * nc + c] -= a * k0;
                }
                (ev.force, ev.period)
            } else {
                aft::forces(&mut self.tr, &law, dc)?
            };
            for c in 0..nc {
                f.ghat[j * nc + c] = a * (force[c] - k0 * dc[c]);
            }
            f.dissipated[j] = a * period.dissipated;
            let d1 = C64::new(dc[1], -dc[2]);
            if d1.norm() > 0.0 {
                f.describing[j] = C64::new(force[1], -force[2]) / d1;
            }
        }
        Ok(f)
    }

    /// Γ entry between coefficient `a` of direction `k` and coefficient `b` of
    /// direction `j` (zero unless both are in one group).
    fn gamma_at(
        &self,
        gamma: &[f64],
        group_of: &[usize],
        k: usize,
        a: usize,
        j: usize,
        b: usize,
    ) -> f64 {
        let g = &self.groups[group_of[j]];
        if group_of[k] != group_of[j] {
            return 0.0;
        }
        let nc = self.tr.ncoef();
        let len = g.len * nc;
        gamma[g.gamma_at + ((k - g.first) * nc + a) * len + (j - g.first) * nc + b]
    }

    /// The group of each direction.
    fn group_of(&self) -> Vec<usize> {
        let mut out = vec![0; self.m()];
        for (gi, g) in self.groups.iter().enumerate() {
            out[g.first..g.first + g.len].fill(gi);
        }
        out
    }

    /// y = Γ x, group by group.
    fn apply_gamma(&self, gamma: &[f64], x: &[f64], y: &mut [f64]) {
        let nc = self.tr.ncoef();
        for g in &self.groups {
            let len = g.len * nc;
            let blk = &gamma[g.gamma_at..g.gamma_at + len * len];
            let off = g.first * nc;
            for a in 0..len {
                y[off + a] = (0..len).map(|b| blk[a * len + b] * x[off + b]).sum();
            }
        }
    }

    /// R = r − r₀ + Ĝ ĝ.
    fn residual(&self, r: &[f64], ghat: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; r.len()];
        self.apply_g(ghat, &mut out);
        let lin: Vec<f64> = self.linear_start().iter().map(|v| v * self.load).collect();
        for ((o, x), l) in out.iter_mut().zip(r).zip(&lin) {
            *o += x - l;
        }
        out
    }

    /// y = y₀ − Ô ĝ per output and harmonic.
    fn outputs(&self, ghat: &[f64]) -> Vec<Vec<C64>> {
        let (m, nc) = (self.m(), self.tr.ncoef());
        let nout = self.setup.problem.outputs.len();
        (0..nout)
            .map(|k| {
                self.rec
                    .iter()
                    .enumerate()
                    .map(|(h, rec)| {
                        let y0 = if h == 1 {
                            rec.y0[k] * self.load
                        } else {
                            C64::new(0.0, 0.0)
                        };
                        let gj = |j: usize| {
                            if h == 0 {
                                C64::new(ghat[j * nc], 0.0)
                            } else {
                                C64::new(ghat[j * nc + 2 * h - 1], -ghat[j * nc + 2 * h])
                            }
                        };
                        let y = y0 - (0..m).map(|j| rec.o[k + nout * j] * gj(j)).sum::<C64>();
                        if h == 0 {
                            C64::new(y.re, 0.0)
                        } else {
                            y
                        }
                    })
                    .collect()
            })
            .collect()
    }
}
