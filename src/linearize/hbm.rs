//! Equivalent stiffness k* by first-order harmonic balance (3.5–3.8) of the loop's
//! Ersatzfunktion (4.3). For the mean of the two branches (odd after the shift of
//! Fig. 4.9), b₁ = (2/π) ∫_{−π/2}^{π/2} f_L(A sin θ) sin θ dθ, so k* = b₁/A = 2S/(πA) with
//! S = ∫ f_L(A sin θ) sin θ dθ = −∫₀^π f_L cos φ dφ (φ = θ + π/2).

use super::loop_shape::LoopShape;
use super::quadrature::{gauss, simpson_or_gauss};
use crate::hysteresis::Rule;
use crate::law::Backbone;
use crate::wide::Wide;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Longest Gauss panel in the sinh/cosh-stretched variable w: the integrand grows like
/// e^{4w} and, in stick, has branch points at w = ±iπ/2; with half-length 0.5 those lie on
/// a Bernstein ellipse of ρ ≈ 6.4.
const W_PANEL: f64 = 1.0;

/// k* = 2S/(πA) (3.8).
pub fn k_star_from_sum(sum: f64, amplitude: f64) -> f64 {
    2.0 * sum / (PI * amplitude) // (3.8) with b₁ from (3.7)
}

/// Smallest A/δ* for which [`stiffness_ratio_sliding`] is used: from there on its
/// integrands' nearest singularity (u = 2A/δ*) lies ≥ 8 times beyond the branch's
/// non-sliding part, so 16 Gauss points are exact to rounding.
pub const TANGENT_FORM_FROM: f64 = 8.0;

/// k*/k_T0 of a sliding loop of half-width a = A/δ* ≥ [`TANGENT_FORM_FROM`] (normalized
/// backbone: μF_N = 1, δ* = 1), from S integrated by parts:
/// S = A ∫ f_L'(A sin θ) cos²θ dθ, so that with the drop Δ = u δ* from the tip
/// k*/k_T0 = (2/π) a^{−3/2} ∫ τ(u) √(u (2 − u/a)) du, τ = f_L'/k_T0 ∈ [0, 1] the tangent
/// along the branch (1 on the elastic line, √(1 − s/δ*) on the Mindlin part (2.48), 0
/// while sliding). Every term is ≥ 0, so k* ∝ a^{−3/2} keeps its digits where the
/// pieces of [`in_phase_sum_graded`] (each ∝ a^{−1/2}) cancel (relative error ≈ 1e-16 a).
pub fn stiffness_ratio_sliding(b: &Backbone, rule: Rule, a: f64) -> Wide {
    const N: usize = 16;
    let root = |u: f64| (u * (2.0 - u / a)).sqrt();
    // Elastic line u ∈ [0, e], u = t²: ∫ 2t √(t² (2 − t²/a)) dt.
    let elastic = |e: f64| gauss(N, 0.0, e.sqrt(), |t| 2.0 * t * root(t * t));
    let integral = match (b, rule) {
        // Spring then slider, both rules: elastic through Δ = 2δ*.
        (Backbone::Jenkins(_), _) => elastic(2.0),
        // Elastic through F̂/k_T0 = δ*/1.5 (F̂ = μF_N), then the virgin curve from zero
        // force: s = u − e ∈ [0, 1], τ = √(1 − s) = w, u = e + 1 − w².
        (Backbone::Mindlin(_), Rule::Thesis) => {
            let e = 1.0 / 1.5;
            elastic(e) + gauss(N, 0.0, 1.0, |w| 2.0 * w * w * root(e + 1.0 - w * w))
        }
        // f_L = F̂ − 2g(Δ/2): τ = √(1 − u/2) on [0, 2]; u = 2 sin²ψ.
        (Backbone::Mindlin(_), Rule::Masing) => gauss(N, 0.0, PI / 2.0, |p| {
            let (sn, cs) = p.sin_cos();
            cs * root(2.0 * sn * sn) * 4.0 * sn * cs
        }),
    };
    Wide::new(2.0 * integral / PI) / (Wide::new(a) * a.sqrt())
}

/// S by plain quadrature in θ of the branch itself (the thesis's way with Simpson).
pub fn in_phase_sum_by_rule(
    b: &Backbone,
    rule: Rule,
    shape: &LoopShape,
    simpson_rule: bool,
    n: usize,
) -> f64 {
    let a = shape.amplitude;
    simpson_or_gauss(simpson_rule, n, -PI / 2.0, PI / 2.0, |t: f64| {
        shape.descending(b, rule, a * t.sin()) * t.sin()
    })
}

/// S split at the loop's kinks into closed-form pieces (sliding, elastic, constants) and
/// one Mindlin piece integrated by Gauss–Legendre in variables that remove its
/// (1 − σ)^{3/2} end behaviour. `points` per panel.
pub fn in_phase_sum_graded(b: &Backbone, rule: Rule, shape: &LoopShape, points: usize) -> f64 {
    let a = shape.amplitude;
    let limit = b.friction_limit();
    let k0 = b.k_t0();
    if let Backbone::Jenkins(j) = b {
        // Parallelogram loop: elastic over Δ ≤ 2δ*, sliding beyond; same for both rules.
        let d = j.slip_limit();
        if a <= d {
            return k0 * a * PI / 2.0;
        }
        let (z, y) = ((d / a).sqrt(), ((a - d) / a).sqrt());
        let eps = 2.0 * z.atan2(y);
        return limit * 2.0 * z * y + 0.5 * k0 * a * eps_minus_sin(eps);
    }
    let sliding = shape.slides();
    let (c, cms) = (shape.c, shape.c_minus_sigma_max);
    // Sliding onset (y_s, z_s) = (sin, cos)(φ_s/2), where σ = 1.
    let (y_s, z_s) = if sliding {
        (
            ((shape.sigma_max - 1.0) / c).sqrt(),
            ((cms + 1.0) / c).sqrt(),
        )
    } else {
        (0.0, 1.0)
    };
    let sin_phi_s = 2.0 * y_s * z_s;
    match rule {
        Rule::Thesis => {
            // End of the virgin part (σ = 0) and start of the elastic line (phase 3).
            let (y0, z0) = ((shape.sigma_max / c).sqrt(), (cms / c).sqrt());
            let eps0 = 2.0 * z0.atan2(y0);
            // Elastic piece: ∫ (F̂ − k_T0 Δ)(−cos φ) over [φ₀, π] = F̂ sin ε₀/2 + k_T0 A (ε₀ − sin ε₀)/2.
            let elastic =
                0.5 * shape.peak_force * 2.0 * z0 * y0 + 0.5 * k0 * a * eps_minus_sin(eps0);
            limit * sin_phi_s + elastic + limit * virgin_piece(shape, y_s, (y0, z0), points)
        }
        Rule::Masing => {
            // f_L = F_A − 2 μF_N G(σ) on [φ_s, π]; −μF_N on [0, φ_s].
            limit * sin_phi_s
                + shape.peak_force * sin_phi_s
                + 2.0 * limit * virgin_piece(shape, y_s, (1.0, 0.0), points)
        }
    }
}

/// J = ∫_{φ_s}^{φ_b} G(σ(φ)) cos φ dφ with G(σ) = 1 − (1 − σ)^{3/2} (2.49 normalized),
/// σ = σ_max − c y², y = sin(φ/2); the end (y_b, z_b) = (sin, cos)(φ_b/2).
///
/// Lower part (y ≤ y_split) in w with y = y_s cosh w (sliding: 1 − σ = c y_s² sinh²w) or
/// y = p sinh w (stick: 1 − σ = (1 − σ_max) cosh²w), which makes the integrand analytic at
/// the loop tip; upper part in z = cos(φ/2). Each part is cut into panels graded toward
/// the nearest singularity beyond its end (the y = 1 or z = 1 of dφ, or the sliding
/// onset), so every panel sees its nearest singularity at ≥ 3 half-lengths from its centre:
/// Gauss–Legendre then converges like 5.8^{−2n}.
fn virgin_piece(shape: &LoopShape, y_s: f64, end: (f64, f64), points: usize) -> f64 {
    let (sm, c, cms) = (shape.sigma_max, shape.c, shape.c_minus_sigma_max);
    let (y_b, z_b) = end;
    let sliding = shape.slides();
    let y_split = if sliding {
        FRAC_1_SQRT_2.max(0.5 * (1.0 + y_s))
    } else {
        FRAC_1_SQRT_2
    };
    let y_hi = y_split.min(y_b);
    let in_y = |y: f64, w: f64| {
        mindlin_g(sm - c * y * y, w) * (1.0 - 2.0 * y * y) * 2.0 / ((1.0 - y) * (1.0 + y)).sqrt()
    };
    let mut total = 0.0;
    if sliding {
        if y_hi > y_s {
            let (w_end, w_one) = ((y_hi / y_s).acosh(), (1.0 / y_s).acosh());
            total += graded(0.0, w_end, w_one - w_end, W_PANEL, points, |w| {
                let (sh, ch) = (w.sinh(), w.cosh());
                in_y(y_s * ch, c * y_s * y_s * sh * sh) * y_s * sh
            });
        }
    } else if sm < 1.0 {
        let gap = 1.0 - sm;
        let p = (gap / c).sqrt();
        let (w_end, w_one) = ((y_hi / p).asinh(), (1.0 / p).asinh());
        total += graded(0.0, w_end, w_one - w_end, W_PANEL, points, |w| {
            let (sh, ch) = (w.sinh(), w.cosh());
            in_y(p * sh, gap * ch * ch) * p * ch
        });
    } else {
        total += graded(0.0, y_hi, 1.0 - y_hi, f64::INFINITY, points, |y| {
            in_y(y, c * y * y)
        });
    }
    if y_b > y_split {
        let z_split = ((1.0 - y_split) * (1.0 + y_split)).sqrt();
        // Nearest singularity beyond z_split: the sliding onset z_s = √((1 + c − σ_max)/c), or z = 1.
        let z_sing = ((1.0 + cms) / c).sqrt().min(1.0);
        total += graded(z_b, z_split, z_sing - z_split, f64::INFINITY, points, |z| {
            let sigma = c * z * z - cms;
            mindlin_g(sigma, 1.0 - sigma) * (2.0 * z * z - 1.0) * 2.0
                / ((1.0 - z) * (1.0 + z)).sqrt()
        });
    }
    total
}

/// G = 1 − (1 − σ)^{3/2} from whichever of σ and w = 1 − σ is known more accurately.
fn mindlin_g(sigma: f64, w: f64) -> f64 {
    if w < 0.5 {
        1.0 - w.max(0.0).powf(1.5)
    } else {
        crate::law::mindlin_normalized_force(sigma.max(0.0))
    }
}

/// ∫_a^b f by Gauss–Legendre panels that double in length away from a singularity at
/// distance `gap` beyond b (first panel [b − gap, b]), none longer than `max_len`.
fn graded(
    a: f64,
    b: f64,
    gap: f64,
    max_len: f64,
    points: usize,
    mut f: impl FnMut(f64) -> f64,
) -> f64 {
    let mut right = b;
    let mut len = gap.max(1e-3 * (b - a)).min(max_len);
    let mut sum = 0.0;
    while right > a {
        let left = (right - len).max(a);
        sum += gauss(points, left, right, &mut f);
        right = left;
        len = (2.0 * len).min(max_len);
    }
    sum
}

/// ε − sin ε without cancellation (Taylor series below 0.2: 7 terms leave < 1e-19 relative).
pub fn eps_minus_sin(eps: f64) -> f64 {
    if eps < 0.2 {
        let e2 = eps * eps;
        let mut term = eps * e2 / 6.0;
        let mut sum = 0.0;
        for k in 0..7 {
            sum += term;
            let n = (2 * k + 4) as f64;
            term *= -e2 / (n * (n + 1.0));
        }
        sum
    } else {
        eps - eps.sin()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eps_minus_sin_is_continuous_and_accurate() {
        let below = eps_minus_sin(0.2 - 1e-15);
        let above = eps_minus_sin(0.2 + 1e-15);
        // The direct form carries ≈ 6e-16/ε² = 1.5e-14 relative rounding at ε = 0.2.
        assert!((below - above).abs() < 5e-14 * below);
        let e: f64 = 1e-5;
        assert!((eps_minus_sin(e) - e.powi(3) / 6.0).abs() < 1e-12 * e.powi(3));
    }
}
