//! Harmonic balance of lumped systems with three-direction contact points
//! (docs/contact3d.md): a unilateral normal law, so the normal force N(t) varies within
//! the cycle and the point may separate, and two tangential directions under one
//! circular slip limit ‖t‖ ≤ μN(t). The AFT ([`super::aft`]'s transforms) marches the
//! library's point (`jointlin_point3d_step`) over the periodic samples of the two
//! tangential displacements and the overclosure together until the loop closes; the
//! Jacobian of the element's force coefficients is a forward difference of that whole
//! map (the coupled, path-dependent law has no exact incremental rule here).
//!
//! Kinematics of element e on DOFs (t₁, t₂, n) of one body against a rigid plane: u₁ =
//! x_{t₁}, u₂ = x_{t₂}, overclosure h = g₀ − x_n (n points from the plane into the body,
//! g₀ the overclosure at x = 0). Internal forces on the body: +F₁, +F₂ on t₁, t₂ (the
//! point returns them with the sign of the displacement) and −N on n.

use nalgebra::{DMatrix, DVector};

use super::aft::{AftError, Transforms, CLOSE_TOL, MAX_PERIODS};
use super::aitken::Aitken;
use super::{linear_coefficients, Hb, MhbError, NewtonOptions, System};
use crate::capi::{self, Contact3, POINT3D_STATE_LEN};

/// One three-direction point between a body's DOFs and the ground plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element3 {
    /// DOF indices (t₁, t₂, n).
    pub dofs: [usize; 3],
    pub contact: Contact3,
    /// Overclosure g₀ at x = 0 (length).
    pub gap: f64,
}

/// A lumped system (M, D, K, loads as [`System`], which holds them; its 1D elements are
/// not used here) with three-direction points.
#[derive(Debug, Clone)]
pub struct System3 {
    pub linear: System,
    pub elements: Vec<Element3>,
}

/// One closed period of a point: forces (t₁, t₂, N) per sample, the energy dissipated
/// over the period, the periods marched and the point's state at the period's end.
#[derive(Debug, Clone)]
pub struct Period3 {
    pub force: [Vec<f64>; 3],
    pub dissipated: f64,
    pub periods: usize,
    /// State at the period's end: where the march of a nearby path may start
    /// ([`march3_from`]).
    pub state: [f64; POINT3D_STATE_LEN],
}

/// Marches `c` over the periodic samples `disp` = (u₁, u₂, h) from a virgin state until
/// two consecutive periods' forces agree to [`CLOSE_TOL`] of the force scale. A cell that
/// slips on a short arc of a path that is not a circle forgets its sideways position
/// slowly (geometrically, docs/contact3d.md §4), each cell at a rate of its own: the
/// sliders' positions (state slots 5 …, the header's layout) are extrapolated slot by
/// slot (Aitken's Δ², [`Aitken::per_slot`]).
pub fn march3(c: &Contact3, disp: &[[f64; 3]]) -> Result<Period3, AftError> {
    march3_from(c, disp, &[0.0; POINT3D_STATE_LEN])
}

/// [`march3`] from the state `start` instead of a virgin point. The forward-difference
/// columns of a Jacobian start from their base path's closed state ([`Period3::state`]):
/// a path 1e-7 away closes within a few periods there, where from a virgin point it
/// repeats the whole transient (the per-point cost of the coupled balance's Jacobian).
pub fn march3_from(
    c: &Contact3,
    disp: &[[f64; 3]],
    start: &[f64; POINT3D_STATE_LEN],
) -> Result<Period3, AftError> {
    let aitken = Aitken::per_slot(SLIDER_SLOTS..POINT3D_STATE_LEN);
    march_with(c, disp, start, aitken)
}

/// [`march3_from`] with the given extrapolation.
fn march_with(
    c: &Contact3,
    disp: &[[f64; 3]],
    start: &[f64; POINT3D_STATE_LEN],
    mut aitken: Aitken,
) -> Result<Period3, AftError> {
    let n = disp.len();
    let mut state = *start;
    let mut next = [0.0; POINT3D_STATE_LEN];
    let mut cur = Period3 {
        force: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
        dissipated: 0.0,
        periods: 0,
        state: *start,
    };
    let mut prev = cur.force.clone();
    for p in 1..=MAX_PERIODS {
        let mut diss = 0.0;
        for (k, d) in disp.iter().enumerate() {
            let s = capi::point3d_step(c, &state, *d, &mut next)?;
            state = next;
            for a in 0..3 {
                cur.force[a][k] = s.force[a];
            }
            diss += s.dissipated;
        }
        cur.dissipated = diss;
        cur.periods = p;
        let mut scale = f64::MIN_POSITIVE;
        let mut diff = 0.0f64;
        for a in 0..3 {
            for k in 0..n {
                scale = scale.max(cur.force[a][k].abs());
                diff = diff.max((cur.force[a][k] - prev[a][k]).abs());
            }
        }
        prev.clone_from(&cur.force);
        if aitken.starting() {
            aitken.first(&state);
            continue;
        }
        if diff <= CLOSE_TOL * scale {
            cur.state = state;
            return Ok(cur);
        }
        if let Some(x) = aitken.after(&state, diff) {
            match <[f64; POINT3D_STATE_LEN]>::try_from(x.as_slice()) {
                Ok(x) if capi::point3d_step(c, &x, disp[0], &mut next).is_ok() => state = x,
                _ => aitken.rejected(&state),
            }
        }
    }
    Err(AftError::NotClosed {
        periods: MAX_PERIODS,
    })
}

/// First slot of the sliders' positions in a three-direction point's state (the
/// header's layout: cell count, u₁, u₂, h, energy, then two slots per cell).
const SLIDER_SLOTS: usize = 5;

/// Residual, Jacobian and each point's energy dissipated per period at one state.
pub type Evaluated3 = (DVector<f64>, DMatrix<f64>, Vec<f64>);

/// The harmonic balance of a [`System3`] at H harmonics and N samples.
pub struct Hb3<'a> {
    sys: &'a System3,
    linear: Hb<'a>,
    tr: Transforms,
}

/// A converged periodic solution: coefficients DOF-major (layout of [`super::aft`]) and
/// the energy dissipated per period by each point (force·length).
#[derive(Debug, Clone)]
pub struct Solution3 {
    pub omega: f64,
    pub u: Vec<f64>,
    pub dissipated: Vec<f64>,
    pub iterations: usize,
    pub residual: f64,
}

impl<'a> Hb3<'a> {
    pub fn new(sys: &'a System3, h: usize, n: usize) -> Self {
        Hb3 {
            sys,
            linear: Hb::new(&sys.linear, h, n),
            tr: Transforms::new(n, h),
        }
    }

    fn m(&self) -> usize {
        self.tr.ncoef()
    }

    /// The element's relative coefficients (u₁, u₂, h) from the system's u.
    fn element_coefficients(&self, e: &Element3, u: &[f64]) -> Vec<f64> {
        let m = self.m();
        let mut c = vec![0.0; 3 * m];
        for q in 0..m {
            c[q] = u[e.dofs[0] * m + q];
            c[m + q] = u[e.dofs[1] * m + q];
            c[2 * m + q] = -u[e.dofs[2] * m + q];
        }
        c[2 * m] += e.gap;
        c
    }

    /// Force coefficients (F₁, F₂, N; 3(2H+1)) and the closed period at relative
    /// coefficients `c`, marched from `start`.
    fn element_forces(
        &mut self,
        e: &Element3,
        c: &[f64],
        start: &[f64; POINT3D_STATE_LEN],
    ) -> Result<(Vec<f64>, Period3), AftError> {
        let (n, m) = (self.tr.n, self.m());
        let mut samples = vec![[0.0; 3]; n];
        let mut x = vec![0.0; n];
        for a in 0..3 {
            self.tr.synthesize(&c[a * m..(a + 1) * m], &mut x);
            for k in 0..n {
                samples[k][a] = x[k];
            }
        }
        let period = march3_from(&e.contact, &samples, start)?;
        let mut f = vec![0.0; 3 * m];
        for a in 0..3 {
            self.tr
                .analyse(&period.force[a], &mut f[a * m..(a + 1) * m]);
        }
        Ok((f, period))
    }

    /// Residual and Jacobian at (u, ω), with each point's dissipated energy per period.
    pub fn eval(&mut self, u: &[f64], omega: f64) -> Result<Evaluated3, MhbError> {
        let ev = self.linear.eval(u, omega)?;
        let (mut r, mut j) = (ev.r, ev.j);
        let m = self.m();
        let mut dissipated = Vec::with_capacity(self.sys.elements.len());
        // Sign of each relative coefficient block in x (u₁, u₂: +; h: −) and of each force
        // block in the internal force (F₁, F₂: +; N: −).
        const SIGN: [f64; 3] = [1.0, 1.0, -1.0];
        for e in &self.sys.elements {
            let c = self.element_coefficients(e, u);
            let (f, period) = self.element_forces(e, &c, &[0.0; POINT3D_STATE_LEN])?;
            dissipated.push(period.dissipated);
            for a in 0..3 {
                for q in 0..m {
                    r[e.dofs[a] * m + q] += SIGN[a] * f[a * m + q];
                }
            }
            // Forward differences of the element map: step 1e-7 of the larger of max|c|
            // and the stick displacement μN/k_T0 at the mean normal force.
            let n0 = (e.contact.k_n * c[2 * m]).max(0.0);
            let scale = c
                .iter()
                .fold(e.contact.mu * n0 / e.contact.k_t0, |s, v| s.max(v.abs()));
            let eps = 1e-7 * scale.max(f64::MIN_POSITIVE);
            let mut cp = c.clone();
            for b in 0..3 {
                for qb in 0..m {
                    let col = b * m + qb;
                    cp[col] = c[col] + eps;
                    let (fp, _) = self.element_forces(e, &cp, &period.state)?;
                    cp[col] = c[col];
                    for a in 0..3 {
                        for qa in 0..m {
                            let d = (fp[a * m + qa] - f[a * m + qa]) / eps;
                            j[(e.dofs[a] * m + qa, e.dofs[b] * m + qb)] += SIGN[a] * SIGN[b] * d;
                        }
                    }
                }
            }
        }
        Ok((r, j, dissipated))
    }

    /// Newton from `u0` at fixed ω with step halving (as [`Hb::solve`]).
    pub fn solve(
        &mut self,
        u0: &[f64],
        omega: f64,
        opt: NewtonOptions,
    ) -> Result<Solution3, MhbError> {
        let scale = self.linear.load().norm().max(f64::MIN_POSITIVE);
        let mut u = DVector::from_column_slice(u0);
        let (mut r, mut j, mut diss) = self.eval(u.as_slice(), omega)?;
        let mut res = r.norm() / scale;
        for it in 0..=opt.max_iter {
            if res <= opt.rtol {
                return Ok(Solution3 {
                    omega,
                    u: u.as_slice().to_vec(),
                    dissipated: diss,
                    iterations: it,
                    residual: res,
                });
            }
            if it == opt.max_iter {
                break;
            }
            let du = j
                .clone()
                .lu()
                .solve(&r)
                .ok_or(MhbError::Singular { omega })?;
            let mut lambda = 1.0;
            loop {
                let trial = &u - lambda * &du;
                let (r2, j2, d2) = self.eval(trial.as_slice(), omega)?;
                let res2 = r2.norm() / scale;
                if res2 < res || lambda < 1e-2 {
                    (u, r, j, diss, res) = (trial, r2, j2, d2, res2);
                    break;
                }
                lambda *= 0.5;
            }
        }
        Err(MhbError::Newton {
            omega,
            residual: res,
            iterations: opt.max_iter,
        })
    }

    /// The linear response with every point stuck and closed (k_T0 on t₁, t₂ and k_N on
    /// n, the normal spring preloaded by k_N·g₀): the start of a solve.
    pub fn stuck_start(&self, omega: f64) -> Vec<f64> {
        let s = &self.sys.linear;
        let m = self.m();
        let mut k = s.k.clone();
        let mut f0 = DVector::from_column_slice(&s.f0);
        for e in &self.sys.elements {
            let [t1, t2, nn] = e.dofs;
            k[(t1, t1)] += e.contact.k_t0;
            k[(t2, t2)] += e.contact.k_t0;
            k[(nn, nn)] += e.contact.k_n;
            f0[nn] += e.contact.k_n * e.gap;
        }
        linear_coefficients(s, &k, &f0, omega, m)
    }

    /// First-harmonic amplitude of DOF `dof` in `u`.
    pub fn amplitude(&self, u: &[f64], dof: usize) -> f64 {
        self.linear.amplitude(u, dof)
    }
}

/// Load-step halvings before [`solve_ramped`] gives up.
const MAX_RAMP_HALVINGS: usize = 12;

/// Solves `sys` at ω with its harmonic load ramped from 0: `steps` equal steps, each
/// solve starting from the last converged one (the first from the stuck start), a step
/// whose Newton fails halved (at most [`MAX_RAMP_HALVINGS`] times in a row): the way
/// through separation or sliding, where Newton from the stuck start at the full load may
/// not converge.
pub fn solve_ramped(
    sys: &System3,
    h: usize,
    n: usize,
    omega: f64,
    steps: usize,
    opt: NewtonOptions,
) -> Result<Solution3, MhbError> {
    let full = 1.0 / steps.max(1) as f64;
    let (mut at, mut step, mut halvings) = (0.0f64, full, 0);
    let mut last: Option<Solution3> = None;
    loop {
        let w = (at + step).min(1.0);
        let mut part = sys.clone();
        part.linear.f1.iter_mut().for_each(|f| *f *= w);
        let mut hb = Hb3::new(&part, h, n);
        let start = match &last {
            Some(s) => s.u.clone(),
            None => hb.stuck_start(omega),
        };
        match hb.solve(&start, omega, opt) {
            Ok(sol) => {
                if w >= 1.0 {
                    return Ok(sol);
                }
                (at, halvings) = (w, 0);
                step = (2.0 * step).min(full);
                last = Some(sol);
            }
            Err(e) if halvings >= MAX_RAMP_HALVINGS => return Err(e),
            Err(_) => {
                halvings += 1;
                step *= 0.5;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::LawName;

    /// Plain marching (no extrapolation) of `periods` periods: the forces of the last.
    fn plain(c: &Contact3, disp: &[[f64; 3]], periods: usize) -> [Vec<f64>; 3] {
        let n = disp.len();
        let mut state = [0.0; POINT3D_STATE_LEN];
        let mut next = [0.0; POINT3D_STATE_LEN];
        let mut f = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        for _ in 0..periods {
            for (k, d) in disp.iter().enumerate() {
                let s = capi::point3d_step(c, &state, *d, &mut next).unwrap();
                state = next;
                (0..3).for_each(|a| f[a][k] = s.force[a]);
            }
        }
        f
    }

    /// `n` samples of the ellipse (a cos ωt, b sin ωt) at overclosure 1.
    fn ellipse(a: f64, b: f64, n: usize) -> Vec<[f64; 3]> {
        (0..n)
            .map(|k| {
                let t = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                [a * t.cos(), b * t.sin(), 1.0]
            })
            .collect()
    }

    /// Largest difference of two periods' forces.
    fn largest_difference(f: &[Vec<f64>; 3], g: &[Vec<f64>; 3]) -> f64 {
        (0..3)
            .flat_map(|i| f[i].iter().zip(&g[i]).map(|(x, y)| (x - y).abs()))
            .fold(0.0f64, f64::max)
    }

    #[test]
    fn a_slowly_closing_coupled_loop_is_extrapolated_to_the_same_loop() {
        // Jenkins (x = μN/k_T0 = 1) on ellipses just beyond the stick circle: the slider
        // forgets its sideways position slowly. Plain marching needs 313 periods for
        // A = (1.01, 0.05) (more than MAX_PERIODS) and 160 for (1.02, 0.5); the
        // extrapolated march closes in 5 and 8 and lands on the loop that 3000 plain
        // periods reach.
        let c = Contact3 {
            law: LawName::Jenkins,
            cells: 0,
            mu: 1.0,
            k_t0: 1.0,
            k_n: 1.0,
        };
        let n = 256;
        for (a, b) in [(1.01, 0.05), (1.02, 0.5)] {
            let disp = ellipse(a, b, n);
            let fast = march3(&c, &disp).unwrap();
            let slow = plain(&c, &disp, 3000);
            let diff = largest_difference(&fast.force, &slow);
            eprintln!(
                "A = ({a}, {b}): closed in {} periods, {diff:.1e} μN from 3000 plain periods",
                fast.periods
            );
            assert!(
                fast.periods <= 20 && diff < 1e-9,
                "{} {diff:e}",
                fast.periods
            );
        }
    }
    #[test]
    fn a_mindlin_point_whose_cells_forget_at_their_own_rates_is_extrapolated_per_cell() {
        // Mindlin cells (δ* = 1.5 μN/k_T0 = 1.5) on nearly straight ellipses near δ*:
        // each cell that slips on a short arc forgets its sideways position at a rate set
        // by its own limit, so one ratio for all cells (that of the force differences)
        // jumps them poorly (17 and 53 periods); each slider's own ratio closes the loop
        // in 8 and 6, on the loop 3000 plain periods reach. (On the knife's
        // coupled-slip harmonic balance, H = 3, one ratio left loops unclosed after 200
        // periods.)
        let c = Contact3 {
            law: LawName::Mindlin,
            cells: 0,
            mu: 1.0,
            k_t0: 1.0,
            k_n: 1.0,
        };
        let n = 256;
        for (a, b) in [(1.0, 0.02), (1.6, 0.01)] {
            let disp = ellipse(a, b, n);
            let fast = march3(&c, &disp).unwrap();
            let virgin = [0.0; POINT3D_STATE_LEN];
            let one_ratio = march_with(
                &c,
                &disp,
                &virgin,
                Aitken::new(SLIDER_SLOTS..POINT3D_STATE_LEN),
            )
            .map_or(MAX_PERIODS, |p| p.periods);
            let slow = plain(&c, &disp, 3000);
            let diff = largest_difference(&fast.force, &slow);
            eprintln!(
                "A = ({a}, {b}): closed in {} periods ({one_ratio} with one ratio), {diff:.1e} μN from 3000 plain periods",
                fast.periods
            );
            assert!(
                fast.periods <= 10 && 2 * fast.periods <= one_ratio && diff < 1e-9,
                "{} {one_ratio} {diff:e}",
                fast.periods
            );
        }
    }

    #[test]
    fn a_nearby_path_marched_from_the_closed_state_gives_the_same_difference_quotient() {
        // A Jacobian column: the path moved by ε = 1e-7 (relative) in one coefficient,
        // marched from the base path's closed state instead of a virgin point, gives the
        // same difference quotient (to 1e-3 of its largest entry: both closed to
        // CLOSE_TOL, divided by ε) in no more periods: 5 instead of 8 for a Jenkins and a
        // Mindlin point on slowly closing ellipses; 3 as from virgin for a Mindlin point
        // whose normal load varies and lifts off for part of the cycle (h = 1 + 1.2 cos ωt:
        // the lift-off clears its memory every period).
        let point = |law| Contact3 {
            law,
            cells: 0,
            mu: 1.0,
            k_t0: 1.0,
            k_n: 1.0,
        };
        let n = 256;
        let lift = |mut d: Vec<[f64; 3]>| {
            for (k, x) in d.iter_mut().enumerate() {
                x[2] = 1.0 + 1.2 * (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos();
            }
            d
        };
        let cases = [
            (point(LawName::Jenkins), ellipse(1.02, 0.5, n)),
            (point(LawName::Mindlin), ellipse(1.0, 0.02, n)),
            (point(LawName::Mindlin), lift(ellipse(0.8, 0.6, n))),
        ];
        let (mut warm_periods, mut cold_periods) = (0, 0);
        for (c, disp) in cases {
            let base = march3(&c, &disp).unwrap();
            let eps = 1e-7;
            let near: Vec<[f64; 3]> = disp
                .iter()
                .map(|d| [d[0] * (1.0 + eps), d[1], d[2]])
                .collect();
            let warm = march3_from(&c, &near, &base.state).unwrap();
            let cold = march3(&c, &near).unwrap();
            let quotient = |f: &[Vec<f64>; 3]| -> [Vec<f64>; 3] {
                std::array::from_fn(|a| {
                    f[a].iter()
                        .zip(&base.force[a])
                        .map(|(x, y)| (x - y) / eps)
                        .collect()
                })
            };
            let (qw, qc) = (quotient(&warm.force), quotient(&cold.force));
            let largest = largest_difference(&qc, &std::array::from_fn(|_| vec![0.0; n]));
            let diff = largest_difference(&qw, &qc);
            eprintln!(
                "{:?}: {} periods from the closed state, {} from virgin; quotients differ by {:.1e} of {largest:.2}",
                c.law, warm.periods, cold.periods, diff / largest
            );
            assert!(
                largest > 0.1 && diff <= 1e-3 * largest && warm.periods <= cold.periods,
                "{} {} {diff:e} {largest:e}",
                warm.periods,
                cold.periods
            );
            warm_periods += warm.periods;
            cold_periods += cold.periods;
        }
        assert!(warm_periods < cold_periods);
    }
}
