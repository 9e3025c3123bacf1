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

use std::f64::consts::PI;

use super::ellipse::{cell_on_ellipse, CellHarmonics};
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

/// Harmonics of a unit cell (k = 1, x = 1) on the ellipse (a, b).
pub fn unit_cell(a: f64, b: f64) -> CellHarmonics {
    let r = a.max(b);
    if r <= 1.0 {
        // Sticks from the virgin start: elastic.
        return CellHarmonics {
            c1: a,
            s1: 0.0,
            c2: 0.0,
            s2: b,
            energy: 0.0,
        };
    }
    if a == b {
        // Circle: |τ| = 1, leading u by β with cos β = 1/R.
        let cos_b = 1.0 / r;
        let sin_b = ((1.0 - cos_b) * (1.0 + cos_b)).sqrt();
        return CellHarmonics {
            c1: cos_b,
            s1: -sin_b,
            c2: sin_b,
            s2: cos_b,
            energy: 2.0 * PI * ((r - 1.0) * (r + 1.0)).sqrt(),
        };
    }
    if b == 0.0 {
        // Straight path: the 1D Jenkins loop, k* = (1/π)(β − ½ sin 2β), cos β = 1 − 2/A,
        // energy 4 (A − 1) (model.md §10).
        let cos_b = 1.0 - 2.0 / a;
        let beta = cos_b.acos();
        let energy = 4.0 * (a - 1.0);
        return CellHarmonics {
            c1: a * (beta - 0.5 * (2.0 * beta).sin()) / PI,
            s1: -energy / (PI * a),
            c2: 0.0,
            s2: 0.0,
            energy,
        };
    }
    if a == 0.0 {
        // Straight path along direction 2, u₂ = b cos(θ − π/2): the line's loop shifted.
        let line = unit_cell(b, 0.0);
        return CellHarmonics {
            c1: 0.0,
            s1: 0.0,
            c2: -line.s1,
            s2: line.c1,
            energy: line.energy,
        };
    }
    // Smallest radius of curvature of the path, at the ends of the major axis.
    let curvature_radius = a.min(b).powi(2) / r;
    if curvature_radius >= RIGID_RATIO || r >= RIGID_CAP {
        return rigid_plastic(a, b);
    }
    cell_on_ellipse(a, b).0
}

/// Above this ratio of the path's smallest radius of curvature, min(A₁, A₂)²/max(A₁, A₂),
/// to the cell's stretch at the limit x, a cell is taken as rigid–plastic (x → 0): its
/// force lags the velocity's direction by about x/ρ, so its harmonics err by O(1e-4).
pub const RIGID_RATIO: f64 = 1e4;
/// Above this ratio of the largest semi-axis to x, a cell is taken as rigid–plastic
/// whatever the path's shape (the time integration would need 2π·10⁷/0.5 steps per cycle);
/// the error is then O(x/ρ) of the path's smallest radius of curvature ρ.
pub const RIGID_CAP: f64 = 1e7;

/// A cell with x → 0 on the ellipse: it slides all the time with its force (|τ| = 1 in
/// units of f, here x = 1 scaling) along the velocity; energy = f × perimeter. The smooth
/// periodic integrands are summed by the trapezoidal rule with enough points to resolve
/// the turn of the velocity at the ends of the major axis (width ≈ minor/major in θ).
pub(crate) fn rigid_plastic(a: f64, b: f64) -> CellHarmonics {
    let flat = a.min(b) / a.max(b);
    let n = ((64.0 / flat).ceil() as usize).clamp(4096, 1 << 20);
    let h = 2.0 * PI / n as f64;
    let mut acc = CellHarmonics {
        c1: 0.0,
        s1: 0.0,
        c2: 0.0,
        s2: 0.0,
        energy: 0.0,
    };
    for j in 0..n {
        let (s, c) = (j as f64 * h).sin_cos();
        let v = [-a * s, b * c];
        let speed = v[0].hypot(v[1]);
        if speed == 0.0 {
            continue;
        }
        let t = [v[0] / speed, v[1] / speed];
        acc.c1 += t[0] * c;
        acc.s1 += t[0] * s;
        acc.c2 += t[1] * c;
        acc.s2 += t[1] * s;
        // Scaled by the major semi-axis: n × a alone overflows for a ≈ 1e305.
        acc.energy += speed / a.max(b);
    }
    CellHarmonics {
        c1: acc.c1 * h / PI,
        s1: acc.s1 * h / PI,
        c2: acc.c2 * h / PI,
        s2: acc.s2 * h / PI,
        energy: acc.energy * h * a.max(b),
    }
}
