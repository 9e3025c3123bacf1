//! Quadrature rules on the reference hexahedron [−1, 1]³, the reference tetrahedron
//! {ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1} (volume 1/6), the reference triangle {s₁, s₂ ≥ 0,
//! s₁ + s₂ ≤ 1} (area 1/2) and the reference wedge (that triangle × [−1, 1], volume 1).
//! A rule is a list of (point, weight).

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

/// A rule on the reference triangle: (point, weight).
pub type TriPoint = ([f64; 2], f64);

/// Centroid rule on the triangle: exact for degree ≤ 1.
pub fn tri_1() -> Vec<TriPoint> {
    vec![([1.0 / 3.0; 2], 0.5)]
}

/// The 3-point interior rule on the triangle, points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3)
/// with weights 1/6: exact for degree ≤ 2.
pub fn tri_3() -> Vec<TriPoint> {
    let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
    vec![([a, a], a), ([b, a], a), ([a, b], a)]
}

/// Collapsed 3×3 Gauss rule on the triangle: s₁ = u, s₂ = v(1 − u), Jacobian (1 − u);
/// u, v ∈ [0, 1]; exact for degree ≤ 4.
pub fn tri_collapsed_3() -> Vec<TriPoint> {
    let g = gauss_legendre(3);
    let mut out = Vec::with_capacity(9);
    for &(x, wx) in &g {
        for &(y, wy) in &g {
            let (u, v) = (0.5 * (x + 1.0), 0.5 * (y + 1.0));
            out.push(([u, v * (1.0 - u)], 0.25 * wx * wy * (1.0 - u)));
        }
    }
    out
}

/// Product rule on the wedge: the triangle rule `tri` in (ξ, η) times n-point Gauss in ζ.
pub fn wedge(tri: &[TriPoint], n: usize) -> Vec<QuadPoint> {
    let g = gauss_legendre(n);
    let mut out = Vec::with_capacity(tri.len() * n);
    for &(z, wz) in &g {
        for &(p, w) in tri {
            out.push(([p[0], p[1], z], w * wz));
        }
    }
    out
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
    fn triangle_and_wedge_rules_are_exact_to_their_degree() {
        // ∫ s₁^a s₂^b over the reference triangle = a! b! / (a + b + 2)!.
        let f = |n: u32| (1..=n).map(f64::from).product::<f64>();
        let exact = |a: u32, b: u32| f(a) * f(b) / f(a + b + 2);
        let tri = |r: &[TriPoint], a: i32, b: i32| -> f64 {
            r.iter().map(|(p, w)| w * p[0].powi(a) * p[1].powi(b)).sum()
        };
        for (rule, degree) in [(tri_1(), 1), (tri_3(), 2), (tri_collapsed_3(), 4)] {
            for a in 0..=degree {
                for b in 0..=degree - a {
                    let got = tri(&rule, a as i32, b as i32);
                    assert!((got - exact(a, b)).abs() < 1e-15, "{a} {b}: {got}");
                }
            }
            // One degree more is not integrated exactly: the test sees a wrong degree.
            let miss = (0..=degree + 1)
                .map(|a| {
                    (tri(&rule, a as i32, (degree + 1 - a) as i32) - exact(a, degree + 1 - a)).abs()
                })
                .fold(0.0, f64::max);
            assert!(miss > 1e-6, "degree {degree}: {miss}");
        }
        // The wedge: the triangle's moment times ∫ ζ^c over [−1, 1] (3 points: c ≤ 5).
        let rule = wedge(&tri_3(), 3);
        for c in 0..=5 {
            let line = if c % 2 == 1 {
                0.0
            } else {
                2.0 / (c as f64 + 1.0)
            };
            let got = integrate(&rule, 1, 1, c);
            assert!((got - exact(1, 1) * line).abs() < 1e-15, "ζ^{c}: {got}");
        }
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
