use super::*;
use crate::fe::mesh::{BoxSpec, Material};

/// A 4 × 4 × 2 box of 8 × 8 × 4 elements from the origin, with its body.
fn plate() -> (Model, Body) {
    let mut m = Model::new(vec![Material::new(2.1e5, 0.3, 7.8e-9).unwrap()]);
    let b = m
        .add_box(BoxSpec {
            origin: [0.0, 0.0, 0.0],
            size: [4.0, 4.0, 2.0],
            divisions: [8, 8, 4],
            material: 0,
        })
        .unwrap();
    let body = *m.body(b).unwrap();
    (m, body)
}

/// Σ w·x of the weighted nodes (the load's centre).
fn centre(m: &Model, w: &[(usize, f64)]) -> [f64; 3] {
    [0, 1, 2].map(|c| w.iter().map(|&(n, v)| v * m.nodes[n][c]).sum())
}

#[test]
fn a_ring_spreads_the_force_over_the_nodes_of_its_annulus_on_the_face() {
    let (m, body) = plate();
    // Inner radius beyond the centre's elements (corners at 0.5·√2 = 0.71).
    let spread = Spread::Ring {
        inner: 0.75,
        outer: 1.4,
    };
    let w = weights(&m, &[body], [2.0, 2.0, 2.0], [0.0, 0.0, -1.0], spread).unwrap();
    let total: f64 = w.iter().map(|x| x.1).sum();
    assert!((total - 1.0).abs() < 1e-12);
    // Only top-face nodes, none on the axis, none beyond the ring's element band.
    for &(n, v) in &w {
        let [x, y, z] = m.nodes[n];
        assert_eq!(z, 2.0);
        let r = ((x - 2.0).powi(2) + (y - 2.0).powi(2)).sqrt();
        assert!(
            v > 0.0 && r > 0.0 && r < 1.4 + 0.5 * 2f64.sqrt(),
            "node at r = {r}"
        );
    }
    // Centred on the axis by symmetry.
    let c = centre(&m, &w);
    assert!((c[0] - 2.0).abs() < 1e-9 && (c[1] - 2.0).abs() < 1e-9);
    // The consistent loads of a uniform pressure: the second moment about the axis
    // Σ w r² equals the ring's (r_i² + r_o²)/2 to the sampling's accuracy.
    let m2: f64 = w
        .iter()
        .map(|&(n, v)| v * ((m.nodes[n][0] - 2.0).powi(2) + (m.nodes[n][1] - 2.0).powi(2)))
        .sum();
    let exact = 0.5 * (0.75f64.powi(2) + 1.4f64.powi(2));
    // Bilinear interpolation adds the element's own spread (h²/6 per direction).
    let smear = 2.0 * 0.5f64.powi(2) / 6.0;
    assert!(
        (m2 - exact - smear).abs() < 0.02 * exact,
        "{m2} vs {}",
        exact + smear
    );
}

#[test]
fn a_ring_cut_by_the_body_edge_keeps_its_resultant_on_the_part_inside() {
    let (m, body) = plate();
    // Centred on the edge y = 0: half the ring lies outside (a symmetry plane).
    let ring = Spread::Ring {
        inner: 0.5,
        outer: 1.5,
    };
    let w = weights(&m, &[body], [2.0, 0.0, 2.0], [0.0, 0.0, -1.0], ring).unwrap();
    assert!((w.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-12);
    let c = centre(&m, &w);
    // The half ring's centroid: 4(r_o³ − r_i³)/(3π(r_o² − r_i²)) from the cut.
    let exact = 4.0 * (1.5f64.powi(3) - 0.5f64.powi(3)) / (3.0 * std::f64::consts::PI * 2.0);
    assert!((c[0] - 2.0).abs() < 1e-9);
    assert!((c[1] - exact).abs() < 0.01, "{} vs {exact}", c[1]);
}

#[test]
fn a_thread_spreads_the_force_through_the_cylinder_it_engages() {
    let (m, body) = plate();
    // From the bottom face up over 1.5 of the 2 thickness, diameter 1.6.
    let thread = Spread::Thread {
        radius: 0.8,
        length: 1.5,
    };
    let w = weights(&m, &[body], [2.0, 2.0, 0.0], [0.0, 0.0, 1.0], thread).unwrap();
    assert!((w.iter().map(|x| x.1).sum::<f64>() - 1.0).abs() < 1e-12);
    let c = centre(&m, &w);
    assert!((c[0] - 2.0).abs() < 1e-9 && (c[1] - 2.0).abs() < 1e-9);
    // The cylinder's centroid is 0.75 up; every loaded node within one element of it.
    assert!((c[2] - 0.75).abs() < 0.01, "centroid z {}", c[2]);
    for &(n, _) in &w {
        assert!(m.nodes[n][2] <= 2.0 && m.nodes[n][2] >= 0.0);
        let r = ((m.nodes[n][0] - 2.0).powi(2) + (m.nodes[n][1] - 2.0).powi(2)).sqrt();
        assert!(r < 0.8 + 0.5 * 2f64.sqrt());
    }
}

#[test]
fn a_region_that_misses_the_body_is_an_error_and_a_node_is_one_node() {
    let (m, body) = plate();
    let ring = Spread::Ring {
        inner: 0.5,
        outer: 1.0,
    };
    // The plane z = 1.3 holds no element face (layers at 0, 0.5, 1, 1.5, 2).
    let e = weights(&m, &[body], [2.0, 2.0, 1.3], [0.0, 0.0, -1.0], ring).unwrap_err();
    assert!(e.contains("no sample of the element faces"), "{e}");
    let thread = Spread::Thread {
        radius: 0.5,
        length: 1.0,
    };
    let e = weights(&m, &[body], [9.0, 9.0, 0.0], [0.0, 0.0, 1.0], thread).unwrap_err();
    assert!(e.contains("outside the body"), "{e}");
    let w = weights(&m, &[body], [2.1, 1.9, 2.2], [0.0, 0.0, -1.0], Spread::Node).unwrap();
    assert_eq!(w.len(), 1);
    assert_eq!(m.nodes[w[0].0], [2.0, 2.0, 2.0]);
}
