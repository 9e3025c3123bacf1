//! Node-pair blocks inside an assembled system: spring forces in the local frame, fixed
//! pair nodes dropped.

use crate::fe::assembly::assemble;
use crate::fe::mesh::{BoxSpec, Face, Layer, Material, Model};
use crate::fe::pair_blocks::*;
use nalgebra::{Complex, Matrix3, Vector3};

#[test]
fn pair_block_gives_spring_forces_in_local_frame() {
    // Two stacked one-element cubes; pairs = the 4 coincident interface node pairs.
    let mut model = Model::new(vec![Material::new(1000.0, 0.25, 1e-9).unwrap()]);
    let ids = model
        .add_stack(
            [0.0; 3],
            [1.0, 1.0],
            [1, 1],
            &[
                Layer {
                    thickness: 1.0,
                    nz: 1,
                    material: 0,
                },
                Layer {
                    thickness: 1.0,
                    nz: 1,
                    material: 0,
                },
            ],
        )
        .unwrap();
    let lo = model.bodies[ids[0]].face_nodes(Face::ZMax);
    let hi = model.bodies[ids[1]].face_nodes(Face::ZMin);
    let pairs: Vec<[usize; 2]> = lo.iter().zip(&hi).map(|(&a, &b)| [a, b]).collect();
    let sys = assemble(&model, &pairs).unwrap();
    // A rotated frame: n tilted, t1, t2 orthonormal.
    let n = Vector3::new(0.2, -0.1, 1.0).normalize();
    let t1 = n.cross(&Vector3::x()).normalize();
    let t2 = n.cross(&t1);
    let q = Matrix3::from_columns(&[n, t1, t2]);
    let kloc = [
        Complex::new(5.0, 0.5),
        Complex::new(2.0, 0.2),
        Complex::new(1.0, -0.3),
    ];
    let kg = diagonal_to_global(&q, kloc);
    let mut s = sys.complex_zeros();
    let ptr = s.values.as_ptr();
    sys.pairs.add(&mut s.values, 1, &kg);
    assert_eq!(ptr, s.values.as_ptr());
    // Only the pair block is nonzero: S u = spring forces for u_b − u_a = δ.
    let delta_loc = Vector3::new(0.3, -0.2, 0.7);
    let delta = q * delta_loc;
    let [(a, _), (b, _)] = sys.pairs.coupling(1) else {
        panic!("a node pair")
    };
    let mut u = vec![Complex::new(0.0, 0.0); sys.dofs.n_free()];
    for c in 0..3 {
        u[sys.dofs.free(3 * a + c).unwrap()] = Complex::new(0.1, 0.0);
        u[sys.dofs.free(3 * b + c).unwrap()] = Complex::new(0.1 + delta[c], 0.0);
    }
    let f = s.mul_vec(&u);
    // Internal force at b: (S u)_b = K δ = Q (k ⊙ δ_loc); at a the opposite.
    let fb_loc: Vec<Complex<f64>> = (0..3).map(|i| kloc[i] * delta_loc[i]).collect();
    for c in 0..3 {
        let fb: Complex<f64> = (0..3).map(|i| fb_loc[i] * q[(c, i)]).sum();
        let got_b = f[sys.dofs.free(3 * b + c).unwrap()];
        let got_a = f[sys.dofs.free(3 * a + c).unwrap()];
        // Round-off of 3×3 products of O(1) numbers.
        assert!((got_b - fb).norm() < 1e-14 * 10.0, "{got_b} vs {fb}");
        assert!((got_a + fb).norm() < 1e-14 * 10.0);
    }
    let others: f64 = f.iter().map(|v| v.norm()).sum::<f64>() - {
        (0..3)
            .map(|c| {
                f[sys.dofs.free(3 * a + c).unwrap()].norm()
                    + f[sys.dofs.free(3 * b + c).unwrap()].norm()
            })
            .sum::<f64>()
    };
    assert!(others.abs() < 1e-13);
}

#[test]
fn fixed_pair_node_is_dropped() {
    let mut model = Model::new(vec![Material::new(1000.0, 0.25, 1e-9).unwrap()]);
    model
        .add_box(BoxSpec {
            origin: [0.0; 3],
            size: [1.0; 3],
            divisions: [1; 3],
            material: 0,
        })
        .unwrap();
    model.fix(&[0], [true; 3]).unwrap();
    let sys = assemble(&model, &[[0, 6]]).unwrap();
    let mut s = sys.complex_zeros();
    let k = Matrix3::from_diagonal_element(Complex::new(7.0, 0.0));
    sys.pairs.add(&mut s.values, 0, &k);
    // Node 6 alone feels a spring to ground: diagonal 7 on its DOFs, nothing else.
    let total: Complex<f64> = s.values.iter().sum();
    assert_eq!(total, Complex::new(21.0, 0.0));
    let d = sys.dofs.free(18).unwrap();
    assert_eq!(
        s.values[sys.pattern.find(d, d).unwrap()],
        Complex::new(7.0, 0.0)
    );
}
