//! Anderson acceleration (Walker & Ni 2011) with mixing β of the amplitude fixed point
//! a = a*(a), in log variables x = ln a, g(x) = ln a*(eᵡ): the host-side update of the
//! fast mode's contact iteration (the thesis mode uses the library store's rule).
//!
//! With residuals fₖ = g(xₖ) − xₖ and the differences ΔX, ΔF of the last `depth` steps,
//! γ = argmin ‖fₖ − ΔF γ‖ and xₖ₊₁ = xₖ + β fₖ − (ΔX + β ΔF) γ. Without history this is
//! a ← a* (β = 1); with history it is a multisecant (GMRES-like on linear maps) step,
//! so the 2-cycle of a ← a* (Fig. 4.13) cannot persist (test below: |g'| = 2).

use nalgebra::{DMatrix, DVector};

/// Mixing β. β = 1/2 (the thesis's relaxation, Fig. 4.14) was measured 3–4× slower on
/// the three-beam scene near resonance (≈ 30 vs 3–11 iterations per frequency).
pub const BETA: f64 = 1.0;
/// Tikhonov regularization of the small least-squares problem (relative to its scale).
const REG: f64 = 1e-12;

/// Anderson state over vectors of length n.
#[derive(Debug, Clone)]
pub struct Anderson {
    depth: usize,
    prev: Option<(Vec<f64>, Vec<f64>)>, // (x, f) of the previous step
    dx: Vec<Vec<f64>>,
    df: Vec<Vec<f64>>,
}

impl Anderson {
    pub fn new(depth: usize) -> Self {
        Anderson {
            depth,
            prev: None,
            dx: Vec::new(),
            df: Vec::new(),
        }
    }

    /// Next iterate from the current x and g(x) (both log amplitudes).
    pub fn next(&mut self, x: &[f64], g: &[f64]) -> Vec<f64> {
        let f: Vec<f64> = g.iter().zip(x).map(|(a, b)| a - b).collect();
        if let Some((xp, fp)) = self.prev.take() {
            self.df
                .push(f.iter().zip(&fp).map(|(a, b)| a - b).collect());
            self.dx
                .push(x.iter().zip(&xp).map(|(a, b)| a - b).collect());
            if self.df.len() > self.depth {
                self.df.remove(0);
                self.dx.remove(0);
            }
        }
        self.prev = Some((x.to_vec(), f.clone()));
        let k = self.df.len();
        let relaxed = |n: usize| x[n] + BETA * f[n];
        if k == 0 {
            return (0..x.len()).map(relaxed).collect();
        }
        // Normal equations (k ≤ depth, tiny): (ΔFᵀΔF + λI) γ = ΔFᵀ f.
        let mut a = DMatrix::<f64>::zeros(k, k);
        let mut rhs = DVector::<f64>::zeros(k);
        for i in 0..k {
            for j in 0..k {
                a[(i, j)] = self.df[i].iter().zip(&self.df[j]).map(|(p, q)| p * q).sum();
            }
            rhs[i] = self.df[i].iter().zip(&f).map(|(p, q)| p * q).sum();
        }
        let scale = (0..k)
            .map(|i| a[(i, i)])
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        for i in 0..k {
            a[(i, i)] += REG * scale;
        }
        let Some(gamma) = a.lu().solve(&rhs) else {
            return (0..x.len()).map(relaxed).collect();
        };
        (0..x.len())
            .map(|n| {
                relaxed(n)
                    - (0..k)
                        .map(|i| (self.dx[i][n] + BETA * self.df[i][n]) * gamma[i])
                        .sum::<f64>()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn norm(v: &[f64]) -> f64 {
        v.iter().map(|x| x * x).sum::<f64>().sqrt()
    }

    #[test]
    fn converges_where_plain_iteration_two_cycles() {
        // g(x) = −2x + 0.3 sin x (per component, coupled): fixed point at 0; plain
        // iteration x ← g(x) diverges (|g'| = 2 > 1), Anderson converges.
        let g = |x: &[f64]| -> Vec<f64> {
            vec![-2.0 * x[0] + 0.3 * x[1].sin(), -1.5 * x[1] + 0.2 * x[0]]
        };
        let mut x = vec![0.5, -0.4];
        let mut acc = Anderson::new(4);
        for _ in 0..15 {
            let gx = g(&x);
            x = acc.next(&x, &gx);
        }
        // Measured: 1e-13 after 6 steps (superlinear, as for GMRES on a linear map).
        assert!(norm(&x) < 1e-10, "{x:?}");
        // Plain iteration moves away.
        let mut y = vec![0.5, -0.4];
        for _ in 0..10 {
            y = g(&y);
        }
        assert!(norm(&y) > 1.0);
    }
}
