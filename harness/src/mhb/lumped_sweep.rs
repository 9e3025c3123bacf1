//! One frequency of a lumped scene's sweep ([`crate::model::lumped::Lumped`]), each
//! continued from the last: the thesis's first-order method ([`super::first_order`]),
//! the multi-harmonic balance ([`super::Hb`]) or, with three-direction points, its
//! balance with them ([`super::contact3d::Hb3`]; a frequency that does not converge from
//! the last solution or the stuck response is reached by ramping the load,
//! [`super::contact3d::solve_ramped`]).

use nalgebra::Complex;

use super::contact3d::{solve_ramped, Hb3, System3};
use super::{first_order, Hb, Law, MhbError, NewtonOptions};
use crate::capi;
use crate::model::lumped::Lumped;

type C64 = Complex<f64>;

/// Load steps of the ramp when the balance with points fails from its starts.
const RAMP_STEPS: usize = 10;

/// One frequency's solution.
#[derive(Debug, Clone)]
pub struct Solved {
    /// First-harmonic complex amplitude per DOF (x(t) = Re(x̂ e^{iωt})).
    pub x: Vec<C64>,
    /// First-harmonic amplitude of each 1D element's relative displacement (length).
    pub elements: Vec<f64>,
    /// Energy dissipated per cycle by each 1D element (force·length).
    pub element_energy: Vec<f64>,
    /// Per three-direction point: first-harmonic amplitudes of u₁, u₂ (length), energy
    /// per cycle (force·length), smallest and largest normal force (force).
    pub points: Vec<PointResult>,
    /// Harmonic balance: every coefficient, DOF-major (2H + 1 per DOF).
    pub coefficients: Option<Vec<f64>>,
}

/// One three-direction point's result at a frequency.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointResult {
    pub amplitude: [f64; 2],
    pub energy: f64,
    pub normal_range: (f64, f64),
}

/// The sweep's solver and the state it continues from.
pub enum Sweep<'a> {
    FirstOrder {
        l: &'a Lumped,
        /// The last element amplitudes.
        a0: Vec<f64>,
    },
    Balance {
        hb: Hb<'a>,
        last: Option<Vec<f64>>,
    },
    Points {
        sys: &'a System3,
        hb: Hb3<'a>,
        h: usize,
        n: usize,
        last: Option<Vec<f64>>,
    },
}

impl<'a> Sweep<'a> {
    /// The solver of `l`: first order without `harmonic`, else the balance at (H, N),
    /// with the points of `sys` (`l`'s system with its points, [`Lumped::system3`]).
    pub fn new(l: &'a Lumped, sys: &'a System3, harmonic: Option<(usize, usize)>) -> Self {
        match harmonic {
            None => Sweep::FirstOrder {
                l,
                a0: vec![0.0; l.system.elements.len()],
            },
            Some((h, n)) if sys.elements.is_empty() => Sweep::Balance {
                hb: Hb::new(&sys.linear, h, n),
                last: None,
            },
            Some((h, n)) => Sweep::Points {
                sys,
                hb: Hb3::new(sys, h, n),
                h,
                n,
                last: None,
            },
        }
    }

    /// Solves at ω (rad per time unit).
    pub fn solve(&mut self, omega: f64) -> Result<Solved, MhbError> {
        let opt = NewtonOptions::default();
        match self {
            Sweep::FirstOrder { l, a0 } => {
                let sys = &l.system;
                let x = first_order::solve(sys, omega, a0)?;
                *a0 = first_order::element_amplitudes(sys, &x);
                let element_energy = sys
                    .elements
                    .iter()
                    .zip(a0.iter())
                    .map(|(e, &a)| match e.law {
                        Law::Point(t) => capi::linearize(&t, a, omega)
                            .map(|l| l.energy_per_cycle)
                            .map_err(|e| MhbError::Aft(e.into())),
                        Law::Cubic(_) => Ok(0.0),
                    })
                    .collect::<Result<_, _>>()?;
                Ok(Solved {
                    x,
                    elements: a0.clone(),
                    element_energy,
                    points: Vec::new(),
                    coefficients: None,
                })
            }
            Sweep::Balance { hb, last } => {
                let sol = match last.as_ref().map(|u| hb.solve(u, omega, opt)) {
                    Some(Ok(sol)) => sol,
                    _ => {
                        let start = hb.stuck_start(omega);
                        hb.solve(&start, omega, opt).inspect_err(|_| *last = None)?
                    }
                };
                *last = Some(sol.u.clone());
                Ok(balance_result(
                    hb.sys,
                    hb.h(),
                    sol.u,
                    sol.dissipated,
                    Vec::new(),
                ))
            }
            Sweep::Points {
                sys,
                hb,
                h,
                n,
                last,
            } => {
                let sol = match last.as_ref().map(|u| hb.solve(u, omega, opt)) {
                    Some(Ok(sol)) => sol,
                    _ => match hb.solve(&hb.stuck_start(omega), omega, opt) {
                        Ok(sol) => sol,
                        Err(_) => solve_ramped(sys, *h, *n, omega, RAMP_STEPS, opt)
                            .inspect_err(|_| *last = None)?,
                    },
                };
                *last = Some(sol.u.clone());
                let points = sys
                    .elements
                    .iter()
                    .enumerate()
                    .map(|(k, e)| PointResult {
                        amplitude: [
                            hb.component_amplitude(&sol.u, e, 0),
                            hb.component_amplitude(&sol.u, e, 1),
                        ],
                        energy: sol.dissipated[k],
                        normal_range: sol.normal_range[k],
                    })
                    .collect();
                Ok(balance_result(
                    &sys.linear,
                    *h,
                    sol.u,
                    sol.element_dissipated,
                    points,
                ))
            }
        }
    }
}

/// A balance's solution `u` at H harmonics as [`Solved`].
fn balance_result(
    sys: &super::System,
    h: usize,
    u: Vec<f64>,
    element_energy: Vec<f64>,
    points: Vec<PointResult>,
) -> Solved {
    let m = 2 * h + 1;
    let first = |c: &dyn Fn(usize) -> f64| C64::new(c(1), -c(2));
    let x = (0..sys.n()).map(|d| first(&|c| u[d * m + c])).collect();
    let elements = sys
        .elements
        .iter()
        .map(|e| first(&|c| u[e.i * m + c] - e.j.map_or(0.0, |j| u[j * m + c])).norm())
        .collect();
    Solved {
        x,
        elements,
        element_energy,
        points,
        coefficients: Some(u),
    }
}
