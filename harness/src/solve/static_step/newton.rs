//! Newton's method on the preload's equation K u + α f_c(u) = f_pre: the Newton matrix
//! (K plus the points' tangents and the sampled points' couplings, factored by UMFPACK)
//! and the iteration with its line search and its two stopping rules (the residual
//! against the load, or against its own round-off floor).

use nalgebra::Matrix3;

use super::{dot, evaluate, norm, Eval, StaticError, BACKWARD_TOL, FLOOR_CEILING, OPEN_STAND_IN};
use crate::capi::CapiError;
use crate::fe::csc::Csc;
use crate::fe::pair_blocks::to_global;
use crate::model::Problem;
use crate::solve::line_search;
use crate::solve::umfpack::{Symbolic, UmfpackError};

/// The Newton matrix K + Σ tangents + sampled couplings, factored and solved.
pub(super) struct NewtonMatrix<'a> {
    pub(super) p: &'a Problem,
    pub(super) sym: Symbolic<f64>,
}

impl NewtonMatrix<'_> {
    /// K + Σ tangents + the sampled couplings.
    fn assemble(&self, tangents: &[Matrix3<f64>], couplings: &[(usize, usize, f64)]) -> Csc<f64> {
        let p = self.p;
        let mut kt = p.sys.k.clone();
        for (c, t) in p.contacts.iter().zip(tangents) {
            let g = to_global(&c.frame, t);
            p.sys.pairs.add(&mut kt.values, c.pair, &g);
        }
        // Bₖ,ₙᵀ C Bⱼ,ₙ of the sampled points (the pattern has these entries).
        for &(k, j, cv) in couplings {
            for &(r, wr) in &p.contacts[k].rows[0] {
                for &(col, wc) in &p.contacts[j].rows[0] {
                    let slot = kt.pattern.find(r, col).expect("coupling entry in pattern");
                    kt.values[slot] += wr * cv * wc;
                }
            }
        }
        kt
    }

    /// The matrix factored and solved for `rhs`.
    pub(super) fn solve(
        &self,
        tangents: &[Matrix3<f64>],
        couplings: &[(usize, usize, f64)],
        rhs: &[f64],
    ) -> Result<Vec<f64>, UmfpackError> {
        let kt = self.assemble(tangents, couplings);
        let x = self.sym.factor(&kt)?.solve(rhs)?;
        Ok(x)
    }

    /// The matrix solved for `rhs` with its residual: (x, ‖A x − rhs‖,
    /// ‖ |A||x| + |rhs| ‖).
    pub(super) fn solve_checked(
        &self,
        tangents: &[Matrix3<f64>],
        rhs: &[f64],
    ) -> Result<(Vec<f64>, f64, f64), UmfpackError> {
        let kt = self.assemble(tangents, &[]);
        let x = self.sym.factor(&kt)?.solve(rhs)?;
        let mut r = kt.mul_vec(&x);
        let mut terms = kt.abs_mul_vec(&x);
        for ((ri, ti), b) in r.iter_mut().zip(terms.iter_mut()).zip(rhs) {
            *ri -= b;
            *ti += b.abs();
        }
        Ok((x, norm(&r), norm(&terms)))
    }
}

/// Newton's method on K u + α f_c(u) = f_pre.
pub(super) struct Newton<'a> {
    pub(super) p: &'a Problem,
    pub(super) props: &'a [[f64; 12]],
    pub(super) matrix: NewtonMatrix<'a>,
    /// ‖f_pre‖ (at least the smallest positive number).
    pub(super) fnorm: f64,
    /// Per point: its tangent at the probe overclosure (α = 1).
    pub(super) probe: Vec<Matrix3<f64>>,
}

/// A converged Newton run.
pub(super) struct Converged {
    pub(super) u: Vec<f64>,
    pub(super) eval: Eval,
    pub(super) iterations: usize,
    pub(super) residual: f64,
    /// Which rule ended it ([`super::StaticState::stopped_by`]).
    pub(super) stopped_by: &'static str,
}

impl Newton<'_> {
    /// Newton from `u` with first matrix from `tangents` and `couplings`, each step
    /// along the line search's length, until ‖R‖ ≤ `tol` ‖f_pre‖, or ‖R‖ at its
    /// round-off floor ([`BACKWARD_TOL`], below [`FLOOR_CEILING`] ‖f_pre‖), or after
    /// `max_iterations`.
    pub(super) fn run(
        &self,
        mut u: Vec<f64>,
        alpha: f64,
        mut tangents: Vec<Matrix3<f64>>,
        mut couplings: Vec<(usize, usize, f64)>,
        (tol, max_iterations): (f64, usize),
    ) -> Result<Converged, StaticError> {
        let (p, props) = (self.p, self.props);
        let mut ev = evaluate(p, props, &u, None, alpha)?;
        let mut res = norm(&ev.residual) / self.fnorm;
        for it in 1..=max_iterations {
            let neg: Vec<f64> = ev.residual.iter().map(|v| -v).collect();
            let du = self.matrix.solve(&tangents, &couplings, &neg)?;
            let slope0 = -dot(&neg, &du);
            let found = line_search::search(slope0, |s| {
                let trial: Vec<f64> = u.iter().zip(&du).map(|(a, b)| a + s * b).collect();
                let e = evaluate(p, props, &trial, None, alpha)?;
                let g = dot(&e.residual, &du);
                Ok::<_, CapiError>(((e, trial), g))
            })?;
            (ev, u) = found.value;
            res = norm(&ev.residual) / self.fnorm;
            couplings.clone_from(&ev.couplings);
            tangents = self.newton_tangents(&ev, alpha);
            let at_floor = res * self.fnorm <= BACKWARD_TOL * ev.scale && res <= FLOOR_CEILING;
            if res <= tol || at_floor {
                return Ok(Converged {
                    u,
                    eval: ev,
                    iterations: it,
                    residual: res,
                    stopped_by: if res <= tol {
                        "load tolerance"
                    } else {
                        "round-off floor"
                    },
                });
            }
        }
        Err(StaticError::NotConverged {
            iterations: max_iterations,
            residual: res,
        })
    }

    /// The points' tangents for the next Newton matrix: their own, or for an open point
    /// of an interface with an initial gap the stand-in [`OPEN_STAND_IN`].
    pub(super) fn newton_tangents(&self, ev: &Eval, alpha: f64) -> Vec<Matrix3<f64>> {
        ev.tangents
            .iter()
            .zip(&ev.out)
            .zip(&self.probe)
            .zip(&self.p.contacts)
            .map(|(((t, o), pt), c)| {
                if o.closed || self.p.interfaces[c.interface].initial_gap == 0.0 {
                    *t
                } else {
                    pt * (OPEN_STAND_IN * alpha)
                }
            })
            .collect()
    }
}
