//! The parallel Jenkins cells (an Iwan model, Iwan 1966) whose sum reproduces Mindlin's
//! virgin curve (2.47) on a straight path (docs/contact3d.md §3).
//!
//! A continuous Iwan model with stiffness density ρ(x) over the cells' stretch at slip x has
//! the virgin curve g(s) = ∫₀ˢ ρ x dx + s ∫ₛ^∞ ρ dx, so g'' = −ρ. Mindlin's curve (2.47),
//! with g' = k_T0 (1 − x/δ*)^{1/2} (2.48), needs ρ(x) = k_T0 / (2δ* (1 − x/δ*)^{1/2}) on
//! [0, δ*] (model.md §3, §4). In w = (1 − x/δ*)^{1/2} the stiffness is uniform,
//! ρ dx = k_T0 dw, and x = δ*(1 − w²). The cells split w ∈ [0, 1] into n intervals; cell i
//! carries the stiffness k_T0 Δwᵢ and the strength fᵢ = ∫ k_T0 x dw over its interval, so
//! that Σ kᵢ = k_T0 and Σ fᵢ = μF_N exactly and the discrete virgin curve equals (2.47) at
//! every interval boundary. The boundaries are graded geometrically in v = 1 − w from
//! v = [`SMALLEST_V`] (the first cell slips at x ≈ 2·10⁻⁴ δ*) to v = 1.
//!
//! Each cell then obeys the same Masing rule in 1D as the continuous model (model.md §4),
//! and in the plane each has its own circular limit (coupled slip).

/// Largest number of cells a point may use.
pub const MAX_CELLS: usize = 128;
/// Cells used when the caller asks for the default.
pub const DEFAULT_CELLS: usize = 32;
/// v = 1 − w at the first boundary above 0: sets the smallest slipping cell, x ≈ 2v δ*.
pub const SMALLEST_V: f64 = 1e-4;

/// A set of cells as fractions: stiffness kᵢ/k_T0 and strength fᵢ/(μF_N).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cells {
    pub n: usize,
    pub stiffness: [f64; MAX_CELLS],
    pub strength: [f64; MAX_CELLS],
}

impl Cells {
    /// One cell: the Jenkins element (k_T0, μF_N).
    pub fn jenkins() -> Self {
        let mut c = Self {
            n: 1,
            stiffness: [0.0; MAX_CELLS],
            strength: [0.0; MAX_CELLS],
        };
        c.stiffness[0] = 1.0;
        c.strength[0] = 1.0;
        c
    }

    /// `n` cells (1 ≤ n ≤ MAX_CELLS, checked by the caller) reproducing Mindlin's curve.
    pub fn mindlin(n: usize) -> Self {
        let mut c = Self {
            n,
            stiffness: [0.0; MAX_CELLS],
            strength: [0.0; MAX_CELLS],
        };
        // Boundaries v₀ = 0 < v₁ = SMALLEST_V < … < v_n = 1 (geometric from v₁ on).
        let v = |j: usize| -> f64 {
            if j == 0 {
                0.0
            } else if j == n || n == 1 {
                1.0
            } else {
                SMALLEST_V * (1.0 / SMALLEST_V).powf((j - 1) as f64 / (n - 1) as f64)
            }
        };
        for i in 0..n {
            let (wa, wb) = (1.0 - v(i), 1.0 - v(i + 1)); // wa > wb
            let dw = v(i + 1) - v(i);
            // ∫ (1 − w²) dw over [wb, wa] = Δw − (wa³ − wb³)/3, with wa³ − wb³ factored.
            let cubes = dw * (wa * wa + wa * wb + wb * wb);
            c.stiffness[i] = dw;
            // fᵢ/(μF_N) = k_T0 δ* (…)/(μF_N) = 1.5 (…) since δ* = 1.5 μF_N/k_T0 (2.46).
            c.strength[i] = 1.5 * (dw - cubes / 3.0);
        }
        c
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::mindlin::Mindlin;

    #[test]
    fn cells_sum_to_k_t0_and_the_friction_limit_and_meet_mindlin_at_the_boundaries() {
        for n in [1, 2, 8, 32, MAX_CELLS] {
            let c = Cells::mindlin(n);
            let k: f64 = c.stiffness[..n].iter().sum();
            let f: f64 = c.strength[..n].iter().sum();
            assert!(
                (k - 1.0).abs() < 1e-14 && (f - 1.0).abs() < 1e-14,
                "{n}: {k} {f}"
            );
            assert!(c.stiffness[..n].iter().all(|&v| v > 0.0));
        }
        // g_n(s) at a boundary x = δ*(1 − w²) equals (2.47): μF_N = 1, k_T0 = 1.5, δ* = 1.
        let m = Mindlin::new(1.0, 1.5);
        let c = Cells::mindlin(32);
        let mut below = 0.0;
        for i in 0..31 {
            below += c.strength[i];
            let x_cell = c.strength[i] / (1.5 * c.stiffness[i]);
            let wb: f64 = 1.0 - c.stiffness[..=i].iter().sum::<f64>();
            let s = 1.0 - wb * wb;
            let above: f64 = c.stiffness[i + 1..32].iter().sum::<f64>() * 1.5;
            assert!(x_cell < s);
            assert!((below + above * s - m.force(s)).abs() < 1e-13, "{i}");
        }
    }
}
