//! The stuck mode a multi-harmonic backbone starts from when it is one of a pair at one
//! frequency (a symmetric structure: a square block on a plane sliding in x and in y).
//! Every combination φ(θ) = cos θ φ_a + sin θ φ_b of the pair is a linear mode, but the
//! nonlinear modes branch off only from the directions where the joints' averaged
//! microslip is stationary: a Mindlin point below its slip limit softens by
//! k_T0 − k* ∝ k_T0·A/δ* (model.md §3), so the pair's averaged nonlinear energy is
//! V(θ) ∝ Σ_e (k_T0,e/δ*_e) |P_e φ(θ)|³ and the branches start where V′(θ) = 0 (the
//! bifurcation equation of the 1:1 resonance, Lyapunov–Schmidt reduction onto the
//! pair). The eigen solver's φ_a is any combination (the block's was 94 % y, 6 % x),
//! which is no branch's start: Newton then has to turn the shape within the pair
//! against a restoring term of the order of the damping and stalls.
//!
//! The first member of a pair starts at the largest V (the block: sliding along x or y),
//! the second at the stationary direction nearest the one M-orthogonal to it.

use super::first_order::{relative, stuck_mode, stuck_modes};
use super::modes::Mode;
use super::{BackboneError, C64};
use crate::capi;
use crate::mhb::{Law, System};

/// Two stuck modes whose frequencies differ by at most this fraction are a pair.
pub const PAIR: f64 = 1e-6;
/// Directions θ ∈ [0, π) sampled for the stationary points of V.
const SAMPLES: usize = 720;
/// Stationary values of V within this fraction of the largest count as equal.
const EQUAL: f64 = 1e-9;

/// Stuck mode `mode` (1-based) of `sys`, turned within its pair to a branch's start
/// (module docs) if it is one of a pair; as [`stuck_mode`] gives it otherwise (also in
/// a triple or where no joint slips below its limit: V is then constant).
pub fn start_mode(sys: &System, mode: usize) -> Result<Mode, BackboneError> {
    // This mode and its neighbours up to two above, by one eigen solve.
    let modes = stuck_modes(sys, mode.saturating_add(2))?;
    let Some(Some(own)) = modes.get(mode.wrapping_sub(1)).cloned() else {
        return stuck_mode(sys, mode); // its error: no such mode, or overdamped
    };
    let w = own.omega();
    let near = |k: usize| {
        modes
            .get(k.wrapping_sub(1))
            .cloned()
            .flatten()
            .filter(|m| (m.omega() / w - 1.0).abs() <= PAIR)
    };
    let (below, above) = (near(mode.wrapping_sub(1)), near(mode + 1));
    let (a, b, member) = match (below, above) {
        (Some(p), None) if near(mode.wrapping_sub(2)).is_none() => (p, own.clone(), 1),
        (None, Some(p)) if near(mode + 2).is_none() => (own.clone(), p, 0),
        _ => return Ok(own),
    };
    // Two vectors of one direction (a solver's repeated vector) are no pair's plane.
    let Some((a, b)) = orthonormal(sys, &a.shape, &b.shape) else {
        return Ok(own);
    };
    let weights = weights(sys)?;
    let v = |theta: f64| {
        let phi = combined(&a, &b, theta);
        relative(sys, &phi)
            .iter()
            .zip(&weights)
            .map(|(r, w)| w * r.powi(3))
            .sum::<f64>()
    };
    let step = std::f64::consts::PI / SAMPLES as f64;
    let values: Vec<f64> = (0..SAMPLES).map(|j| v(j as f64 * step)).collect();
    let top = values.iter().copied().fold(0.0, f64::max);
    let flat = values.iter().all(|x| (x - top).abs() <= EQUAL * top);
    if top <= 0.0 || flat {
        return Ok(own);
    }
    // Stationary points on the periodic grid (V(θ + π) = V(θ)), refined by a parabola.
    let at = |j: isize| values[j.rem_euclid(SAMPLES as isize) as usize];
    let stationary: Vec<(f64, f64)> = (0..SAMPLES as isize)
        .filter(|&j| {
            let (l, c, r) = (at(j - 1), at(j), at(j + 1));
            (c > l && c >= r) || (c < l && c <= r)
        })
        .map(|j| {
            let (l, c, r) = (at(j - 1), at(j), at(j + 1));
            let curvature = l - 2.0 * c + r;
            let shift = if curvature != 0.0 {
                (0.5 * (l - r) / curvature).clamp(-1.0, 1.0)
            } else {
                0.0
            };
            let theta = (j as f64 + shift) * step;
            (theta, v(theta))
        })
        .collect();
    // The largest V; among equal ones (symmetry: x and y) the one that a rule of the
    // shapes alone picks, not the eigen solver's basis of the pair, which may differ
    // from run to run: so `--mode 1` and `--mode 2` start on different branches.
    let best = stationary.iter().fold(0.0f64, |m, s| m.max(s.1));
    let Some(first) = stationary
        .iter()
        .filter(|s| s.1 >= (1.0 - EQUAL) * best)
        .map(|s| s.0)
        .max_by(|x, y| ranked(&combined(&a, &b, *x), &combined(&a, &b, *y)))
    else {
        return Ok(own);
    };
    let theta = if member == 0 {
        first
    } else {
        let across = first + 0.5 * std::f64::consts::PI;
        stationary
            .iter()
            .map(|s| s.0)
            .min_by(|x, y| angle(*x, across).total_cmp(&angle(*y, across)))
            .unwrap_or(first)
    };
    Ok(Mode {
        lambda: own.lambda,
        shape: combined(&a, &b, theta),
    })
}

/// The order of two shapes of equal V, from the shapes alone (the same whatever basis
/// and sign the pair is given in): the larger |Σᵢ wᵢ φᵢ| with fixed weights
/// wᵢ = sin(√2 (i + 1)), which no symmetry of a model makes cancel as it can with
/// patterned weights (two free blocks sliding against each other have Σ φᵢ = 0 per
/// axis); where those agree to 1e-6 (about what the refined directions are good to),
/// the one whose first moving DOF comes first.
fn ranked(x: &[C64], y: &[C64]) -> std::cmp::Ordering {
    let score = |phi: &[C64]| {
        phi.iter()
            .enumerate()
            .map(|(i, v)| v * (std::f64::consts::SQRT_2 * (i + 1) as f64).sin())
            .sum::<C64>()
            .norm()
    };
    let (sx, sy) = (score(x), score(y));
    if (sx - sy).abs() > 1e-6 * sx.max(sy) {
        return sx.total_cmp(&sy);
    }
    first_moving(y).cmp(&first_moving(x))
}

/// The index of the first DOF that moves by more than 1e-6 of the largest.
fn first_moving(phi: &[C64]) -> usize {
    let top = phi.iter().map(|v| v.norm()).fold(0.0, f64::max);
    phi.iter()
        .position(|v| v.norm() > 1e-6 * top)
        .unwrap_or(phi.len())
}

/// The angle between the directions θ and φ of the pair's plane (period π).
fn angle(theta: f64, phi: f64) -> f64 {
    let d = (theta - phi).rem_euclid(std::f64::consts::PI);
    d.min(std::f64::consts::PI - d)
}

/// k_T0/δ* of each element that is a point (1/length·force/length), 0 for the others.
fn weights(sys: &System) -> Result<Vec<f64>, BackboneError> {
    sys.elements
        .iter()
        .map(|e| match e.law {
            Law::Point(t) => {
                let dstar = capi::linearize(&t, 0.0, 1.0)?.slip_limit;
                Ok(if dstar > 0.0 { t.k_t0 / dstar } else { 0.0 })
            }
            _ => Ok(0.0),
        })
        .collect()
}

/// `shape` turned so that its largest entry is real and positive.
fn real_phase(shape: &[C64]) -> Vec<C64> {
    let big = shape
        .iter()
        .copied()
        .max_by(|x, y| x.norm().total_cmp(&y.norm()))
        .unwrap_or(C64::new(1.0, 0.0));
    let turn = if big.norm() > 0.0 {
        big.conj() / big.norm()
    } else {
        C64::new(1.0, 0.0)
    };
    shape.iter().map(|v| v * turn).collect()
}

/// xᴴ M y.
fn m_inner(sys: &System, x: &[C64], y: &[C64]) -> C64 {
    let n = x.len();
    (0..n)
        .map(|i| x[i].conj() * (0..n).map(|j| y[j] * sys.m[(i, j)]).sum::<C64>())
        .sum()
}

/// The pair (a, b) M-orthonormalized (Gram–Schmidt; the eigen solver's vectors of a
/// double eigenvalue are any two of its plane), each turned real where largest; `None`
/// where b is a along (all but 1e-8 of its M-norm) or either is zero.
fn orthonormal(sys: &System, a: &[C64], b: &[C64]) -> Option<(Vec<C64>, Vec<C64>)> {
    let norm = |x: &[C64]| m_inner(sys, x, x).re.max(0.0).sqrt();
    let unit = |x: Vec<C64>, n: f64| x.into_iter().map(|v| v / n).collect::<Vec<C64>>();
    let (na, nb) = (norm(a), norm(b));
    if !(na > 0.0 && nb > 0.0) {
        return None;
    }
    let a = unit(real_phase(a), na);
    let p = m_inner(sys, &a, b);
    let b: Vec<C64> = b.iter().zip(&a).map(|(y, x)| y - x * p).collect();
    let n_perp = norm(&b);
    (n_perp > 1e-8 * nb).then(|| (a, unit(real_phase(&b), n_perp)))
}

/// cos θ a + sin θ b (M-normalized: the pair is M-orthonormal).
fn combined(a: &[C64], b: &[C64], theta: f64) -> Vec<C64> {
    let (s, c) = theta.sin_cos();
    a.iter().zip(b).map(|(x, y)| x * c + y * s).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(v: &[f64]) -> Vec<C64> {
        v.iter().map(|&x| C64::new(x, 0.0)).collect()
    }

    #[test]
    fn two_blocks_sliding_against_each_other_are_ranked_the_same_in_any_sign() {
        // Σ φᵢ = 0 per axis: DOF-number weights (i + 1) gave both 2.1213 (a tie, broken
        // by the eigen solver's basis).
        let x = shape(&[1.0, 0.0, 0.0, -1.0, 0.0, 0.0]);
        let y = shape(&[0.0, 1.0, 0.0, 0.0, -1.0, 0.0]);
        let neg = |v: &[C64]| v.iter().map(|z| -z).collect::<Vec<_>>();
        let order = ranked(&x, &y);
        assert_ne!(order, std::cmp::Ordering::Equal);
        assert_eq!(ranked(&neg(&x), &y), order);
        assert_eq!(ranked(&x, &neg(&y)), order);
        assert_eq!(ranked(&y, &x), order.reverse());
    }

    #[test]
    fn equal_scores_go_to_the_shape_whose_first_moving_dof_comes_first() {
        // Both score |w₂| (weights sin(√2 (i + 1)); w₂ = sin(3√2)).
        let w = |i: usize| (std::f64::consts::SQRT_2 * (i + 1) as f64).sin();
        let early = shape(&[w(2) / w(0), 0.0, 0.0]);
        let late = shape(&[0.0, 0.0, 1.0]);
        assert_eq!(first_moving(&early), 0);
        assert_eq!(ranked(&early, &late), std::cmp::Ordering::Greater);
        assert_eq!(ranked(&late, &early), std::cmp::Ordering::Less);
    }

    #[test]
    fn a_repeated_vector_is_no_pair() {
        let n = 2;
        let sys = System {
            m: nalgebra::DMatrix::identity(n, n) * 2.0,
            d: nalgebra::DMatrix::zeros(n, n),
            k: nalgebra::DMatrix::identity(n, n),
            f0: vec![0.0; n],
            f1: vec![C64::new(0.0, 0.0); n],
            elements: Vec::new(),
        };
        let a = shape(&[1.0, 2.0]);
        assert!(orthonormal(&sys, &a, &shape(&[-3.0, -6.0])).is_none());
        assert!(orthonormal(&sys, &a, &shape(&[0.0, 0.0])).is_none());
        let (p, q) = orthonormal(&sys, &a, &shape(&[1.0, 0.0])).unwrap();
        assert!(m_inner(&sys, &p, &q).norm() < 1e-15);
        assert!((m_inner(&sys, &q, &q).re - 1.0).abs() < 1e-15);
    }
}
