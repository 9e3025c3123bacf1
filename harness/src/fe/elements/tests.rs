//! Element tests: rigid-body modes, patch test, mass = ρV, face orientation and
//! tributary areas, for every supported type.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use super::box_mesh::box_mesh;
use super::face::{tributary_areas, MeshFace};
use super::ElementKind;
use crate::fe::mesh::Material;
use crate::util::rng::Rng;

fn steel() -> Material {
    Material::new(210_000.0, 0.3, 7.85e-9).unwrap()
}

/// One element of type `kind` on [0,1]³ mapped by a fixed affine map and then every
/// node moved randomly by up to ±0.05 (so no element is a parallelepiped).
fn distorted(kind: ElementKind) -> Vec<[f64; 3]> {
    let mesh = box_mesh(kind, [1.0; 3], [1, 1, 1], 0.0, 1);
    let conn = &mesh.elements[0];
    let a = Matrix3::new(1.2, 0.2, -0.1, 0.1, 0.9, 0.15, 0.05, -0.1, 1.1);
    let mut rng = Rng::new(9);
    conn.iter()
        .map(|&n| {
            let p = a * Vector3::from(mesh.nodes[n]);
            std::array::from_fn(|c| p[c] + rng.uniform(-0.05, 0.05))
        })
        .collect()
}

fn rigid_modes(x: &[[f64; 3]]) -> Vec<DVector<f64>> {
    let n = x.len();
    let mut out = Vec::new();
    for c in 0..3 {
        out.push(DVector::from_fn(3 * n, |r, _| {
            f64::from(u8::from(r % 3 == c))
        }));
    }
    for axis in 0..3 {
        let w = Vector3::ith(axis, 1.0);
        out.push(DVector::from_fn(3 * n, |r, _| {
            w.cross(&Vector3::from(x[r / 3]))[r % 3]
        }));
    }
    out
}

/// Zero eigenvalues of one element's stiffness: 6 rigid modes, plus for C3D20R the 6
/// zero-energy modes of a single element under 2×2×2 reduced integration and for C3D6
/// the one of its 2-point rule (neither communicates between elements: the assembled
/// meshes below have exactly 6).
fn expected_zero_modes(kind: ElementKind) -> usize {
    match kind {
        ElementKind::C3D20R => 12,
        ElementKind::C3D6 => 7,
        _ => 6,
    }
}

fn zero_eigenvalues(k: &DMatrix<f64>) -> usize {
    let eig = k.clone().symmetric_eigenvalues();
    let max = eig.max();
    assert!(eig.iter().all(|&l| l > -1e-10 * max));
    eig.iter().filter(|&&l| l.abs() < 1e-10 * max).count()
}

#[test]
fn rigid_body_modes_are_force_free_and_the_only_zero_modes() {
    for kind in ElementKind::ALL {
        let x = distorted(kind);
        let k = kind.element().stiffness(&x, &steel()).unwrap();
        let scale = k.abs().max();
        for u in rigid_modes(&x) {
            let f = &k * &u;
            assert!(f.abs().max() < 1e-11 * scale * u.abs().max(), "{kind}");
        }
        assert!((&k - k.transpose()).abs().max() == 0.0, "{kind} symmetric");
        assert_eq!(zero_eigenvalues(&k), expected_zero_modes(kind), "{kind}");
    }
}

#[test]
fn assembled_meshes_of_underintegrated_types_have_only_rigid_zero_modes() {
    for kind in [ElementKind::C3D20R, ElementKind::C3D6] {
        let mesh = box_mesh(kind, [2.0; 3], [2, 2, 2], 0.0, 1);
        let (k, _) = mesh.dense_matrices(&steel()).unwrap();
        assert_eq!(zero_eigenvalues(&k), 6, "{kind}");
    }
}

#[test]
fn mass_sums_to_rho_v_and_volume_is_exact() {
    let rho = 7.85e-9;
    for kind in ElementKind::ALL {
        // A parallelepiped (affine image of the unit cube): exact volume det(A).
        let mesh = box_mesh(kind, [1.0; 3], [1, 1, 1], 0.0, 1);
        let a = Matrix3::new(2.0, 0.5, 0.3, 0.0, 3.0, -0.4, 0.0, 0.0, 4.0);
        let nodes: Vec<[f64; 3]> = mesh
            .nodes
            .iter()
            .map(|p| {
                let q = a * Vector3::from(*p);
                [q[0], q[1], q[2]]
            })
            .collect();
        let mut total = 0.0;
        let mut vol = 0.0;
        let e = kind.element();
        for conn in &mesh.elements {
            let x: Vec<[f64; 3]> = conn.iter().map(|&n| nodes[n]).collect();
            let m = e.mass(&x, rho).unwrap();
            assert!((&m - m.transpose()).abs().max() == 0.0);
            for comp in 0..3 {
                let mut s = 0.0;
                for i in 0..x.len() {
                    for j in 0..x.len() {
                        s += m[(3 * i + comp, 3 * j + comp)];
                    }
                }
                if comp == 0 {
                    total += s;
                } else {
                    approx::assert_relative_eq!(s, total_of(&m, comp), max_relative = 1e-14);
                }
            }
            vol += e.volume(&x).unwrap();
        }
        approx::assert_relative_eq!(vol, a.determinant(), max_relative = 1e-13);
        approx::assert_relative_eq!(total, rho * a.determinant(), max_relative = 1e-13);
    }
}

fn total_of(m: &DMatrix<f64>, comp: usize) -> f64 {
    let n = m.nrows() / 3;
    let mut s = 0.0;
    for i in 0..n {
        for j in 0..n {
            s += m[(3 * i + comp, 3 * j + comp)];
        }
    }
    s
}

/// Patch test: a box of 3×3×3 cells with its interior corner nodes moved randomly by up
/// to ±0.2 cells; boundary nodes get the linear field u = u₀ + G x, the interior nodes
/// are solved for and must reproduce it. Returns the relative error.
fn patch_error(kind: ElementKind) -> f64 {
    let mesh = box_mesh(kind, [3.0; 3], [3, 3, 3], 0.2, 42);
    let (k, _) = mesh.dense_matrices(&steel()).unwrap();
    let g = Matrix3::new(1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, -2e-4, 3e-4, 4e-4);
    let u0 = Vector3::new(0.01, -0.02, 0.03);
    let on_boundary = |p: &[f64; 3]| {
        p.iter()
            .any(|&v| v.abs() < 1e-12 || (v - 3.0).abs() < 1e-12)
    };
    let free: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&n| !on_boundary(&mesh.nodes[n]))
        .flat_map(|n| (0..3).map(move |c| 3 * n + c))
        .collect();
    assert!(!free.is_empty());
    let mut u = DVector::zeros(3 * mesh.nodes.len());
    for (n, p) in mesh.nodes.iter().enumerate() {
        let e = u0 + g * Vector3::from(*p);
        for c in 0..3 {
            u[3 * n + c] = e[c];
        }
    }
    let exact = DVector::from_iterator(free.len(), free.iter().map(|&r| u[r]));
    for &r in &free {
        u[r] = 0.0;
    }
    let rhs = -DVector::from_iterator(free.len(), free.iter().map(|&r| (k.row(r) * &u)[0]));
    let kff = DMatrix::from_fn(free.len(), free.len(), |a, b| k[(free[a], free[b])]);
    let uf = kff.lu().solve(&rhs).unwrap();
    (uf - &exact).norm() / exact.norm()
}

#[test]
fn patch_test_reproduces_linear_fields() {
    for kind in ElementKind::ALL {
        let err = patch_error(kind);
        eprintln!("{kind}: patch test relative error {err:.1e}");
        assert!(err < 1e-10, "{kind}: {err}");
    }
}

#[test]
fn inverted_element_and_wrong_node_count_are_errors() {
    for kind in ElementKind::ALL {
        let mut x = distorted(kind);
        let e = kind.element();
        assert!(e.stiffness(&x[1..], &steel()).is_err());
        // Mirror the element: every Jacobian determinant changes sign.
        x.iter_mut().for_each(|p| p[2] = -p[2]);
        assert!(e.stiffness(&x, &steel()).is_err(), "{kind}");
        assert!(e.mass(&x, 1.0).is_err(), "{kind}");
    }
}

#[test]
fn faces_point_outward_and_tributary_areas_sum_to_the_face_area() {
    for kind in ElementKind::ALL {
        let x = distorted(kind);
        let conn: Vec<usize> = (0..x.len()).collect();
        let centroid = x
            .iter()
            .fold(Vector3::zeros(), |s, p| s + Vector3::from(*p))
            / x.len() as f64;
        assert!(MeshFace::new(kind, 0, &conn, kind.face_count()).is_none());
        for s in 0..kind.face_count() {
            let f = MeshFace::new(kind, 0, &conn, s).unwrap();
            let p = f.at(&x, f.shape.centre());
            let n = p.outward_normal().unwrap();
            assert!(n.dot(&(p.x - centroid)) > 0.0, "{kind} S{}", s + 1);
            let areas = f.nodal_areas(&x);
            approx::assert_relative_eq!(
                areas.iter().sum::<f64>(),
                f.area(&x),
                max_relative = 1e-13
            );
            assert!(
                areas.iter().all(|&a| a > 0.0),
                "{kind} S{}: {areas:?}",
                s + 1
            );
        }
    }
    // Whole boundary z = 0 of a 2×2 C3D20 box (faces S1): areas sum to 4, the centre
    // node (a corner of four faces) gets 4× a face corner's HRZ share.
    let mesh = box_mesh(ElementKind::C3D20, [2.0, 2.0, 1.0], [2, 2, 1], 0.0, 1);
    let faces: Vec<MeshFace> = mesh
        .elements
        .iter()
        .enumerate()
        .map(|(e, c)| MeshFace::new(ElementKind::C3D20, e, c, 0).unwrap())
        .collect();
    let t = tributary_areas(&faces, &mesh.nodes);
    approx::assert_relative_eq!(t.values().sum::<f64>(), 4.0, max_relative = 1e-13);
    let centre = mesh
        .nodes
        .iter()
        .position(|p| *p == [1.0, 1.0, 0.0])
        .unwrap();
    let corner = mesh
        .nodes
        .iter()
        .position(|p| *p == [0.0, 0.0, 0.0])
        .unwrap();
    approx::assert_relative_eq!(t[&centre], 4.0 * t[&corner], max_relative = 1e-13);
}
