//! Equivalent damping by energy balance (3.9–3.14): a viscous damper d* dissipates
//! π ω A² d* per cycle of δ = A cos ωt; equating that to the loop area A_hys gives
//! d* = A_hys/(π ω A²) (3.14). The structural form is the loss factor η = A_hys/(π k* A²).

use super::loop_shape::LoopShape;
use super::quadrature::simpson_or_gauss;
use crate::hysteresis::Rule;
use crate::law::Backbone;
use std::f64::consts::PI;

/// d* = A_hys/(π ω A²) (3.14); ω > 0, A > 0. No loop, no damping (also where A²
/// underflows: A = 1e-170, a round-off amplitude of a welded joint, made 0/0); A is
/// divided out twice, not squared, so that d* stays finite while A_hys/A is.
pub fn viscous_damping(area: f64, amplitude: f64, omega: f64) -> f64 {
    if area == 0.0 {
        return 0.0;
    }
    area / amplitude / (PI * omega * amplitude) // (3.14)
}

/// η = A_hys/(π k* A²): the frequency-independent loss factor of the same loop (0
/// without a loop, A divided out twice as in [`viscous_damping`]).
pub fn loss_factor(area: f64, amplitude: f64, k_star: f64) -> f64 {
    if area == 0.0 {
        return 0.0;
    }
    area / amplitude / (PI * k_star * amplitude)
}

/// A_hys by quadrature over x of the gap between the branches, as the thesis computes it
/// (areas under phases 1+2 minus the area under phase 3, Fig. 4.11):
/// A_hys = ∫_{−A}^{A} [D(A + x) + D(A − x) − 2F̂] dx.
pub fn area_by_rule(
    b: &Backbone,
    rule: Rule,
    shape: &LoopShape,
    simpson_rule: bool,
    n: usize,
) -> f64 {
    let a = shape.amplitude;
    simpson_or_gauss(simpson_rule, n, -a, a, |x: f64| {
        shape.drop(b, rule, a + x) + shape.drop(b, rule, a - x) - 2.0 * shape.peak_force
    })
}
