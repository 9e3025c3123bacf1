//! The reference face shapes (3-, 6-, 4- and 8-node) and an element type's face: its
//! local nodes and shape.
//!
//! Face natural coordinates s = (s₁, s₂): triangles use s₁, s₂ ≥ 0, s₁ + s₂ ≤ 1 with
//! corners (0,0), (1,0), (0,1); quadrilaterals use [−1, 1]² with corners (−1,−1),
//! (1,−1), (1,1), (−1,1). Edge midpoints follow the corners (edge 1-2, 2-3, …).
//! In the Abaqus node order of a face, ∂x/∂s₁ × ∂x/∂s₂ points into the element, so
//! the outward normal is its negative.

use super::rules::{gauss_legendre, tri_collapsed_3};

/// One face of an element type: its local nodes (0-based; corners, then edge midpoints,
/// in the Abaqus order, normal into the element) and its shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FaceDef {
    pub nodes: &'static [usize],
    pub shape: FaceShape,
}

impl FaceDef {
    /// Face of `shape` through local `nodes`.
    pub const fn new(nodes: &'static [usize], shape: FaceShape) -> Self {
        FaceDef { nodes, shape }
    }

    /// The corner nodes (the edge midpoints left out).
    pub fn corners(&self) -> &'static [usize] {
        &self.nodes[..self.shape.corner_count()]
    }
}

/// The shape of a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceShape {
    Tri3,
    Tri6,
    Quad4,
    Quad8,
}

/// Most nodes on one face (Quad8).
pub const MAX_FACE_NODES: usize = 8;

impl FaceShape {
    /// Number of nodes.
    pub fn node_count(self) -> usize {
        match self {
            FaceShape::Tri3 => 3,
            FaceShape::Tri6 => 6,
            FaceShape::Quad4 => 4,
            FaceShape::Quad8 => 8,
        }
    }

    /// Number of corner nodes (3 or 4).
    pub fn corner_count(self) -> usize {
        if self.is_tri() {
            3
        } else {
            4
        }
    }

    /// True for the quadratic (mid-edge node) shapes.
    pub fn is_quadratic(self) -> bool {
        matches!(self, FaceShape::Tri6 | FaceShape::Quad8)
    }

    /// True for triangles.
    pub fn is_tri(self) -> bool {
        matches!(self, FaceShape::Tri3 | FaceShape::Tri6)
    }

    /// Natural coordinates of the centre.
    pub fn centre(self) -> [f64; 2] {
        if self.is_tri() {
            [1.0 / 3.0; 2]
        } else {
            [0.0; 2]
        }
    }

    /// Distance of natural point `s` outside the reference face (0 inside), in natural
    /// units; used to decide whether a projection lands on the face.
    pub fn outside(self, s: [f64; 2]) -> f64 {
        if self.is_tri() {
            let over = (s[0] + s[1] - 1.0).max(0.0);
            (-s[0]).max(0.0).max((-s[1]).max(0.0)).max(over)
        } else {
            (s[0].abs() - 1.0).max(s[1].abs() - 1.0).max(0.0)
        }
    }

    /// Shape functions `n[i]` and derivatives `dn[i] = ∂Nᵢ/∂(s₁, s₂)` at `s`.
    pub fn shape(self, s: [f64; 2], n: &mut [f64], dn: &mut [[f64; 2]]) {
        let [a, b] = s;
        match self {
            FaceShape::Tri3 => {
                n[..3].copy_from_slice(&[1.0 - a - b, a, b]);
                dn[..3].copy_from_slice(&[[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]]);
            }
            FaceShape::Tri6 => {
                let l = [1.0 - a - b, a, b];
                let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
                for i in 0..3 {
                    n[i] = l[i] * (2.0 * l[i] - 1.0);
                    dn[i] = dl[i].map(|d| (4.0 * l[i] - 1.0) * d);
                }
                for (e, (p, q)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                    n[3 + e] = 4.0 * l[p] * l[q];
                    for k in 0..2 {
                        dn[3 + e][k] = 4.0 * (dl[p][k] * l[q] + l[p] * dl[q][k]);
                    }
                }
            }
            FaceShape::Quad4 => {
                for (i, c) in QUAD_NODES[..4].iter().enumerate() {
                    let (u, v) = (1.0 + c[0] * a, 1.0 + c[1] * b);
                    n[i] = 0.25 * u * v;
                    dn[i] = [0.25 * c[0] * v, 0.25 * u * c[1]];
                }
            }
            FaceShape::Quad8 => {
                for (i, c) in QUAD_NODES.iter().enumerate() {
                    let (u, v) = (1.0 + c[0] * a, 1.0 + c[1] * b);
                    if i < 4 {
                        // ¼(1+s₁ᵢs₁)(1+s₂ᵢs₂)(s₁ᵢs₁ + s₂ᵢs₂ − 1)
                        let t = c[0] * a + c[1] * b - 1.0;
                        n[i] = 0.25 * u * v * t;
                        dn[i] = [0.25 * c[0] * v * (t + u), 0.25 * c[1] * u * (t + v)];
                    } else if c[0] == 0.0 {
                        n[i] = 0.5 * (1.0 - a * a) * v;
                        dn[i] = [-a * v, 0.5 * (1.0 - a * a) * c[1]];
                    } else {
                        n[i] = 0.5 * u * (1.0 - b * b);
                        dn[i] = [0.5 * c[0] * (1.0 - b * b), -b * u];
                    }
                }
            }
        }
    }

    /// Quadrature rule (points, weights): exact for degree ≤ 5 per direction on
    /// quadrilaterals (3×3 Gauss) and degree ≤ 4 on triangles (collapsed 3×3 Gauss).
    pub fn rule(self) -> Vec<([f64; 2], f64)> {
        if self.is_tri() {
            return tri_collapsed_3();
        }
        let g = gauss_legendre(3);
        let mut out = Vec::with_capacity(9);
        for &(x, wx) in &g {
            for &(y, wy) in &g {
                out.push(([x, y], wx * wy));
            }
        }
        out
    }
}

/// Natural coordinates of the Quad8 nodes (the first 4 are Quad4's).
const QUAD_NODES: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];
