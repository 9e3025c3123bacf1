//! Pseudo-arclength continuation in ω (Keller 1977; e.g. Seydel, *Practical Bifurcation
//! and Stability Analysis*, 2010, §4.4): on the curve R(u, ω) = 0 with y = (u, ω/ω_s),
//! the tangent t solves [R_u, ω_s R_ω; t_prevᵀ] t = (0, 1) (normalised, oriented along
//! the previous one); predictor y_p = y + s t; corrector Newton on
//! (R(y) = 0, tᵀ(y − y_p) = 0). Step s adapts to the corrector's iterations (halved on
//! failure, grown by 1.5 after fast ones).
//!
//! Turning points (folds): the ω component of the tangent changes sign together with
//! det R_u; a step after which ω turns back while det R_u keeps its sign, or whose
//! corrected point lies behind the previous one, jumped across the branch (the step
//! was long for the curvature) and is repeated at half the length. The branch ends where
//! it leaves the range between ω_start and ω_end (or reaches ω ≤ 0). The fold
//! frequency is the vertex of the parabola ω(s) through the three points around it.
//! Stability: det R_u changes sign at a fold (a real Floquet multiplier crosses +1), so a
//! point whose det sign differs from that of the start (a stable, far-from-resonance
//! point) is marked unstable. This detects fold instabilities only (no Neimark–Sacker or
//! period doubling, which need the Hill eigenvalues).

use nalgebra::{DMatrix, DVector};

use super::{Hb, MhbError, Solution};
use crate::linalg::{self, Lu};

/// Settings of a continuation run.
#[derive(Debug, Clone, Copy)]
pub struct Options {
    pub omega_start: f64,
    pub omega_end: f64,
    /// Initial arclength step (in the scaled variables).
    pub step: f64,
    pub step_min: f64,
    pub step_max: f64,
    pub max_points: usize,
    /// Corrector tolerance ‖R‖/‖f̂‖.
    pub rtol: f64,
}

/// A point on the branch.
#[derive(Debug, Clone)]
pub struct Point {
    pub sol: Solution,
    pub stable: bool,
    /// Arclength from the start (scaled variables).
    pub s: f64,
}

/// A traced branch and its folds.
#[derive(Debug, Clone)]
pub struct Branch {
    pub points: Vec<Point>,
    /// Fold frequencies in order of passage.
    pub folds: Vec<f64>,
    /// Corrector iterations in total.
    pub iterations: usize,
}

/// Traces the branch from the solution at `omega_start` (found from `u0` by Newton) to
/// `omega_end` (either direction).
pub fn trace(hb: &mut Hb, u0: &[f64], opt: Options) -> Result<Branch, MhbError> {
    let first = hb.solve(u0, opt.omega_start, super::NewtonOptions::default())?;
    let dim = hb.size();
    // Scales: ω by ω_start, u by the first solution's norm (so both are O(1)).
    let sc = Scaling {
        dim,
        us: DVector::from_column_slice(&first.u).norm().max(1e-300),
        ws: opt.omega_start.abs(),
    };
    let ws = sc.ws;
    let dir = (opt.omega_end - opt.omega_start).signum();
    let start_sign = first.det_sign;
    let mut y = sc.y(&first.u, first.omega);
    let mut t_prev = DVector::zeros(dim + 1);
    t_prev[dim] = dir;
    let mut pts = vec![Point {
        stable: true,
        s: 0.0,
        sol: first,
    }];
    let mut folds = Vec::new();
    let mut step = opt.step;
    let mut iterations = 0;
    let scale = hb.load().norm().max(f64::MIN_POSITIVE);
    let ev0 = hb.eval(&pts[0].sol.u, pts[0].sol.omega)?;
    let mut rhs = DVector::zeros(dim + 1);
    rhs[dim] = 1.0;
    let mut t = linalg::solve(&sc.augmented(&ev0, &t_prev), &rhs).ok_or(MhbError::Singular {
        omega: opt.omega_start,
    })?;
    t /= t.norm();
    let mut s_total = 0.0;
    while pts.len() < opt.max_points {
        let yp = &y + step * &t;
        let Some((its, ev, res, yc)) = correct(hb, &sc, &yp, &t, opt.rtol, scale)? else {
            step *= 0.5;
            if step < opt.step_min {
                return Err(MhbError::Continuation(format!(
                    "step below {:.1e} at ω = {:.6e}",
                    opt.step_min,
                    y[dim] * ws
                )));
            }
            continue;
        };
        // New tangent at the corrected point.
        let Some(mut tn) = linalg::solve(&sc.augmented(&ev, &t), &rhs) else {
            return Err(MhbError::Singular {
                omega: yc[dim] * ws,
            });
        };
        tn /= tn.norm();
        let det = Lu::factor(&ev.j).map_or(0.0, |lu| lu.determinant_sign());
        let last_det = pts[pts.len() - 1].sol.det_sign;
        // A step too long for the curvature jumps to another part of the branch: the
        // corrected point lies behind the predictor's direction, or ω turns back where
        // det R_u keeps its sign (no fold). Both are rejected and the step shortened.
        let backwards = t.dot(&(&yc - &y)) <= 0.0;
        let false_fold = tn[dim] * t[dim] < 0.0 && det == last_det;
        if backwards || false_fold {
            step *= 0.5;
            if step < opt.step_min {
                return Err(MhbError::Continuation(format!(
                    "step below {:.1e} at ω = {:.6e} (the branch turns back without a fold)",
                    opt.step_min,
                    y[dim] * ws
                )));
            }
            continue;
        }
        // Range guard: a branch that turns back past the start (or reaches ω ≤ 0) ends.
        let w = yc[dim] * ws;
        if (w - opt.omega_start) * dir < 0.0 || w <= 0.0 {
            break;
        }
        iterations += its;
        s_total += (&yc - &y).norm();
        let sol = Solution {
            omega: w,
            u: sc.u(&yc),
            iterations: its,
            residual: res,
            det_sign: det,
            dissipated: ev.dissipated,
        };
        if tn[dim] * t[dim] < 0.0 {
            folds.push(fold_vertex(
                pts.len().checked_sub(2).map(|i| &pts[i]),
                &pts[pts.len() - 1],
                (s_total, sol.omega),
            ));
        }
        pts.push(Point {
            stable: det == start_sign,
            s: s_total,
            sol,
        });
        y = yc;
        t = tn;
        if its <= 3 {
            step = (step * 1.5).min(opt.step_max);
        } else if its > 6 {
            step = (step * 0.7).max(opt.step_min);
        }
        let w = y[dim] * ws;
        if (w - opt.omega_end) * dir >= 0.0 {
            break;
        }
    }
    Ok(Branch {
        points: pts,
        folds,
        iterations,
    })
}

/// The continuation's scaled unknowns y = (u/us, ω/ws), both O(1).
struct Scaling {
    dim: usize,
    us: f64,
    ws: f64,
}

impl Scaling {
    fn y(&self, u: &[f64], w: f64) -> DVector<f64> {
        let mut y = DVector::zeros(self.dim + 1);
        for i in 0..self.dim {
            y[i] = u[i] / self.us;
        }
        y[self.dim] = w / self.ws;
        y
    }

    fn u(&self, y: &DVector<f64>) -> Vec<f64> {
        (0..self.dim).map(|i| y[i] * self.us).collect()
    }

    /// Augmented matrix [R_u·us, R_ω·ws; tᵀ].
    fn augmented(&self, ev: &super::Eval, t: &DVector<f64>) -> DMatrix<f64> {
        let dim = self.dim;
        let mut a = DMatrix::zeros(dim + 1, dim + 1);
        a.view_mut((0, 0), (dim, dim)).copy_from(&(&ev.j * self.us));
        a.view_mut((0, dim), (dim, 1))
            .copy_from(&(&ev.r_omega * self.ws));
        a.view_mut((dim, 0), (1, dim + 1)).copy_from(&t.transpose());
        a
    }
}

/// A converged corrector: its iterations, the evaluation there, ‖R‖/scale, the point.
type Corrected = (usize, super::Eval, f64, DVector<f64>);

/// The corrector: Newton on R(y) = 0 with tᵀ(y − yp) = 0 from the predictor `yp`, at
/// most 12 iterations; None where it does not converge (a singular matrix, a non-finite
/// step).
fn correct(
    hb: &mut Hb,
    sc: &Scaling,
    yp: &DVector<f64>,
    t: &DVector<f64>,
    rtol: f64,
    scale: f64,
) -> Result<Option<Corrected>, MhbError> {
    let dim = sc.dim;
    let mut yc = yp.clone();
    for it in 1..=12 {
        let ev = hb.eval(&sc.u(&yc), yc[dim] * sc.ws)?;
        let res = ev.r.norm() / scale;
        let mut g = DVector::zeros(dim + 1);
        g.rows_mut(0, dim).copy_from(&ev.r);
        g[dim] = t.dot(&(&yc - yp));
        if res <= rtol && g[dim].abs() <= 1e-12 {
            return Ok(Some((it, ev, res, yc)));
        }
        let Some(dy) = linalg::solve(&sc.augmented(&ev, t), &g) else {
            return Ok(None);
        };
        yc -= dy;
        if !yc.iter().all(|v| v.is_finite()) {
            return Ok(None);
        }
    }
    Ok(None)
}

/// Vertex of the parabola ω(s) through (a, b, c); falls back to b's ω.
fn fold_vertex(a: Option<&Point>, b: &Point, c: (f64, f64)) -> f64 {
    let Some(a) = a else { return b.sol.omega };
    let (s0, w0, s1, w1, s2, w2) = (a.s, a.sol.omega, b.s, b.sol.omega, c.0, c.1);
    // Divided differences.
    let d01 = (w1 - w0) / (s1 - s0);
    let d12 = (w2 - w1) / (s2 - s1);
    let d012 = (d12 - d01) / (s2 - s0);
    if d012 == 0.0 || !d012.is_finite() {
        return w1;
    }
    // ω(s) = w0 + d01 (s − s0) + d012 (s − s0)(s − s1); ω'(s) = 0.
    let sv = 0.5 * (s0 + s1) - d01 / (2.0 * d012);
    w0 + d01 * (sv - s0) + d012 * (sv - s0) * (sv - s1)
}
