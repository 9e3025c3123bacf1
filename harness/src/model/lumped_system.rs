//! A lumped system: dense M, D, K, its loads and its nonlinear elements (contact points
//! of the library and cubic springs) between DOFs or to ground. Built from a scene by
//! `model::lumped` (mass bodies, `[[matrices]]`, springs, joints) or by reducing an FE
//! scene (`backbone::fe`); balanced by `mhb`, followed by `backbone`.

use nalgebra::DMatrix;

use crate::capi::Tangential;

/// The nonlinear force law of an element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Law {
    /// A contact point of the library (tangential direction), marched through the C API.
    Point(Tangential),
    /// Cubic spring F = k₃ δ³ (the Duffing oscillator's term; thesis (4.1)).
    Cubic(f64),
}

/// One nonlinear element between DOF `i` and DOF `j` (`None`: ground); its force acts
/// with + on i and − on j.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    pub i: usize,
    pub j: Option<usize>,
    pub law: Law,
}

/// A lumped system: dense M, D, K (n × n), first-harmonic load f̂ (f(t) = f₀ +
/// Re(f̂ e^{iωt}) = f₀ + f̂.re cos ωt − f̂.im sin ωt) and elements.
#[derive(Debug, Clone)]
pub struct System {
    pub m: DMatrix<f64>,
    pub d: DMatrix<f64>,
    pub k: DMatrix<f64>,
    pub f0: Vec<f64>,
    pub f1: Vec<nalgebra::Complex<f64>>,
    pub elements: Vec<Element>,
}

impl System {
    pub fn n(&self) -> usize {
        self.k.nrows()
    }

    /// K with every contact element stuck: its k_T0 between its DOFs (thesis (2.46)). An
    /// open (F_N ≤ 0) or frictionless point carries no stuck stiffness (it transmits no
    /// tangential force), and a cubic spring adds nothing at zero amplitude.
    pub fn stuck_stiffness(&self) -> DMatrix<f64> {
        let mut k = self.k.clone();
        for e in &self.elements {
            let Law::Point(t) = e.law else { continue };
            if t.normal <= 0.0 || t.mu <= 0.0 {
                continue;
            }
            k[(e.i, e.i)] += t.k_t0;
            if let Some(j) = e.j {
                k[(j, j)] += t.k_t0;
                k[(e.i, j)] -= t.k_t0;
                k[(j, e.i)] -= t.k_t0;
            }
        }
        k
    }
}
