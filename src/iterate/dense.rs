//! A small dense complex system with contact elements, solved for consistent amplitudes
//! by Newton on log-amplitudes (default) or the scalar update rule per contact.

use super::*;

/// One contact element of a dense system, acting in the direction of its DOFs: between
/// DOF `dof` and DOF `other`, or between `dof` and ground when `other` is None. Its
/// amplitude is |u_dof − u_other| (|u_dof| to ground).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactElement {
    pub contact: Contact,
    pub dof: usize,
    pub other: Option<usize>,
}

/// A small dense linear system with contact elements:
/// (K + K_c(k*) + iω(D + D_c(d*)) − ω²M) u = f, n ≤ ~50 DOF.
#[derive(Debug, Clone, PartialEq)]
pub struct DenseProblem {
    /// Mass matrix M (n × n).
    pub mass: DMatrix<f64>,
    /// Stiffness K without the contacts (n × n).
    pub stiffness: DMatrix<f64>,
    /// Viscous damping D without the contacts (n × n).
    pub damping: DMatrix<f64>,
    /// Complex force amplitudes f (n).
    pub force: DVector<Complex64>,
    /// Angular frequency ω > 0.
    pub omega: f64,
    pub contacts: Vec<ContactElement>,
}

/// The consistent state of a dense problem.
#[derive(Debug, Clone, PartialEq)]
pub struct DenseSolution {
    /// Contact amplitudes a* of the last solve, one per contact element.
    pub amplitudes: Vec<f64>,
    /// The estimates the last linearizations were made for.
    pub estimates: Vec<f64>,
    /// Complex displacement amplitudes u of the last solve.
    pub displacement: DVector<Complex64>,
    pub linearizations: Vec<Linearization>,
    /// Linear solves made (iterations plus finite-difference solves).
    pub solves: usize,
    /// Contact linearizations made, over all contacts.
    pub linearization_count: usize,
    /// Outer iterations (one per full residual evaluation).
    pub iterations: usize,
}

impl DenseProblem {
    fn validate(&self) -> Result<(), IterateError> {
        let n = self.force.len();
        let square = |m: &DMatrix<f64>| m.nrows() == n && m.ncols() == n;
        if !square(&self.mass) || !square(&self.stiffness) || !square(&self.damping) {
            return Err(IterateError::Invalid(
                "M, K, D must be n x n with n = len(f)",
            ));
        }
        if !(self.omega.is_finite() && self.omega > 0.0) {
            return Err(IterateError::Invalid("omega must be finite and > 0"));
        }
        let finite = self
            .mass
            .iter()
            .chain(self.stiffness.iter())
            .chain(self.damping.iter());
        if !finite.clone().all(|x| x.is_finite())
            || !self
                .force
                .iter()
                .all(|z| z.re.is_finite() && z.im.is_finite())
        {
            return Err(IterateError::Invalid("non-finite matrix or force entry"));
        }
        for c in &self.contacts {
            if c.dof >= n || c.other.is_some_and(|j| j >= n || j == c.dof) {
                return Err(IterateError::Invalid(
                    "contact DOF out of range or tied to itself",
                ));
            }
        }
        Ok(())
    }

    /// The linear solve for given contact linearizations: u and the contact amplitudes.
    pub fn solve_linear(
        &self,
        lins: &[Linearization],
    ) -> Result<(DVector<Complex64>, Vec<f64>), IterateError> {
        let w = self.omega;
        let n = self.force.len();
        let mut z = DMatrix::<Complex64>::from_fn(n, n, |i, j| {
            Complex64::new(
                self.stiffness[(i, j)] - w * w * self.mass[(i, j)],
                w * self.damping[(i, j)],
            )
        });
        for (c, lin) in self.contacts.iter().zip(lins) {
            // Spring k* and damper d* between the two DOFs (4.2 per contact, Fig. 4.5).
            let y = Complex64::new(lin.k_star, w * lin.d_star);
            let i = c.dof;
            z[(i, i)] += y;
            if let Some(j) = c.other {
                z[(j, j)] += y;
                z[(i, j)] -= y;
                z[(j, i)] -= y;
            }
        }
        let u = z.lu().solve(&self.force).ok_or(IterateError::Singular)?;
        if !u.iter().all(|v| v.re.is_finite() && v.im.is_finite()) {
            return Err(IterateError::Singular);
        }
        let amps = self
            .contacts
            .iter()
            .map(|c| (u[c.dof] - c.other.map_or(Complex64::new(0.0, 0.0), |j| u[j])).norm())
            .collect();
        Ok((u, amps))
    }
}

/// State of the dense iteration: linearize, solve, and count.
struct DenseEval<'p> {
    problem: &'p DenseProblem,
    method: Method,
    solves: usize,
    lin_count: usize,
    floor: f64,
}

impl DenseEval<'_> {
    fn linearize(&mut self, c: usize, a: f64) -> Result<Linearization, IterateError> {
        self.lin_count += 1;
        let p = self.problem;
        Ok(linearize(&p.contacts[c].contact, a, p.omega, self.method)?)
    }

    fn solve(
        &mut self,
        lins: &[Linearization],
    ) -> Result<(DVector<Complex64>, Vec<f64>), IterateError> {
        self.solves += 1;
        self.problem.solve_linear(lins)
    }

    /// Residual r_c = ln a*_c − ln a_c for estimates a (floored), with everything used.
    fn residual(&mut self, a: &[f64]) -> Result<Residual, IterateError> {
        let lins = (0..a.len())
            .map(|c| self.linearize(c, a[c]))
            .collect::<Result<Vec<_>, _>>()?;
        let (u, a_star) = self.solve(&lins)?;
        let r = self.log_residual(a, &a_star);
        Ok(Residual { lins, u, a_star, r })
    }

    fn log_residual(&self, a: &[f64], a_star: &[f64]) -> DVector<f64> {
        DVector::from_fn(a.len(), |c, _| {
            a_star[c].max(self.floor).ln() - a[c].max(self.floor).ln()
        })
    }
}

struct Residual {
    lins: Vec<Linearization>,
    u: DVector<Complex64>,
    a_star: Vec<f64>,
    r: DVector<f64>,
}

/// Finds consistent contact amplitudes a_c = |u_i − u_j| of a small dense system (4.2.3 for
/// several points at once).
///
/// [`Scheme::Secant`] (default): Newton on s = ln a with a forward-difference Jacobian (one
/// extra linearization and solve per contact: perturbing s_c changes only contact c's k*,
/// d*), steps limited to a decade (or to the largest |r_c|), backtracking on ‖r‖₂; when the Jacobian is singular or
/// backtracking fails, one relaxation step a ← (a + a*)/2 (the scalar rule
/// [`next_estimate`] per contact) and Newton again. [`Scheme::Direct`] and
/// [`Scheme::Relaxation`] apply [`next_estimate`] per contact; Direct reports a 2-cycle.
///
/// Stops when |a*_c − a_c| ≤ tolerance · a_c for every contact. Amplitudes below
/// 1e-14 × the largest stick amplitude are floored there (a contact that does not move).
pub fn solve_dense(
    problem: &DenseProblem,
    options: &Options,
) -> Result<DenseSolution, IterateError> {
    problem.validate()?;
    options.validate()?;
    let nc = problem.contacts.len();
    let mut ev = DenseEval {
        problem,
        method: options.method,
        solves: 0,
        lin_count: 0,
        floor: 0.0,
    };
    let zeros = vec![0.0; nc];
    let stick = ev.residual(&zeros)?;
    let scale = stick.a_star.iter().fold(0.0_f64, |m, &x| m.max(x));
    if nc == 0 || scale == 0.0 {
        return Ok(DenseSolution {
            amplitudes: stick.a_star,
            estimates: zeros,
            displacement: stick.u,
            linearizations: stick.lins,
            solves: ev.solves,
            linearization_count: ev.lin_count,
            iterations: 0,
        });
    }
    ev.floor = AMPLITUDE_FLOOR * scale;
    let mut a: Vec<f64> = match options.initial {
        Some(x) => vec![x; nc],
        None => stick.a_star.iter().map(|&x| x.max(ev.floor)).collect(),
    };
    let mut histories: Vec<Vec<(f64, f64)>> = vec![Vec::new(); nc];
    let mut last_change = f64::INFINITY;
    let mut cur = ev.residual(&a)?;
    for iteration in 1..=options.max_iterations {
        for c in 0..nc {
            histories[c].push((a[c].max(ev.floor), cur.a_star[c].max(ev.floor)));
        }
        last_change = (0..nc)
            .map(|c| (cur.a_star[c].max(ev.floor) - a[c].max(ev.floor)).abs() / a[c].max(ev.floor))
            .fold(0.0, f64::max);
        if last_change <= options.tolerance {
            return Ok(DenseSolution {
                amplitudes: cur.a_star,
                estimates: a,
                displacement: cur.u,
                linearizations: cur.lins,
                solves: ev.solves,
                linearization_count: ev.lin_count,
                iterations: iteration,
            });
        }
        if iteration == options.max_iterations {
            break;
        }
        let scalar = |scheme: Scheme, h: &[Vec<(f64, f64)>]| -> Vec<f64> {
            h.iter().map(|hc| next_estimate(scheme, hc)).collect()
        };
        match options.scheme {
            Scheme::Direct => {
                if let Some((x, y)) = dense_two_cycle(&histories, options.tolerance) {
                    return Err(IterateError::TwoCycle { a: x, b: y });
                }
                a = scalar(Scheme::Direct, &histories);
                cur = ev.residual(&a)?;
            }
            Scheme::Relaxation => {
                a = scalar(Scheme::Relaxation, &histories);
                cur = ev.residual(&a)?;
            }
            Scheme::Secant => match newton_step(&mut ev, &a, &cur)? {
                Some((a_new, next)) => {
                    a = a_new;
                    cur = next;
                }
                None => {
                    a = scalar(Scheme::Relaxation, &histories);
                    cur = ev.residual(&a)?;
                }
            },
        }
    }
    Err(IterateError::MaxIterations {
        iterations: options.max_iterations,
        last_change,
    })
}

/// One damped Newton step on r(s) = 0, s = ln a; None when it cannot make progress.
fn newton_step(
    ev: &mut DenseEval,
    a: &[f64],
    cur: &Residual,
) -> Result<Option<(Vec<f64>, Residual)>, IterateError> {
    let nc = a.len();
    let s: Vec<f64> = a.iter().map(|&x| x.max(ev.floor).ln()).collect();
    let mut jac = DMatrix::<f64>::zeros(nc, nc);
    for c in 0..nc {
        let a_c = (s[c] + FD_STEP).exp();
        let mut lins = cur.lins.clone();
        lins[c] = ev.linearize(c, a_c)?;
        let (_, a_star) = ev.solve(&lins)?;
        let mut a_pert = a.to_vec();
        a_pert[c] = a_c;
        let r = ev.log_residual(&a_pert, &a_star);
        jac.set_column(c, &((r - &cur.r) / FD_STEP));
    }
    let Some(mut step) = jac.lu().solve(&(-&cur.r)) else {
        return Ok(None);
    };
    let biggest = step.amax();
    if !biggest.is_finite() {
        return Ok(None);
    }
    // At most a decade, or as far as the direct update a ← a* would go (a contact that
    // starts at the floor, e.g. one at rest in the stick state by symmetry, may need many).
    let limit = MAX_LOG_STEP.max(cur.r.amax());
    if biggest > limit {
        step *= limit / biggest;
    }
    let norm0 = cur.r.norm();
    let mut lambda = 1.0;
    for _ in 0..8 {
        let a_new: Vec<f64> = (0..nc).map(|c| (s[c] + lambda * step[c]).exp()).collect();
        let next = ev.residual(&a_new)?;
        // Armijo-type sufficient decrease of ‖r‖₂ (coefficient 1e-4, halving λ).
        if next.r.norm() <= (1.0 - 1e-4 * lambda) * norm0 {
            return Ok(Some((a_new, next)));
        }
        lambda *= 0.5;
    }
    Ok(None)
}

/// [`super::point`]'s `two_cycle` for every contact at once: each has settled (a_k ≈ a_{k−2}) and at least
/// one still swings by more than the tolerance; reports the contact with the largest swing.
fn dense_two_cycle(histories: &[Vec<(f64, f64)>], tolerance: f64) -> Option<(f64, f64)> {
    let mut worst: Option<(f64, f64, f64)> = None;
    for h in histories {
        let n = h.len();
        if n < 2 {
            return None;
        }
        let (a0, a1, a2) = (h[n - 2].0, h[n - 1].0, h[n - 1].1);
        if (a2 - a0).abs() > TWO_CYCLE_MATCH * a2 {
            return None;
        }
        let swing = (a2 - a1).abs() / a2;
        if swing > tolerance && worst.is_none_or(|w| swing > w.0) {
            worst = Some((swing, a1, a2));
        }
    }
    worst.map(|w| (w.1, w.2))
}
