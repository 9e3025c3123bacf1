//! The static step of a lumped system with three-direction points: K x + f_c(x) = f₀
//! with each point's normal law unilateral (N = max(0, k_N·h), h = g₀ − g) and its
//! tangential directions stuck (k_T0: the load is applied from a virgin, sticking
//! contact; an open point carries nothing), the 1D joints stuck at their fixed normal force; solved by active sets
//! (closed points carry k_N, open ones nothing) until no point changes side. Gives each
//! point's static normal force, from which the thesis's model linearizes.

use nalgebra::{DMatrix, DVector};

use super::lumped_system::{Element3, System3};

/// Active-set rounds at most (each opens or closes at least one point).
const MAX_ROUNDS: usize = 100;

/// The static state: per point its normal force N₀ (force, ≥ 0) and
/// the magnitude of its stuck tangential force (force); the displacements.
#[derive(Debug, Clone)]
pub struct Static {
    pub normal: Vec<f64>,
    pub tangential: Vec<f64>,
    /// The static displacement per DOF (length).
    pub x: Vec<f64>,
}

/// Solves the static step of `sys` (its 1D elements stuck, points stuck tangentially
/// and unilateral normally); an error names what leaves the system without a static
/// state.
pub fn solve(sys: &System3, names: &[String]) -> Result<Static, String> {
    let mut closed = vec![true; sys.elements.len()];
    for _ in 0..MAX_ROUNDS {
        let x = stuck_solution(sys, &closed).ok_or_else(|| {
            let open: Vec<&str> = names
                .iter()
                .zip(&closed)
                .filter(|(_, c)| !**c)
                .map(|(n, _)| n.as_str())
                .collect();
            if open.is_empty() {
                "the static step is singular: a body is held by nothing along some direction"
                    .to_string()
            } else {
                format!(
                    "the static step is singular with joint(s) {} open: the static load lifts them off and nothing else holds the body",
                    open.join(", ")
                )
            }
        })?;
        let h: Vec<f64> = sys
            .elements
            .iter()
            .map(|e| e.displacement(x.as_slice())[2])
            .collect();
        let next: Vec<bool> = h.iter().map(|&h| h > 0.0).collect();
        if next == closed {
            return Ok(Static {
                normal: sys
                    .elements
                    .iter()
                    .zip(&h)
                    .map(|(e, &h)| e.contact.k_n * h.max(0.0))
                    .collect(),
                tangential: sys
                    .elements
                    .iter()
                    .map(|e| {
                        let d = e.displacement(x.as_slice());
                        e.contact.k_t0 * d[0].hypot(d[1])
                    })
                    .collect(),
                x: x.as_slice().to_vec(),
            });
        }
        closed = next;
    }
    Err(format!(
        "the static step's contact states did not settle in {MAX_ROUNDS} rounds"
    ))
}

/// The solution of the stuck system with the points in `closed` carrying k_N (and its
/// preload k_N·g₀) and the others open, or None when singular.
fn stuck_solution(sys: &System3, closed: &[bool]) -> Option<DVector<f64>> {
    let only_closed = System3 {
        linear: sys.linear.clone(),
        elements: sys
            .elements
            .iter()
            .zip(closed)
            .map(|(e, &c)| Element3 {
                // An open point carries nothing, tangentially either.
                rows: if c {
                    e.rows.clone()
                } else {
                    Default::default()
                },
                ..e.clone()
            })
            .collect(),
    };
    let (k, f): (DMatrix<f64>, DVector<f64>) = only_closed.stuck();
    let x = k.clone().lu().solve(&f)?;
    // A solve that is not finite, or does not satisfy K x = f to round-off (LU of a
    // numerically singular K), has no static state.
    let scale = k.abs().column_sum().max() * x.amax() + f.amax();
    let ok = x.iter().all(|v| v.is_finite()) && (&k * &x - &f).amax() <= 1e-9 * scale;
    ok.then_some(x)
}
