//! A lumped system: dense M, D, K, its loads and its nonlinear elements (contact points
//! of the library and cubic springs) between DOFs or to ground. Built from a scene by
//! `model::lumped` (mass bodies, `[[matrices]]`, springs, joints) or by reducing an FE
//! scene (`backbone::fe`); balanced by `mhb`, followed by `backbone`.

use nalgebra::{DMatrix, DVector};

use crate::capi::{Contact3, Tangential};

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

/// Weighted DOFs (index, weight) whose sum is one relative displacement component.
pub type Row = Vec<(usize, f64)>;

/// One three-direction point between DOFs of a system (or them and the ground).
#[derive(Debug, Clone, PartialEq)]
pub struct Element3 {
    /// Rows of u₁, u₂ and the opening g (length); an empty normal row keeps h at
    /// [`Element3::gap`] (a constant normal force: the normal direction is then linear,
    /// outside the point).
    pub rows: [Row; 3],
    pub contact: Contact3,
    /// Overclosure g₀ at x = 0 (length).
    pub gap: f64,
    /// Both tangential directions under one circular slip limit; false: each direction
    /// its own point, the two sharing h (`mhb::contact3d::step`).
    pub coupled: bool,
}

impl Element3 {
    /// A coupled point on a body's DOFs (t₁, t₂, n) against a rigid plane.
    pub fn on_plane(dofs: [usize; 3], contact: Contact3, gap: f64) -> Self {
        Element3 {
            rows: dofs.map(|d| vec![(d, 1.0)]),
            contact,
            gap,
            coupled: true,
        }
    }

    /// The point's displacement (u₁, u₂, h) at the system displacements `y`.
    pub fn displacement(&self, y: &[f64]) -> [f64; 3] {
        let sum = |r: &Row| r.iter().map(|&(d, w)| w * y[d]).sum::<f64>();
        [
            sum(&self.rows[0]),
            sum(&self.rows[1]),
            self.gap - sum(&self.rows[2]),
        ]
    }

    /// Adds the point's internal forces (F₁, F₂, N) to `out` (per DOF).
    pub fn add_internal(&self, force: [f64; 3], out: &mut [f64]) {
        for (a, row) in self.rows.iter().enumerate() {
            for &(d, w) in row {
                out[d] += SIGN[a] * w * force[a];
            }
        }
    }
}

/// Sign of ∂u_a/∂(row sum) per component (u₁, u₂: +; h = g₀ − g: −).
pub const SIGN: [f64; 3] = [1.0, 1.0, -1.0];

/// A lumped system (M, D, K, loads and its 1D elements as [`System`]) with
/// three-direction points.
#[derive(Debug, Clone)]
pub struct System3 {
    pub linear: System,
    pub elements: Vec<Element3>,
}

impl System3 {
    /// The stiffness of `sys` with its 1D elements and points stuck and closed, and its
    /// constant load with the normal springs' preloads k_N·g₀ (the static step's stuck
    /// system; `mhb::contact3d::Hb3::stuck_start`).
    pub fn stuck(&self) -> (DMatrix<f64>, DVector<f64>) {
        let sys = self;
        let s = &sys.linear;
        let mut k = s.stuck_stiffness();
        let mut f0 = DVector::from_column_slice(&s.f0);
        for e in &sys.elements {
            for (a, row) in e.rows.iter().enumerate() {
                let kk = if a == 2 {
                    e.contact.k_n
                } else {
                    e.contact.k_t0
                };
                for &(p, wp) in row {
                    for &(q, wq) in row {
                        k[(p, q)] += kk * wp * wq;
                    }
                    if a == 2 {
                        f0[p] += e.contact.k_n * e.gap * wp;
                    }
                }
            }
        }
        (k, f0)
    }
}
