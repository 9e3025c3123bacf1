//! Quadrature rules on the reference hexahedron [−1, 1]³ and the reference tetrahedron
//! {ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1} (volume 1/6). A rule is a list of (point, weight).

/// One quadrature point: natural coordinates and weight.
pub type QuadPoint = ([f64; 3], f64);

/// Gauss–Legendre abscissae and weights on [−1, 1] for 1…4 points.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    match n {
        1 => vec![(0.0, 2.0)],
        2 => {
            let a = (1.0f64 / 3.0).sqrt();
            vec![(-a, 1.0), (a, 1.0)]
        }
        3 => {
            let a = (0.6f64).sqrt();
            vec![(-a, 5.0 / 9.0), (0.0, 8.0 / 9.0), (a, 5.0 / 9.0)]
        }
        _ => {
            let s = (6.0f64 / 5.0).sqrt();
            let a = ((3.0 - 2.0 * s) / 7.0).sqrt();
            let b = ((3.0 + 2.0 * s) / 7.0).sqrt();
            let wa = (18.0 + 30.0f64.sqrt()) / 36.0;
            let wb = (18.0 - 30.0f64.sqrt()) / 36.0;
            vec![(-b, wb), (-a, wa), (a, wa), (b, wb)]
        }
    }
}

/// n×n×n Gauss rule on [−1, 1]³: exact for degree ≤ 2n − 1 in each coordinate.
pub fn hex_gauss(n: usize) -> Vec<QuadPoint> {
    let g = gauss_legendre(n);
    let mut out = Vec::with_capacity(n * n * n);
    for &(z, wz) in &g {
        for &(y, wy) in &g {
            for &(x, wx) in &g {
                out.push(([x, y, z], wx * wy * wz));
            }
        }
    }
    out
}

/// Centroid rule on the tetrahedron: exact for degree ≤ 1.
pub fn tet_1() -> Vec<QuadPoint> {
    vec![([0.25; 3], 1.0 / 6.0)]
}

/// The symmetric 4-point rule on the tetrahedron: exact for degree ≤ 2
/// (a = (5 + 3√5)/20, b = (5 − √5)/20, weights 1/24).
pub fn tet_4() -> Vec<QuadPoint> {
    let a = (5.0 + 3.0 * 5.0f64.sqrt()) / 20.0;
    let b = (5.0 - 5.0f64.sqrt()) / 20.0;
    vec![
        ([b, b, b], 1.0 / 24.0),
        ([a, b, b], 1.0 / 24.0),
        ([b, a, b], 1.0 / 24.0),
        ([b, b, a], 1.0 / 24.0),
    ]
}

/// Collapsed (Duffy) 4×4×4 Gauss rule on the tetrahedron: ξ = u, η = v(1 − u),
/// ζ = w(1 − u)(1 − v) with u, v, w ∈ [0, 1], Jacobian (1 − u)²(1 − v). A polynomial
/// of degree p becomes degree ≤ p + 2 in u, so the rule is exact for p ≤ 5 (all
/// weights positive).
pub fn tet_collapsed_4() -> Vec<QuadPoint> {
    let g: Vec<(f64, f64)> = gauss_legendre(4)
        .into_iter()
        .map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w))
        .collect();
    let mut out = Vec::with_capacity(64);
    for &(u, wu) in &g {
        for &(v, wv) in &g {
            for &(w, ww) in &g {
                let p = [u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v)];
                out.push((p, wu * wv * ww * (1.0 - u) * (1.0 - u) * (1.0 - v)));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ ξ^a η^b ζ^c over the reference tetrahedron = a! b! c! / (a + b + c + 3)!.
    fn tet_monomial(a: u32, b: u32, c: u32) -> f64 {
        let f = |n: u32| (1..=n).map(f64::from).product::<f64>();
        f(a) * f(b) * f(c) / f(a + b + c + 3)
    }

    fn integrate(rule: &[QuadPoint], a: i32, b: i32, c: i32) -> f64 {
        rule.iter()
            .map(|(p, w)| w * p[0].powi(a) * p[1].powi(b) * p[2].powi(c))
            .sum()
    }

    #[test]
    fn tet_rules_are_exact_to_their_degree() {
        for (rule, degree) in [(tet_1(), 1), (tet_4(), 2), (tet_collapsed_4(), 5)] {
            for a in 0..=degree {
                for b in 0..=degree - a {
                    for c in 0..=degree - a - b {
                        let exact = tet_monomial(a, b, c);
                        let got = integrate(&rule, a as i32, b as i32, c as i32);
                        assert!((got - exact).abs() < 1e-14, "{a} {b} {c}: {got} {exact}");
                    }
                }
            }
        }
        // tet_4 is not exact for degree 3: the test can see a wrong degree.
        assert!((integrate(&tet_4(), 3, 0, 0) - tet_monomial(3, 0, 0)).abs() > 1e-6);
    }

    #[test]
    fn hex_rules_are_exact_to_their_degree() {
        for n in 1..=4 {
            let rule = hex_gauss(n);
            let d = 2 * n as i32 - 1;
            let exact = |k: i32| {
                if k % 2 == 1 {
                    0.0
                } else {
                    2.0 / (k as f64 + 1.0)
                }
            };
            let got = integrate(&rule, d - 1, d, 0);
            assert!((got - exact(d - 1) * exact(d) * 2.0).abs() < 1e-14);
            let got = integrate(&rule, d - 1, 0, d - 1);
            assert!(
                (got - exact(d - 1) * exact(d - 1) * 2.0).abs() < 1e-13,
                "{n}"
            );
        }
    }
}
