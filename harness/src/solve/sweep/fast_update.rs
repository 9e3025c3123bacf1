//! The amplitude updates of the fast sweep's contact iterations ([`super::fast`]): the
//! predictor from the last converged frequencies, the consistency test, the next
//! estimate (Anderson in ln a, or the bracketed scalar search for one amplitude) and the
//! product with the updated dynamic stiffness S₀ + BᵀΔB for FGMRES.

use super::anderson::Anderson;
use super::bracket::Bracket;
use super::C64;
use crate::fe::csc::Csc;

/// Largest step of an Anderson iterate beyond the bracket of the current amplitude
/// and its image, in ln a (one decade). Without it, a stiff joint (k_T0·L/(E·A) = 1e6,
/// scenes/hard/stiffness-ratio.toml near resonance) extrapolated to A/δ* ≈ 1e16, where
/// the linearization is no longer representable and the run stopped.
const MAX_EXTRAPOLATION: f64 = std::f64::consts::LN_10;

/// The start estimate `a` at frequency `f` (1/time): ln a extrapolated linearly over
/// frequency from the last two converged frequencies `hist` (f, a), where both are
/// positive; unchanged with fewer than two.
pub fn predict(hist: &[(f64, Vec<f64>)], f: f64, a: &mut [f64]) {
    if let [(f2, a2), (f1, a1)] = hist {
        // At most one decade (MAX_EXTRAPOLATION): a far frequency (7500 Hz → 1e7 Hz
        // on three-beams-coarse) extrapolated ln a by 2e4 steps to an infinite or
        // zero amplitude, and the whole sweep stopped.
        let t = (f - f1) / (f1 - f2);
        for j in 0..a.len() {
            if a1[j] > 0.0 && a2[j] > 0.0 {
                let step = (t * (a1[j] / a2[j]).ln()).clamp(-MAX_EXTRAPOLATION, MAX_EXTRAPOLATION);
                a[j] = a1[j] * if step.is_finite() { step.exp() } else { 1.0 };
            }
        }
    }
}

/// Whether the estimate `a` and the computed amplitudes `a_star` agree, the store's test
/// per unknown: |a − a*| ≤ rtol·max(a, a*) + atol, both raised to `floor` (round-off),
/// atol the iterate's own scale (ATOL_REL, or the tolerance when that is tighter), not
/// the start estimate's.
pub fn consistent(a: &[f64], a_star: &[f64], floor: f64, rtol: f64) -> bool {
    let atol = super::ATOL_REL.min(rtol) * a.iter().chain(a_star).fold(0.0f64, |x, &y| x.max(y));
    a.iter().zip(a_star).all(|(&e, &c)| {
        let (e, c) = (e.max(floor), c.max(floor));
        (e - c).abs() <= rtol * e.max(c) + atol
    })
}

/// The next estimate from the amplitudes `a` and their image `a_star` (below `floor`:
/// round-off) and, with coupled slip, the points' phase cosines ρ and their image (empty
/// otherwise), which ride along in the Anderson vector (clamped to [−1, 1]).
pub fn next_estimate(
    (a, a_star): (&[f64], &[f64]),
    (rho, rho_star): (&[f64], &[f64]),
    floor: f64,
    acc: &mut Anderson,
    bracket: &mut Bracket,
) -> (Vec<f64>, Vec<f64>) {
    // A direction whose computed amplitude is round-off (below the floor) is
    // not excited: it leaves the update (constant 0 in x and g, so it cannot
    // tie the Anderson columns to the moving floor) and is handed on as
    // exactly 0. Kept in, it made the block of block-stick.toml with
    // k_T0 = 1e12 N/mm³ cycle for 50 iterations around 5e-13 mm.
    let excited: Vec<bool> = a_star.iter().map(|&v| v >= floor).collect();
    let log = |v: &f64, e: &bool| if *e { v.max(floor).ln() } else { 0.0 };
    let xs: Vec<f64> = a.iter().zip(&excited).map(|(v, e)| log(v, e)).collect();
    let gs: Vec<f64> = a_star
        .iter()
        .zip(&excited)
        .map(|(v, e)| log(v, e))
        .collect();
    let n = a.len();
    let (mut next, rho_next): (Vec<f64>, Vec<f64>) = if n == 1 && rho.is_empty() {
        (vec![bracket.next(xs[0], gs[0]).exp()], Vec::new())
    } else {
        // Anderson extrapolates; keep each step within a decade of the bracket
        // [min(a, a*), max(a, a*)] (MAX_EXTRAPOLATION).
        let x: Vec<f64> = xs.iter().chain(rho).copied().collect();
        let g: Vec<f64> = gs.iter().chain(rho_star).copied().collect();
        let step = acc.next(&x, &g);
        let amps = step[..n]
            .iter()
            .zip(xs.iter().zip(&gs))
            .map(|(v, (x, g))| {
                v.clamp(x.min(*g) - MAX_EXTRAPOLATION, x.max(*g) + MAX_EXTRAPOLATION)
                    .exp()
            })
            .collect();
        (amps, step[n..].iter().map(|v| v.clamp(-1.0, 1.0)).collect())
    };
    for (v, _) in next.iter_mut().zip(&excited).filter(|(_, e)| !**e) {
        *v = 0.0;
    }
    (next, rho_next)
}

/// y = (S₀ + Σⱼ Bⱼᵀ Δⱼ Bⱼ + Σ_q (B₂q ᵀ Δ'_q B₂q₊₁ + B₂q₊₁ᵀ Δ'_q B₂q)) x: the dynamic
/// stiffness with the contact update `delta` on the rows `row(j)` of B and, with coupled
/// slip, each point's off-diagonal `delta_off` (empty otherwise), without forming it.
pub fn updated_product<'a>(
    s0: &Csc<C64>,
    delta: &[C64],
    delta_off: &[C64],
    row: &impl Fn(usize) -> &'a [(usize, f64)],
    xv: &[C64],
    y: &mut [C64],
) {
    y.iter_mut().for_each(|v| *v = C64::new(0.0, 0.0));
    let pt = &s0.pattern;
    for col in 0..pt.n {
        let xc = xv[col];
        for k in pt.col_ptr[col] as usize..pt.col_ptr[col + 1] as usize {
            y[pt.row_idx[k] as usize] += s0.values[k] * xc;
        }
    }
    let bx = |j: usize| -> C64 { row(j).iter().map(|&(i, w)| xv[i] * w).sum() };
    for (j, d) in delta.iter().enumerate() {
        let mut c = d * bx(j);
        if j < 2 * delta_off.len() {
            c += delta_off[j / 2] * bx(j ^ 1);
        }
        for &(i, w) in row(j) {
            y[i] += c * w;
        }
    }
}
