//! Element faces: the 3-, 6-, 4- and 8-node face shapes, faces of a mesh (element +
//! Abaqus face label S1…S6) and the tributary area of each face node.
//!
//! Face natural coordinates s = (s₁, s₂): triangles use s₁, s₂ ≥ 0, s₁ + s₂ ≤ 1 with
//! corners (0,0), (1,0), (0,1); quadrilaterals use [−1, 1]² with corners (−1,−1),
//! (1,−1), (1,1), (−1,1). Edge midpoints follow the corners (edge 1-2, 2-3, …).
//! In the Abaqus node order of a face, ∂x/∂s₁ × ∂x/∂s₂ points into the element, so
//! the outward normal is its negative.

use std::collections::BTreeMap;

use nalgebra::Vector3;

use super::rules::gauss_legendre;
use super::ElementKind;

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
    /// The shape of face `s` of an element type (every face of one type has one shape).
    pub fn of(kind: ElementKind) -> FaceShape {
        match (kind.is_tet(), kind.is_quadratic()) {
            (true, false) => FaceShape::Tri3,
            (true, true) => FaceShape::Tri6,
            (false, false) => FaceShape::Quad4,
            (false, true) => FaceShape::Quad8,
        }
    }

    /// Number of nodes.
    pub fn node_count(self) -> usize {
        match self {
            FaceShape::Tri3 => 3,
            FaceShape::Tri6 => 6,
            FaceShape::Quad4 => 4,
            FaceShape::Quad8 => 8,
        }
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
        let g = gauss_legendre(3);
        let mut out = Vec::with_capacity(9);
        for &(x, wx) in &g {
            for &(y, wy) in &g {
                if self.is_tri() {
                    // s₁ = u, s₂ = v(1 − u), Jacobian (1 − u); u, v ∈ [0, 1].
                    let (u, v) = (0.5 * (x + 1.0), 0.5 * (y + 1.0));
                    out.push(([u, v * (1.0 - u)], 0.25 * wx * wy * (1.0 - u)));
                } else {
                    out.push(([x, y], wx * wy));
                }
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

/// One face of a mesh element.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFace {
    /// Element index (0-based, in the mesh's element list).
    pub element: usize,
    /// Face index, 0 = S1.
    pub face: usize,
    /// Node indices (0-based, into the mesh's coordinates), Abaqus face order.
    pub nodes: Vec<usize>,
    /// The face's shape.
    pub shape: FaceShape,
}

/// A point of a face: position, the two tangents ∂x/∂s and the shape functions there.
pub struct FacePoint {
    pub x: Vector3<f64>,
    pub t1: Vector3<f64>,
    pub t2: Vector3<f64>,
    pub n: [f64; MAX_FACE_NODES],
}

impl FacePoint {
    /// Unit outward normal (−t₁ × t₂ normalised; see the module doc), None on a
    /// degenerate face.
    pub fn outward_normal(&self) -> Option<Vector3<f64>> {
        let n = -self.t1.cross(&self.t2);
        let len = n.norm();
        (len > 0.0 && len.is_finite()).then(|| n / len)
    }
}

impl MeshFace {
    /// Face `face` (0 = S1) of element `element` of type `kind` with connectivity
    /// `conn`; None if the type has no such face.
    pub fn new(kind: ElementKind, element: usize, conn: &[usize], face: usize) -> Option<Self> {
        let local = kind.face_nodes(face)?;
        Some(MeshFace {
            element,
            face,
            nodes: local.iter().map(|&i| conn[i]).collect(),
            shape: FaceShape::of(kind),
        })
    }

    /// Position, tangents and shape functions at natural point `s`.
    pub fn at(&self, coords: &[[f64; 3]], s: [f64; 2]) -> FacePoint {
        let mut n = [0.0; MAX_FACE_NODES];
        let mut dn = [[0.0; 2]; MAX_FACE_NODES];
        self.shape.shape(s, &mut n, &mut dn);
        let mut p = FacePoint {
            x: Vector3::zeros(),
            t1: Vector3::zeros(),
            t2: Vector3::zeros(),
            n,
        };
        for (i, &node) in self.nodes.iter().enumerate() {
            let x = Vector3::from(coords[node]);
            p.x += x * n[i];
            p.t1 += x * dn[i][0];
            p.t2 += x * dn[i][1];
        }
        p
    }

    /// Area (length²).
    pub fn area(&self, coords: &[[f64; 3]]) -> f64 {
        self.shape
            .rule()
            .iter()
            .map(|&(s, w)| {
                let p = self.at(coords, s);
                w * p.t1.cross(&p.t2).norm()
            })
            .sum()
    }

    /// The area each face node carries (length², summing to the face area): row sums
    /// ∫ Nᵢ dA on linear faces; on quadratic faces, where ∫ Nᵢ dA is zero or negative
    /// at the corners, the HRZ diagonal ∫ Nᵢ² dA scaled to the face area.
    pub fn nodal_areas(&self, coords: &[[f64; 3]]) -> Vec<f64> {
        let nn = self.nodes.len();
        let quadratic = matches!(self.shape, FaceShape::Tri6 | FaceShape::Quad8);
        let mut a = vec![0.0; nn];
        let mut total = 0.0;
        for (s, w) in self.shape.rule() {
            let p = self.at(coords, s);
            let da = w * p.t1.cross(&p.t2).norm();
            total += da;
            for i in 0..nn {
                a[i] += if quadratic { p.n[i] * p.n[i] } else { p.n[i] } * da;
            }
        }
        if quadratic {
            let sum: f64 = a.iter().sum();
            if sum > 0.0 {
                a.iter_mut().for_each(|v| *v *= total / sum);
            }
        }
        a
    }
}

/// Tributary area of every node of a set of faces (node index → length²), the sum of
/// its [`MeshFace::nodal_areas`] over the faces it belongs to.
pub fn tributary_areas(faces: &[MeshFace], coords: &[[f64; 3]]) -> BTreeMap<usize, f64> {
    let mut out = BTreeMap::new();
    for f in faces {
        for (node, a) in f.nodes.iter().zip(f.nodal_areas(coords)) {
            *out.entry(*node).or_insert(0.0) += a;
        }
    }
    out
}

/// Consistent nodal forces of pressure `p` (positive into the face) on `face`:
/// fᵢ = p ∫ Nᵢ (∂x/∂s₁ × ∂x/∂s₂) ds, the cross product pointing into the element in the
/// Abaqus face order (`fe::elements::face`) with the length of the area element.
pub fn add_pressure(x: &[[f64; 3]], face: &MeshFace, p: f64, f: &mut [f64]) {
    for (s, w) in face.shape.rule() {
        let fp = face.at(x, s);
        let inward: Vector3<f64> = fp.t1.cross(&fp.t2) * (w * p);
        for (i, &n) in face.nodes.iter().enumerate() {
            for c in 0..3 {
                f[3 * n + c] += fp.n[i] * inward[c];
            }
        }
    }
}
