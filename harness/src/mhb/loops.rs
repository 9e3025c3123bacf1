//! The elements' hysteresis loops of a balance's solution: every DOF's motion rebuilt
//! from its harmonics at N samples of one period, each element's relative displacement
//! marched through the library's point until its loop closes (the AFT's own march,
//! [`super::aft::march`], [`super::contact3d::march_point`]): the loop the balance
//! describes, to set beside the time domain's.

use serde::Serialize;

use super::aft::march;
use super::contact3d::{march_point, System3, VIRGIN};
use super::MhbError;

/// An element at one instant: its displacement (one-direction: (δ, 0, 0); point: (u₁,
/// u₂, h), h the overclosure) and force (one-direction: (F, 0, 0); point: (F₁, F₂, N)).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct LoopSample {
    pub displacement: [f64; 3],
    pub force: [f64; 3],
}

/// Relative displacement of element (i, j) in the state y (j = None: to ground).
pub fn element_slip(y: &[f64], i: usize, j: Option<usize>) -> f64 {
    y[i] - j.map_or(0.0, |j| y[j])
}

/// Per sample t_k = kT/n (k = 1..n) and per element (one-direction elements, then
/// points) the closed loop of the solution `u` (DOF-major, 2H + 1 coefficients per DOF:
/// c₀, then a_j, b_j of cos jωt and sin jωt).
pub fn balance_loops(
    sys: &System3,
    u: &[f64],
    h: usize,
    n: usize,
) -> Result<Vec<Vec<LoopSample>>, MhbError> {
    let m = 2 * h + 1;
    let dofs = sys.linear.n();
    let x: Vec<Vec<f64>> = (1..=n)
        .map(|k| {
            let theta = std::f64::consts::TAU * k as f64 / n as f64;
            (0..dofs)
                .map(|d| {
                    let c = &u[d * m..(d + 1) * m];
                    c[0] + (1..=h)
                        .map(|j| {
                            let (s, co) = (j as f64 * theta).sin_cos();
                            c[2 * j - 1] * co + c[2 * j] * s
                        })
                        .sum::<f64>()
                })
                .collect()
        })
        .collect();
    let mut loops = vec![Vec::with_capacity(sys.linear.elements.len() + sys.elements.len()); n];
    for e in &sys.linear.elements {
        let delta: Vec<f64> = x.iter().map(|y| element_slip(y, e.i, e.j)).collect();
        let p = march(&e.law, &delta)?;
        for (k, l) in loops.iter_mut().enumerate() {
            l.push(LoopSample {
                displacement: [delta[k], 0.0, 0.0],
                force: [p.force[k], 0.0, 0.0],
            });
        }
    }
    for e in &sys.elements {
        let disp: Vec<[f64; 3]> = x.iter().map(|y| e.displacement(y)).collect();
        let p = march_point(&e.contact, e.coupled, &disp, &VIRGIN)?;
        for (k, l) in loops.iter_mut().enumerate() {
            l.push(LoopSample {
                displacement: disp[k],
                force: [p.force[0][k], p.force[1][k], p.force[2][k]],
            });
        }
    }
    Ok(loops)
}
