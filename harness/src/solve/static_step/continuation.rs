//! Continuation on the contact force for a preload Newton cannot solve from rest:
//! K u + α f_c(u) = f_pre from a soft contact α = [`ALPHA_START`] up to the model's
//! α = 1, each stage's Newton starting from the previous stage's solution with its
//! matrix (the contact tangents scale with α).
//!
//! Why not load steps: the laws are positively homogeneous where it matters (linear
//! normal law, stick k_T0, Coulomb's cap μp), so the solution scales with the load and
//! every load step meets the same contact states. What makes Newton cycle is an
//! interface much stiffer than the elements beside it on a non-conforming mesh: the
//! pressure alternates from node to node, points open and close between iterations,
//! and a stuck point's tangential force disappears when it opens. With a soft contact
//! the structure spreads the load smoothly; raising α lets the alternation grow stage
//! by stage. The end point is the model's own equation (α = 1 exactly), so a converged
//! continuation is the same solution Newton would have found.

use super::newton::{Converged, Newton};
use super::{StaticError, MAX_NEWTON, RESIDUAL_TOL};

/// Contact force scale of the first stage.
pub const ALPHA_START: f64 = 1e-6;
/// Largest ratio between two stages' α.
const GROWTH: f64 = 10.0;
/// Smallest ratio: below it the continuation has stalled.
const MIN_GROWTH: f64 = 1.01;
/// Residual tolerance of the stages before α = 1 (relative to ‖f_pre‖): they only
/// lead the way, the last stage converges to [`RESIDUAL_TOL`].
const STAGE_TOL: f64 = 1e-6;
/// Most Newton iterations of a stage before α = 1: a stage that needs more is a step in
/// α too large, retried smaller.
const STAGE_ITERATIONS: usize = MAX_NEWTON;
/// Most stages (successful or not).
const MAX_STAGES: usize = 200;

/// The preload by continuation in α; the stalled error when a stage fails at a ratio
/// below [`MIN_GROWTH`] or after [`MAX_STAGES`] stages.
pub(super) fn continuation(newton: &Newton) -> Result<Converged, StaticError> {
    let start = vec![0.0; newton.p.sys.dofs.n_free()];
    let probe = newton.probe.iter().map(|t| t * ALPHA_START).collect();
    let mut done = newton.run(
        start,
        ALPHA_START,
        probe,
        Vec::new(),
        (STAGE_TOL, MAX_NEWTON),
    )?;
    let (mut alpha, mut growth, mut iterations) = (ALPHA_START, GROWTH, done.iterations);
    let mut residual = done.residual;
    for _ in 0..MAX_STAGES {
        if alpha == 1.0 {
            return Ok(Converged { iterations, ..done });
        }
        let next = (alpha * growth).min(1.0);
        let scale = next / alpha;
        let tangents = newton
            .newton_tangents(&done.eval, alpha)
            .iter()
            .map(|t| t * scale)
            .collect();
        let couplings = done
            .eval
            .couplings
            .iter()
            .map(|&(k, j, c)| (k, j, c * scale))
            .collect();
        let limits = if next == 1.0 {
            (RESIDUAL_TOL, MAX_NEWTON)
        } else {
            (STAGE_TOL, STAGE_ITERATIONS)
        };
        match newton.run(done.u.clone(), next, tangents, couplings, limits) {
            Ok(stage) => {
                iterations += stage.iterations;
                (alpha, done) = (next, stage);
                growth = (growth * growth).min(GROWTH);
            }
            Err(StaticError::NotConverged {
                iterations: spent,
                residual: r,
            }) => {
                iterations += spent;
                residual = r;
                growth = growth.sqrt();
                if growth < MIN_GROWTH {
                    break;
                }
            }
            Err(e) => return Err(e),
        }
    }
    Err(StaticError::Stalled {
        start: ALPHA_START,
        alpha,
        iterations,
        residual,
    })
}
