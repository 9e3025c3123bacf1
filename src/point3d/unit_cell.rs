//! The unit Jenkins cell (stiffness 1, stretch at the limit x = 1) on the elliptic path
//! (a cos θ, b sin θ): its first harmonics and energy per cycle, in closed form for the
//! stuck cell, the circle and the straight path, by time integration otherwise
//! (`ellipse.rs`), rigid–plastic for very thin or very large paths (docs/contact3d.md §4).
//! The describing function sums it over a point's cells; the table interpolates it.

use std::f64::consts::PI;

use super::ellipse::{cell_on_ellipse, CellHarmonics};

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
