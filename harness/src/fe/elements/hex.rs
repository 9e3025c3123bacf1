//! Shape functions of the 8-node and 20-node (serendipity) hexahedra, natural
//! coordinates (ξ, η, ζ) ∈ [−1, 1]³, Abaqus/CalculiX node order: corners 1–4 on ζ = −1
//! counter-clockwise seen from +ζ, corners 5–8 above them, then the 12 edge midpoints
//! 9–12 (bottom edges 1-2, 2-3, 3-4, 4-1), 13–16 (top edges 5-6, 6-7, 7-8, 8-5) and
//! 17–20 (vertical edges 1-5, 2-6, 3-7, 4-8).

use super::face_shape::{FaceDef, FaceShape};

/// Natural coordinates of the 20 nodes (the first 8 are the 8-node element's).
pub const NODES20: [[f64; 3]; 20] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [1.0, 0.0, -1.0],
    [0.0, 1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [0.0, -1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// Faces S1…S6 of the 8-node hexahedron (local node indices, 0-based), as Abaqus lists
/// them: S1 = 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3, S5 = 3-7-8-4,
/// S6 = 4-8-5-1. In this order (ξ₁ × ξ₂ of the face map) the normal points into the
/// element.
pub const FACES8: [FaceDef; 6] = [
    FaceDef::new(&[0, 1, 2, 3], FaceShape::Quad4),
    FaceDef::new(&[4, 7, 6, 5], FaceShape::Quad4),
    FaceDef::new(&[0, 4, 5, 1], FaceShape::Quad4),
    FaceDef::new(&[1, 5, 6, 2], FaceShape::Quad4),
    FaceDef::new(&[2, 6, 7, 3], FaceShape::Quad4),
    FaceDef::new(&[3, 7, 4, 0], FaceShape::Quad4),
];

/// Faces S1…S6 of the 20-node hexahedron: [`FACES8`]'s corners, then their edge
/// midpoints.
pub const FACES20: [FaceDef; 6] = [
    FaceDef::new(&[0, 1, 2, 3, 8, 9, 10, 11], FaceShape::Quad8),
    FaceDef::new(&[4, 7, 6, 5, 15, 14, 13, 12], FaceShape::Quad8),
    FaceDef::new(&[0, 4, 5, 1, 16, 12, 17, 8], FaceShape::Quad8),
    FaceDef::new(&[1, 5, 6, 2, 17, 13, 18, 9], FaceShape::Quad8),
    FaceDef::new(&[2, 6, 7, 3, 18, 14, 19, 10], FaceShape::Quad8),
    FaceDef::new(&[3, 7, 4, 0, 19, 15, 16, 11], FaceShape::Quad8),
];

/// The corner pairs of the edge midpoints 9…20.
pub const EDGES: [(usize, usize); 12] = [
    (0, 1),
    (1, 2),
    (2, 3),
    (3, 0),
    (4, 5),
    (5, 6),
    (6, 7),
    (7, 4),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

/// Trilinear shape functions Nᵢ = ⅛(1+ξᵢξ)(1+ηᵢη)(1+ζᵢζ) and ∂Nᵢ/∂(ξ, η, ζ).
pub fn shape8(p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    for (i, c) in NODES20[..8].iter().enumerate() {
        let a = [1.0 + c[0] * p[0], 1.0 + c[1] * p[1], 1.0 + c[2] * p[2]];
        n[i] = 0.125 * a[0] * a[1] * a[2];
        dn[i] = [
            0.125 * c[0] * a[1] * a[2],
            0.125 * a[0] * c[1] * a[2],
            0.125 * a[0] * a[1] * c[2],
        ];
    }
}

/// Serendipity shape functions of the 20-node hexahedron and ∂Nᵢ/∂(ξ, η, ζ):
/// corners Nᵢ = ⅛(1+ξᵢξ)(1+ηᵢη)(1+ζᵢζ)(ξᵢξ+ηᵢη+ζᵢζ−2); an edge midpoint with
/// ξᵢ = 0 has Nᵢ = ¼(1−ξ²)(1+ηᵢη)(1+ζᵢζ) (likewise for the other axes).
pub fn shape20(p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    for (i, c) in NODES20.iter().enumerate() {
        let a = [1.0 + c[0] * p[0], 1.0 + c[1] * p[1], 1.0 + c[2] * p[2]];
        if i < 8 {
            let s = c[0] * p[0] + c[1] * p[1] + c[2] * p[2] - 2.0;
            n[i] = 0.125 * a[0] * a[1] * a[2] * s;
            for k in 0..3 {
                let (b, d) = ((k + 1) % 3, (k + 2) % 3);
                // ∂/∂p_k of a_k·s = c_k·s + a_k·c_k
                dn[i][k] = 0.125 * c[k] * a[b] * a[d] * (s + a[k]);
            }
        } else {
            // The axis along which this midpoint's coordinate is 0.
            let k = (0..3).find(|&k| c[k] == 0.0).unwrap_or(0);
            let (b, d) = ((k + 1) % 3, (k + 2) % 3);
            let q = 1.0 - p[k] * p[k];
            n[i] = 0.25 * q * a[b] * a[d];
            dn[i][k] = -0.5 * p[k] * a[b] * a[d];
            dn[i][b] = 0.25 * q * c[b] * a[d];
            dn[i][d] = 0.25 * q * a[b] * c[d];
        }
    }
}
