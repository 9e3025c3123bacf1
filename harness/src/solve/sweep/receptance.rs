//! The linear part condensed onto the contact directions and the outputs, from one
//! factorization of S = K + K_c − ω²M + iωD: with B the contact map (rows: relative
//! tangential displacements) and C the output map,
//!
//!   G = B S⁻¹ Bᵀ (m × m receptance),   O = C S⁻¹ Bᵀ (outputs per unit contact force),
//!
//! column by column (m solves), and the load's images r₀ = B S⁻¹ f̂, y₀ = C S⁻¹ f̂.
//! Used by the fast sweep (one S per frequency) and the harmonic balance (one S per
//! harmonic h·ω). Memory O(n + m² + m·outputs).

use super::C64;
use crate::model::Output;
use crate::solve::umfpack::{Numeric, UmfpackError};

/// Condensed receptances of one factorization.
#[derive(Debug, Clone)]
pub struct Receptance {
    /// Contact directions m.
    pub m: usize,
    /// G, column-major m × m: G[k + m·j] = relative displacement k per unit force pair j.
    pub g: Vec<C64>,
    /// O, column-major outputs × m.
    pub o: Vec<C64>,
    /// r₀ = B S⁻¹ f̂ (length m) and y₀ = C S⁻¹ f̂ (one per output).
    pub r0: Vec<C64>,
    pub y0: Vec<C64>,
    b: Vec<C64>,
    /// S⁻¹ f̂ after [`Receptance::load`] (then scratch of [`Receptance::condense`]).
    pub x: Vec<C64>,
}

impl Receptance {
    /// Scratch for n free DOFs, m contact directions and `nout` outputs.
    pub fn new(n: usize, m: usize, nout: usize) -> Self {
        let z = C64::new(0.0, 0.0);
        Receptance {
            m,
            g: vec![z; m * m],
            o: vec![z; nout * m],
            r0: vec![z; m],
            y0: vec![z; nout],
            b: vec![z; n],
            x: vec![z; n],
        }
    }

    /// r₀ and y₀ for the load `f` (one solve).
    pub fn load<'r>(
        &mut self,
        num: &Numeric,
        f: &[C64],
        row: &dyn Fn(usize) -> &'r [(usize, f64)],
        outputs: &[Output],
    ) -> Result<(), UmfpackError> {
        num.solve_into(f, &mut self.x)?;
        for j in 0..self.m {
            self.r0[j] = row(j).iter().map(|&(i, w)| self.x[i] * w).sum();
        }
        for (k, out) in outputs.iter().enumerate() {
            self.y0[k] = out.value(&self.x);
        }
        Ok(())
    }

    /// G and O (m solves), `row(j)` the sparse row of contact direction j.
    pub fn condense<'r>(
        &mut self,
        num: &Numeric,
        row: &dyn Fn(usize) -> &'r [(usize, f64)],
        outputs: &[Output],
    ) -> Result<(), UmfpackError> {
        let (m, nout) = (self.m, outputs.len());
        for j in 0..m {
            for &(i, w) in row(j) {
                self.b[i] = C64::new(w, 0.0);
            }
            num.solve_into(&self.b, &mut self.x)?;
            for &(i, _) in row(j) {
                self.b[i] = C64::new(0.0, 0.0);
            }
            for k in 0..m {
                self.g[k + m * j] = row(k).iter().map(|&(i, w)| self.x[i] * w).sum();
            }
            for (k, out) in outputs.iter().enumerate() {
                self.o[k + nout * j] = out.value(&self.x);
            }
        }
        Ok(())
    }
}
