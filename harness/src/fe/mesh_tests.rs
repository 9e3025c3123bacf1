//! Meshes: box counts and numbering, face selection, stacks with coincident interface
//! nodes, bad input.

use super::*;

fn steel() -> Material {
    Material::new(210_000.0, 0.3, 7.85e-9).unwrap()
}

#[test]
fn box_counts_and_numbering() {
    let mut m = Model::new(vec![steel()]);
    let b = m
        .add_box(BoxSpec {
            origin: [1.0, 2.0, 3.0],
            size: [4.0, 2.0, 1.0],
            divisions: [4, 2, 1],
            material: 0,
        })
        .unwrap();
    let body = *m.body(b).unwrap();
    assert_eq!(m.nodes.len(), 5 * 3 * 2);
    assert_eq!(m.elements.len(), 8);
    assert_eq!(m.fixed.len(), 90);
    assert_eq!(m.nodes[body.node(0, 0, 0)], [1.0, 2.0, 3.0]);
    assert_eq!(m.nodes[body.node(4, 2, 1)], [5.0, 4.0, 4.0]);
    assert_eq!(m.nodes[body.node(1, 1, 0)], [2.0, 3.0, 3.0]);
    // Element (1,0,0): corner 0 at grid (1,0,0), corner 6 at grid (2,1,1).
    let e = &m.elements[body.element(1, 0, 0)];
    assert_eq!(e.nodes[0], body.node(1, 0, 0));
    assert_eq!(e.nodes[6], body.node(2, 1, 1));
}

#[test]
fn face_selection_matches_predicate() {
    let mut m = Model::new(vec![steel()]);
    let b = m
        .add_box(BoxSpec {
            origin: [0.0; 3],
            size: [3.0, 2.0, 1.0],
            divisions: [3, 2, 2],
            material: 0,
        })
        .unwrap();
    let body = *m.body(b).unwrap();
    for (face, pred) in [
        (
            Face::XMin,
            Box::new(|p: [f64; 3]| p[0] == 0.0) as Box<dyn Fn([f64; 3]) -> bool>,
        ),
        (Face::XMax, Box::new(|p: [f64; 3]| p[0] == 3.0)),
        (Face::YMax, Box::new(|p: [f64; 3]| p[1] == 2.0)),
        (Face::ZMin, Box::new(|p: [f64; 3]| p[2] == 0.0)),
    ] {
        let mut a = body.face_nodes(face);
        a.sort();
        assert_eq!(a, m.nodes_where(pred), "{face:?}");
    }
    // Face quads have outward normals and lie on the face.
    for face in Face::ALL {
        let quads = body.face_quads(face, &m.elements);
        let n = face.outward_normal();
        let [nx, ny, nz] = body.spec.divisions;
        let expect = match face.axis() {
            0 => ny * nz,
            1 => nx * nz,
            _ => nx * ny,
        };
        assert_eq!(quads.len(), expect);
        for q in quads {
            let p: Vec<[f64; 3]> = q.iter().map(|&i| m.nodes[i]).collect();
            let a = [0, 1, 2].map(|c| p[1][c] - p[0][c]);
            let b = [0, 1, 2].map(|c| p[3][c] - p[0][c]);
            let cross = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            let dot: f64 = (0..3).map(|c| cross[c] * n[c]).sum();
            assert!(dot > 0.0, "{face:?} quad not outward");
        }
    }
}

#[test]
fn stack_has_coincident_distinct_interface_nodes() {
    let mut m = Model::new(vec![steel(), steel()]);
    let ids = m
        .add_stack(
            [0.0, 0.0, 0.0],
            [60.0, 10.0],
            [6, 2],
            &[
                Layer {
                    thickness: 2.0,
                    nz: 1,
                    material: 0,
                },
                Layer {
                    thickness: 1.0,
                    nz: 1,
                    material: 1,
                },
                Layer {
                    thickness: 2.0,
                    nz: 1,
                    material: 0,
                },
            ],
        )
        .unwrap();
    assert_eq!(ids, vec![0, 1, 2]);
    for w in ids.windows(2) {
        let lo = m.bodies[w[0]].face_nodes(Face::ZMax);
        let hi = m.bodies[w[1]].face_nodes(Face::ZMin);
        assert_eq!(lo.len(), 7 * 3);
        for (a, b) in lo.iter().zip(&hi) {
            assert_ne!(a, b);
            assert_eq!(m.nodes[*a], m.nodes[*b]);
        }
    }
    let top = m.bodies[2].face_nodes(Face::ZMax);
    assert!(top.iter().all(|&n| m.nodes[n][2] == 5.0));
}

#[test]
fn bad_input_is_an_error() {
    let mut m = Model::new(vec![steel()]);
    let spec = BoxSpec {
        origin: [0.0; 3],
        size: [1.0; 3],
        divisions: [1; 3],
        material: 0,
    };
    assert_eq!(
        m.add_box(BoxSpec {
            divisions: [1, 0, 1],
            ..spec
        }),
        Err(MeshError::BadDivisions([1, 0, 1]))
    );
    assert_eq!(
        m.add_box(BoxSpec {
            material: 3,
            ..spec
        }),
        Err(MeshError::UnknownMaterial(3))
    );
    assert!(m
        .add_box(BoxSpec {
            size: [1.0, -1.0, 1.0],
            ..spec
        })
        .is_err());
    assert!(Material::new(1.0, 0.5, 1.0).is_err());
    assert!(m.fix(&[99], [true; 3]).is_err());
}
