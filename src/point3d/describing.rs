//! First-order describing function of the coupled tangential element at constant normal
//! load, for the elliptic slip path u(t) = (A₁ cos ωt, A₂ sin ωt) in the element's principal
//! axes (docs/contact3d.md §4). Per direction j, with the force's first harmonic
//! t̂ⱼ = (k*ⱼ + iωd*ⱼ) ûⱼ:
//!
//! * k*ⱼ: the in-phase first-harmonic coefficient (first-order harmonic balance, (3.8));
//! * d*ⱼ: the quadrature coefficient, equal to the energy the direction takes per cycle
//!   over π ω Aⱼ², the energy balance (3.14) per direction.
//!
//! A circle (A₁ = A₂ = R) has a closed form per Jenkins cell (stiffness k, stretch at the
//! limit x = f/k): below R = x the cell sticks; above it the force has magnitude f and leads
//! the displacement by β, cos β = x/R, so k* = k x²/R², ωd* = k (x/R)√(1 − x²/R²) and the
//! energy per cycle is 2π f √(R² − x²) (the slider runs on a circle of radius √(R² − x²)).
//! A straight path (A₂ = 0) is the 1D Jenkins loop of model.md §10. Any other ellipse is
//! integrated in time (`ellipse.rs`). The point's coefficients are the sum over its
//! cells.

use super::ellipse::CellHarmonics;
pub use super::unit_cell::{unit_cell, RIGID_RATIO};
use super::Contact3d;
use crate::error::{finite, Error};
use crate::linearize::Regime;

/// The linearized coupled element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Describing3d {
    /// Equivalent stiffness per direction (force/length).
    pub k_star: [f64; 2],
    /// Equivalent viscous damping per direction (force·time/length), (3.14).
    pub d_star: [f64; 2],
    /// Energy dissipated per cycle by the whole point (force × length).
    pub energy_per_cycle: f64,
    pub regime: Regime,
}

/// Describes the point for amplitudes A₁, A₂ ≥ 0 (length) at the constant normal force
/// `normal_force` (force; ≤ 0 is open: everything 0) and angular frequency ω > 0. A
/// direction with zero amplitude while the other moves has no first harmonic to balance and
/// gets k* = d* = 0 (its value for a vanishing minor axis is a perturbation result not
/// computed here); with both zero the point sticks (k* = k_T0).
pub fn describe(
    contact: &Contact3d,
    normal_force: f64,
    amplitude: [f64; 2],
    omega: f64,
) -> Result<Describing3d, Error> {
    describe_with(contact, normal_force, amplitude, omega, Method::Integrated)
}

/// How a cell's harmonics are obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Closed forms, or the cycle integrated in time ([`unit_cell`]): the reference,
    /// 0.1–0.5 s per 32-cell point.
    Integrated,
    /// Interpolated from the unit cell's table ([`super::table`]): microseconds per point,
    /// force harmonics within [`super::table::TABLE_TOLERANCE`] of each cell's limit force.
    Tabulated,
}

/// [`describe`] with the cells' harmonics by `method`.
pub fn describe_with(
    contact: &Contact3d,
    normal_force: f64,
    amplitude: [f64; 2],
    omega: f64,
    method: Method,
) -> Result<Describing3d, Error> {
    contact.validate()?;
    finite(normal_force, "normal force")?;
    finite(omega, "omega")?;
    for a in amplitude {
        finite(a, "amplitude")?;
        if a < 0.0 {
            return Err(Error::OutOfRange("amplitude must be >= 0"));
        }
    }
    if omega <= 0.0 {
        return Err(Error::OutOfRange("omega must be > 0"));
    }
    let limit = contact.mu * normal_force;
    if !limit.is_finite() {
        return Err(Error::Overflow("friction limit mu N"));
    }
    if limit <= 0.0 {
        return Ok(Describing3d {
            k_star: [0.0; 2],
            d_star: [0.0; 2],
            energy_per_cycle: 0.0,
            regime: Regime::Open,
        });
    }
    let k0 = contact.k_t0;
    if amplitude[0].max(amplitude[1]) < f64::MIN_POSITIVE {
        return Ok(Describing3d {
            k_star: [k0; 2],
            d_star: [0.0; 2],
            energy_per_cycle: 0.0,
            regime: Regime::Stick,
        });
    }
    let (main, slipping) = harmonics(contact, limit, amplitude, method);
    let mut k_star = [0.0; 2];
    let mut q = [0.0; 2]; // ω d*
                          // u₁ = A₁ cos θ: k*₁ = c₁/A₁, ωd*₁ = −s₁/A₁; u₂ = A₂ sin θ: k*₂ = s₂/A₂, ωd*₂ = c₂/A₂.
                          // A direction that does not move has no first harmonic to balance: 0.
    if amplitude[0] > 0.0 {
        (k_star[0], q[0]) = (main.c1 / amplitude[0], -main.s1 / amplitude[0]);
    }
    if amplitude[1] > 0.0 {
        (k_star[1], q[1]) = (main.s2 / amplitude[1], main.c2 / amplitude[1]);
    }
    let d_star = [q[0].max(0.0) / omega, q[1].max(0.0) / omega];
    if d_star.iter().chain(&k_star).any(|v| !v.is_finite()) {
        return Err(Error::Overflow("d* (amplitude or omega too small)"));
    }
    let n = contact.cell_count();
    let regime = match slipping {
        0 => Regime::Stick,
        s if s < n => Regime::Microslip,
        _ => Regime::Sliding,
    };
    Ok(Describing3d {
        k_star,
        d_star,
        energy_per_cycle: main.energy.max(0.0),
        regime,
    })
}

/// Sum over the cells of the force harmonics (force units) and of the energy, and the
/// number of cells that slip.
fn harmonics(
    contact: &Contact3d,
    limit: f64,
    amplitude: [f64; 2],
    method: Method,
) -> (CellHarmonics, usize) {
    let unit = match method {
        Method::Integrated => unit_cell,
        Method::Tabulated => super::table::unit_cell_tabulated,
    };
    let cells = contact.cells();
    let mut sum = CellHarmonics {
        c1: 0.0,
        s1: 0.0,
        c2: 0.0,
        s2: 0.0,
        energy: 0.0,
    };
    let mut slipping = 0;
    for i in 0..cells.n {
        let k = contact.k_t0 * cells.stiffness[i];
        let x = limit * cells.strength[i] / k;
        let (a, b) = (amplitude[0] / x, amplitude[1] / x);
        let h = unit(a, b);
        if h.energy > 0.0 {
            slipping += 1;
        }
        let f = k * x;
        sum.c1 += f * h.c1;
        sum.s1 += f * h.s1;
        sum.c2 += f * h.c2;
        sum.s2 += f * h.s2;
        sum.energy += f * x * h.energy;
    }
    (sum, slipping)
}
