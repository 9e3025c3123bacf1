//! Shape functions of the 4-node and 10-node tetrahedra. Natural coordinates
//! (ξ, η, ζ) are the volume coordinates L₂, L₃, L₄ (L₁ = 1 − ξ − η − ζ); Abaqus/CalculiX
//! node order: corners 1–4 (node 1 at the origin of (ξ, η, ζ), 2 at ξ = 1, 3 at η = 1,
//! 4 at ζ = 1), then the edge midpoints 5 (1-2), 6 (2-3), 7 (3-1), 8 (1-4), 9 (2-4),
//! 10 (3-4).

use super::face_shape::{FaceDef, FaceShape};

/// Natural coordinates of the 10 nodes (the first 4 are the 4-node element's).
pub const NODES10: [[f64; 3]; 10] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.0, 0.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.0],
    [0.0, 0.0, 0.5],
    [0.5, 0.0, 0.5],
    [0.0, 0.5, 0.5],
];

/// Faces S1…S4 of the 4-node tetrahedron (local node indices, 0-based), as Abaqus lists
/// them: S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1 (normal into the element in this
/// order).
pub const FACES4: [FaceDef; 4] = [
    FaceDef::new(&[0, 1, 2], FaceShape::Tri3),
    FaceDef::new(&[0, 3, 1], FaceShape::Tri3),
    FaceDef::new(&[1, 3, 2], FaceShape::Tri3),
    FaceDef::new(&[2, 3, 0], FaceShape::Tri3),
];

/// Faces S1…S4 of the 10-node tetrahedron: [`FACES4`]'s corners, then their edge
/// midpoints.
pub const FACES10: [FaceDef; 4] = [
    FaceDef::new(&[0, 1, 2, 4, 5, 6], FaceShape::Tri6),
    FaceDef::new(&[0, 3, 1, 7, 8, 4], FaceShape::Tri6),
    FaceDef::new(&[1, 3, 2, 8, 9, 5], FaceShape::Tri6),
    FaceDef::new(&[2, 3, 0, 9, 7, 6], FaceShape::Tri6),
];

/// The corner pairs of the edge midpoints 5…10.
pub const EDGES: [(usize, usize); 6] = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)];

/// Volume coordinates L₁…L₄ and their derivatives ∂Lᵢ/∂(ξ, η, ζ).
fn volume_coordinates(p: [f64; 3]) -> ([f64; 4], [[f64; 3]; 4]) {
    (
        [1.0 - p[0] - p[1] - p[2], p[0], p[1], p[2]],
        [
            [-1.0, -1.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
    )
}

/// Linear shape functions Nᵢ = Lᵢ.
pub fn shape4(p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let (l, dl) = volume_coordinates(p);
    n[..4].copy_from_slice(&l);
    dn[..4].copy_from_slice(&dl);
}

/// Quadratic shape functions: corners Nᵢ = Lᵢ(2Lᵢ − 1), edge midpoints N = 4 L_a L_b.
pub fn shape10(p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let (l, dl) = volume_coordinates(p);
    for i in 0..4 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        for k in 0..3 {
            dn[i][k] = (4.0 * l[i] - 1.0) * dl[i][k];
        }
    }
    for (e, &(a, b)) in EDGES.iter().enumerate() {
        n[4 + e] = 4.0 * l[a] * l[b];
        for k in 0..3 {
            dn[4 + e][k] = 4.0 * (dl[a][k] * l[b] + l[a] * dl[b][k]);
        }
    }
}
