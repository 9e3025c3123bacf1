//! Shape functions of the 6-node and 15-node wedges (triangular prisms). Natural
//! coordinates: (ξ, η) on the triangle ξ, η ≥ 0, ξ + η ≤ 1 (area coordinates
//! L₁ = 1 − ξ − η, L₂ = ξ, L₃ = η) and ζ ∈ [−1, 1] along the prism. Abaqus/CalculiX
//! node order: corners 1–3 on ζ = −1 (counter-clockwise seen from +ζ), 4–6 above them,
//! then the 9 edge midpoints 7–9 (bottom edges 1-2, 2-3, 3-1), 10–12 (top edges 4-5,
//! 5-6, 6-4) and 13–15 (vertical edges 1-4, 2-5, 3-6).

use super::face_shape::{FaceDef, FaceShape};

/// Faces S1…S5 of the 6-node wedge (local node indices, 0-based), as Abaqus lists them:
/// S1 = 1-2-3, S2 = 4-6-5, S3 = 1-4-5-2, S4 = 2-5-6-3, S5 = 3-6-4-1 (normal into the
/// element in this order).
pub const FACES6: [FaceDef; 5] = [
    FaceDef::new(&[0, 1, 2], FaceShape::Tri3),
    FaceDef::new(&[3, 5, 4], FaceShape::Tri3),
    FaceDef::new(&[0, 3, 4, 1], FaceShape::Quad4),
    FaceDef::new(&[1, 4, 5, 2], FaceShape::Quad4),
    FaceDef::new(&[2, 5, 3, 0], FaceShape::Quad4),
];

/// Faces S1…S5 of the 15-node wedge: [`FACES6`]'s corners, then their edge midpoints.
pub const FACES15: [FaceDef; 5] = [
    FaceDef::new(&[0, 1, 2, 6, 7, 8], FaceShape::Tri6),
    FaceDef::new(&[3, 5, 4, 11, 10, 9], FaceShape::Tri6),
    FaceDef::new(&[0, 3, 4, 1, 12, 9, 13, 6], FaceShape::Quad8),
    FaceDef::new(&[1, 4, 5, 2, 13, 10, 14, 7], FaceShape::Quad8),
    FaceDef::new(&[2, 5, 3, 0, 14, 11, 12, 8], FaceShape::Quad8),
];

/// The corner pairs of the edge midpoints 7…15.
pub const EDGES: [(usize, usize); 9] = [
    (0, 1),
    (1, 2),
    (2, 0),
    (3, 4),
    (4, 5),
    (5, 3),
    (0, 3),
    (1, 4),
    (2, 5),
];

/// Area coordinates L₁…L₃ of (ξ, η) and their derivatives ∂Lᵢ/∂(ξ, η).
fn area_coordinates(p: [f64; 3]) -> ([f64; 3], [[f64; 2]; 3]) {
    (
        [1.0 - p[0] - p[1], p[0], p[1]],
        [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]],
    )
}

/// Linear shape functions Nᵢ = Lᵢ (1 ∓ ζ)/2 (− for the corners on ζ = −1).
pub fn shape6(p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let (l, dl) = area_coordinates(p);
    for (level, s) in [-1.0, 1.0].into_iter().enumerate() {
        let h = 0.5 * (1.0 + s * p[2]);
        for i in 0..3 {
            let k = 3 * level + i;
            n[k] = l[i] * h;
            dn[k] = [dl[i][0] * h, dl[i][1] * h, 0.5 * s * l[i]];
        }
    }
}

/// Quadratic shape functions with h± = (1 ± ζ)/2 and b = 1 − ζ²: corners
/// Nᵢ = Lᵢ(2Lᵢ − 1)h± − ½Lᵢb, triangle-edge midpoints N = 4 L_a L_b h±, vertical-edge
/// midpoints N = Lᵢ b.
pub fn shape15(p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
    let (l, dl) = area_coordinates(p);
    let z = p[2];
    let (b, db) = (1.0 - z * z, -2.0 * z);
    for (level, s) in [-1.0, 1.0].into_iter().enumerate() {
        let (h, dh) = (0.5 * (1.0 + s * z), 0.5 * s);
        for i in 0..3 {
            let k = 3 * level + i;
            let q = l[i] * (2.0 * l[i] - 1.0);
            let dq = 4.0 * l[i] - 1.0;
            n[k] = q * h - 0.5 * l[i] * b;
            dn[k] = [
                dl[i][0] * (dq * h - 0.5 * b),
                dl[i][1] * (dq * h - 0.5 * b),
                q * dh - 0.5 * l[i] * db,
            ];
        }
        for (e, &(i, j)) in EDGES[3 * level..3 * level + 3].iter().enumerate() {
            let k = 6 + 3 * level + e;
            let (j, i) = (j % 3, i % 3);
            let m = 4.0 * l[i] * l[j];
            n[k] = m * h;
            dn[k] = [
                4.0 * (dl[i][0] * l[j] + l[i] * dl[j][0]) * h,
                4.0 * (dl[i][1] * l[j] + l[i] * dl[j][1]) * h,
                m * dh,
            ];
        }
    }
    for i in 0..3 {
        n[12 + i] = l[i] * b;
        dn[12 + i] = [dl[i][0] * b, dl[i][1] * b, l[i] * db];
    }
}
