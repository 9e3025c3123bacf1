//! The omitted modes of the modal route ([`super::modal_route`]) by their residual
//! flexibility and its first inertia term: with R = K_s⁻¹ − ΦΛ⁻¹Φᵀ (the static
//! flexibility the p kept modes leave out) and the omitted pairs' expansion
//!
//!   Σ_{r>p} φ_rφ_rᵀ/(λ_r − ω²) = R + ω² R M R + O(ω⁴/λ_{p+1}²)
//!
//! (the mode-acceleration correction and its inertia term, undamped: the omitted modes
//! sit above the band, where their damping barely acts). Every image under the contact
//! rows B and the outputs C comes from one Cholesky factor of K_s: 2 solves per contact
//! direction once per basis, 4 per load, 2 blocked ones (real and imaginary part) per
//! field.

use nalgebra::DMatrix;

use super::C64;
use crate::fe::csc::Csc;
use crate::model::Output;
use crate::solve::cholmod::{Cholesky, CholmodError};

/// Contact row j of a sweep's m contact directions (sparse: free DOF, weight).
pub type RowFn<'a, 'r> = dyn Fn(usize) -> &'r [(usize, f64)] + 'a;

/// The kept modes: shapes φ_r (M-normalized, on the free DOFs) and λ_r.
pub struct Kept<'a> {
    pub shapes: &'a [Vec<f64>],
    pub lambda: &'a [f64],
}

/// The residual's factor and images.
pub struct Residual {
    factor: Cholesky,
    /// M, for R M R.
    mass: Csc<f64>,
    /// [B R Bᵀ, B R M R Bᵀ] (m × m) and [C R Bᵀ, C R M R Bᵀ] (outputs × m).
    brb: [DMatrix<f64>; 2],
    crb: [DMatrix<f64>; 2],
    /// [B R f̂, B R M R f̂] and [C R f̂, C R M R f̂] of the current load.
    brf: [Vec<C64>; 2],
    crf: [Vec<C64>; 2],
}

/// Contact directions per blocked solve while forming the residual's images.
const BLOCK: usize = 32;

fn dot_row(r: &[(usize, f64)], v: &[f64]) -> f64 {
    r.iter().map(|&(i, w)| w * v[i]).sum()
}

impl Residual {
    /// Factors K_s and forms the contact rows' images; `row(j)` is contact row j of m.
    pub fn new<'r>(
        ks: &Csc<f64>,
        mass: &Csc<f64>,
        kept: &Kept,
        (m, row): (usize, &RowFn<'_, 'r>),
        outputs: &[Output],
    ) -> Result<Self, CholmodError> {
        let nout = outputs.len();
        let mut r = Residual {
            factor: Cholesky::factor(ks)?,
            mass: mass.clone(),
            brb: [DMatrix::zeros(m, m), DMatrix::zeros(m, m)],
            crb: [DMatrix::zeros(nout, m), DMatrix::zeros(nout, m)],
            brf: [vec![C64::new(0.0, 0.0); m], vec![C64::new(0.0, 0.0); m]],
            crf: [
                vec![C64::new(0.0, 0.0); nout],
                vec![C64::new(0.0, 0.0); nout],
            ],
        };
        let n = ks.n();
        for j0 in (0..m).step_by(BLOCK) {
            let k = BLOCK.min(m - j0);
            let mut b = vec![0.0; n * k];
            for c in 0..k {
                for &(i, w) in row(j0 + c) {
                    b[c * n + i] += w;
                }
            }
            let xs = r.images(kept, &b, k)?;
            for (order, x) in xs.iter().enumerate() {
                for (c, x) in x.chunks(n).enumerate() {
                    for kk in 0..m {
                        r.brb[order][(kk, j0 + c)] = dot_row(row(kk), x);
                    }
                    for (kk, out) in outputs.iter().enumerate() {
                        r.crb[order][(kk, j0 + c)] = dot_row(&out.dofs, x);
                    }
                }
            }
        }
        Ok(r)
    }

    /// R V and R M R V for the `k` columns of V (n × k, column-major).
    fn images(&mut self, kept: &Kept, v: &[f64], k: usize) -> Result<[Vec<f64>; 2], CholmodError> {
        let first = self.apply(kept, v, k)?;
        let n = v.len() / k.max(1);
        let m_first: Vec<f64> = first.chunks(n).flat_map(|c| self.mass.mul_vec(c)).collect();
        let second = self.apply(kept, &m_first, k)?;
        Ok([first, second])
    }

    /// R V = K_s⁻¹V − Σ_r φ_r (φ_rᵀV)/λ_r, one blocked solve for the k columns.
    fn apply(&mut self, kept: &Kept, v: &[f64], k: usize) -> Result<Vec<f64>, CholmodError> {
        let mut x = vec![0.0; v.len()];
        self.factor.solve_many(k, v, &mut x)?;
        let n = v.len() / k.max(1);
        for (vc, xc) in v.chunks(n).zip(x.chunks_mut(n)) {
            for (phi, l) in kept.shapes.iter().zip(kept.lambda) {
                let c = phi.iter().zip(vc).map(|(a, b)| a * b).sum::<f64>() / l;
                xc.iter_mut().zip(phi).for_each(|(xi, p)| *xi -= c * p);
            }
        }
        Ok(x)
    }

    /// The load's images for excitation `f` (complex: real and imaginary parts in turn).
    pub fn set_load<'r>(
        &mut self,
        kept: &Kept,
        f: &[C64],
        row: &dyn Fn(usize) -> &'r [(usize, f64)],
        outputs: &[Output],
    ) -> Result<(), CholmodError> {
        let z = C64::new(0.0, 0.0);
        for v in self.brf.iter_mut().chain(self.crf.iter_mut()) {
            v.iter_mut().for_each(|x| *x = z);
        }
        for unit in [C64::new(1.0, 0.0), C64::new(0.0, 1.0)] {
            let part: Vec<f64> = f.iter().map(|v| (v * unit.conj()).re).collect();
            if part.iter().all(|&v| v == 0.0) {
                continue;
            }
            let xs = self.images(kept, &part, 1)?;
            for (order, x) in xs.iter().enumerate() {
                for (k, v) in self.brf[order].iter_mut().enumerate() {
                    *v += unit * dot_row(row(k), x);
                }
                for (k, out) in outputs.iter().enumerate() {
                    self.crf[order][k] += unit * dot_row(&out.dofs, x);
                }
            }
        }
        Ok(())
    }

    /// Adds the omitted modes at ω² = `w2` to G, O (column-major slices), r₀ and y₀.
    pub fn add_to(&self, w2: f64, g: &mut [C64], o: &mut [C64], r0: &mut [C64], y0: &mut [C64]) {
        let add = |out: &mut [C64], a: &[DMatrix<f64>; 2]| {
            for (v, (s, d)) in out.iter_mut().zip(a[0].iter().zip(a[1].iter())) {
                v.re += s + w2 * d;
            }
        };
        add(g, &self.brb);
        add(o, &self.crb);
        for (out, a) in [(r0, &self.brf), (y0, &self.crf)] {
            for (v, (s, d)) in out.iter_mut().zip(a[0].iter().zip(&a[1])) {
                *v += s + d * w2;
            }
        }
    }

    /// Adds (R + ω²RMR) g to `x` at ω² = `w2`.
    pub fn add_field(
        &mut self,
        kept: &Kept,
        w2: f64,
        g: &[C64],
        x: &mut [C64],
    ) -> Result<(), CholmodError> {
        // The real and the imaginary part (those not zero) as one blocked solve each
        // for R and R M R.
        let n = g.len();
        let mut units = Vec::with_capacity(2);
        let mut parts = Vec::with_capacity(2 * n);
        for unit in [C64::new(1.0, 0.0), C64::new(0.0, 1.0)] {
            let start = parts.len();
            parts.extend(g.iter().map(|v| (v * unit.conj()).re));
            if parts[start..].iter().all(|&v| v == 0.0) {
                parts.truncate(start);
            } else {
                units.push(unit);
            }
        }
        if units.is_empty() {
            return Ok(());
        }
        let [first, second] = self.images(kept, &parts, units.len())?;
        for (c, unit) in units.iter().enumerate() {
            let (a, b) = (&first[c * n..(c + 1) * n], &second[c * n..(c + 1) * n]);
            for (xi, (a, b)) in x.iter_mut().zip(a.iter().zip(b)) {
                *xi += unit * (a + w2 * b);
            }
        }
        Ok(())
    }
}
