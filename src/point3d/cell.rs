//! One Jenkins cell in the tangent plane: a spring of stiffness k in series with a Coulomb
//! slider whose limit is a circle, |t| ≤ f (docs/contact3d.md §2). The cell is moved along a
//! straight segment Δu of the tangential displacement and its force follows the exact
//! solution of the rate equations on that segment, so a step's result does not depend on
//! how a straight segment is subdivided:
//!
//! * stick: ṫ = k u̇ while |t| < f (2.38 in the plane);
//! * slip: |t| = f and t·u̇ > 0; the slider moves along t (associated flow, Coulomb's law
//!   (2.39) with a circular limit): ṫ = k (u̇ − (t̂·u̇) t̂). On a straight segment the angle ψ
//!   between t and the direction d of motion then obeys dψ/ds = −sin ψ / x (x = f/k, s the
//!   arc length), i.e. tan(ψ/2) = tan(ψ₀/2) e^{−s/x}, and the slider travels
//!   ∫cos ψ ds = s − x ln[(1 + T₀²)/(1 + T₀² e^{−2s/x})], T₀ = tan(ψ₀/2).
//!
//! A limit that fell below |t| (the normal load dropped) first returns t radially to the new
//! circle at fixed displacement; the elastic energy released, (|t|² − f²)/(2k), is dissipated.

/// Force of a cell after a step and what happened on the way.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellStep {
    /// Spring force at the end of the segment (force units, in the tangent plane).
    pub force: [f64; 2],
    /// Energy dissipated by the slider on the way (≥ 0, force × length).
    pub dissipated: f64,
    /// Whether the slider moved (slip during the segment or a radial return).
    pub slipped: bool,
    /// Whether the step ends slipping (on the circle, the last part of the segment in
    /// slip, or a radial return at zero increment): the end state's tangent is then the
    /// slip tangent k(I − t̂t̂ᵀ), else k I. A radial return followed by elastic motion back
    /// inside has slipped but ends sticking.
    pub sliding: bool,
    /// Whether the step began with a radial return (the limit fell below |t|): the end
    /// force then depends on the limit through the returned force, ∂t/∂f = t̂ at the start.
    pub returned: bool,
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// Moves a cell of stiffness `k` (> 0) and slip limit `limit` (≥ 0) with force `force` along
/// the displacement increment `du`. A zero limit carries no force (the slider follows the
/// displacement).
pub fn advance(force: [f64; 2], k: f64, limit: f64, du: [f64; 2]) -> CellStep {
    let x = limit / k; // the spring's stretch at the limit (length)
    if x.is_nan() || x <= 0.0 {
        // Open contact or no friction: the slider follows, stored energy is released.
        let t2 = dot(force, force);
        return CellStep {
            force: [0.0, 0.0],
            dissipated: t2 / (2.0 * k),
            slipped: t2 > 0.0,
            sliding: false,
            returned: false,
        };
    }
    let mut t = force;
    let mut dissipated = 0.0;
    let mut slipped = false;
    let mag = norm(t);
    let returned = mag > limit;
    if returned {
        // Radial return to the smaller circle at fixed displacement.
        dissipated += (mag - limit) * (mag + limit) / (2.0 * k);
        t = [t[0] / mag * limit, t[1] / mag * limit];
        slipped = true;
    }
    let len = norm(du);
    if len == 0.0 {
        return CellStep {
            force: t,
            dissipated,
            slipped,
            sliding: slipped,
            returned,
        };
    }
    let d = [du[0] / len, du[1] / len];
    // Elastic stretch s₁ (length) until |t + k s d| = f: k s₁ = −b + √(b² − c),
    // b = t·d, c = |t|² − f² ≤ 0, in the form without cancellation.
    let b = dot(t, d);
    let c = ((norm(t) - limit) * (norm(t) + limit)).min(0.0);
    let root = (b * b - c).sqrt();
    let ks1 = if b <= 0.0 { root - b } else { -c / (b + root) };
    if ks1 >= k * len {
        let mut end = [t[0] + k * du[0], t[1] + k * du[1]];
        let m = norm(end);
        if m > limit {
            end = [end[0] / m * limit, end[1] / m * limit]; // rounding only
        }
        return CellStep {
            force: end,
            dissipated,
            slipped,
            sliding: false,
            returned,
        };
    }
    // Slip from the entry point T₁ (|T₁| = f) over the remaining length r.
    let s1 = ks1 / k;
    let r = len - s1;
    let entry = [t[0] + ks1 * d[0], t[1] + ks1 * d[1]];
    let along = dot(entry, d);
    let perp = [entry[0] - along * d[0], entry[1] - along * d[1]];
    let perp_len = norm(perp);
    let cos0 = (along / limit).clamp(0.0, 1.0);
    let sin0 = (perp_len / limit).clamp(0.0, 1.0);
    let t0 = sin0 / (1.0 + cos0); // tan(ψ₀/2) ∈ [0, 1]
    let decay = (-r / x).exp();
    let t_end = t0 * decay;
    // cos ψ, sin ψ from tan(ψ/2) without trigonometric round trips.
    let q = t_end * t_end;
    let cos_end = (1.0 - q) / (1.0 + q);
    let sin_end = 2.0 * t_end / (1.0 + q);
    let n = if perp_len > 0.0 {
        [perp[0] / perp_len, perp[1] / perp_len]
    } else {
        [0.0, 0.0]
    };
    let end = [
        limit * (cos_end * d[0] + sin_end * n[0]),
        limit * (cos_end * d[1] + sin_end * n[1]),
    ];
    // Slider travel r − x ln[(1 + T₀²)/(1 + T₀² e^{−2r/x})] (≥ 0 because ψ ≤ π/2).
    let travel = (r - x * ((t0 * t0).ln_1p() - (q).ln_1p())).max(0.0);
    dissipated += limit * travel;
    CellStep {
        force: end,
        dissipated,
        slipped: true,
        sliding: true,
        returned,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_motion_is_the_one_dimensional_jenkins_element() {
        // k = 100, f = 2 (x = 0.02): stretch 0.05 from rest: slips 0.03 at force 2.
        let s = advance([0.0, 0.0], 100.0, 2.0, [0.05, 0.0]);
        assert_eq!(s.force, [2.0, 0.0]);
        assert!((s.dissipated - 2.0 * 0.03).abs() < 1e-15);
        // Reversal: elastic back by 0.04 (force −2 reached at 0.04), then slides 0.01.
        let s2 = advance(s.force, 100.0, 2.0, [-0.05, 0.0]);
        assert_eq!(s2.force, [-2.0, 0.0]);
        assert!((s2.dissipated - 2.0 * 0.01).abs() < 1e-15);
        // Inside the limit: elastic, nothing lost.
        let s3 = advance([0.5, -0.5], 100.0, 2.0, [0.001, 0.002]);
        assert_eq!((s3.dissipated, s3.slipped), (0.0, false));
        assert!((s3.force[0] - 0.6).abs() < 1e-15 && (s3.force[1] + 0.3).abs() < 1e-15);
    }

    #[test]
    fn sideways_motion_turns_the_force_toward_the_motion() {
        // At the limit along +e₁, moved along +e₂ by s: tan(ψ/2) = e^{−s/x} (ψ₀ = π/2).
        let (k, f) = (10.0, 1.0); // x = 0.1
        let s = 0.07;
        let r = advance([f, 0.0], k, f, [0.0, s]);
        let psi = 2.0 * (-s / 0.1_f64).exp().atan();
        assert!((r.force[1] - f * psi.cos()).abs() < 1e-15);
        assert!((r.force[0] - f * psi.sin()).abs() < 1e-15);
        // Travel s − x ln(2 / (1 + e^{−2s/x})).
        let travel = s - 0.1 * (2.0 / (1.0 + (-2.0 * s / 0.1_f64).exp())).ln();
        assert!((r.dissipated - f * travel).abs() < 1e-15);
        // Subdividing a straight segment does not change the result.
        let mut t = [f, 0.0];
        let mut diss = 0.0;
        for _ in 0..7 {
            let p = advance(t, k, f, [0.0, s / 7.0]);
            t = p.force;
            diss += p.dissipated;
        }
        assert!((t[0] - r.force[0]).abs() < 1e-14 && (t[1] - r.force[1]).abs() < 1e-14);
        assert!((diss - r.dissipated).abs() < 1e-14);
    }

    #[test]
    fn a_lower_limit_returns_the_force_radially_and_a_zero_limit_releases_it() {
        let r = advance([3.0, 4.0], 10.0, 2.5, [0.0, 0.0]);
        assert!((r.force[0] - 1.5).abs() < 1e-15 && (r.force[1] - 2.0).abs() < 1e-15);
        assert!((r.dissipated - (25.0 - 6.25) / 20.0).abs() < 1e-15);
        let open = advance([3.0, 4.0], 10.0, 0.0, [1.0, 0.0]);
        assert_eq!(open.force, [0.0, 0.0]);
        assert!((open.dissipated - 25.0 / 20.0).abs() < 1e-15);
        let tiny = advance([0.0, 0.0], 10.0, 1e-310, [1.0, 1.0]);
        assert!(tiny
            .force
            .iter()
            .all(|v| v.is_finite() && v.abs() <= 1e-310));
    }
}
