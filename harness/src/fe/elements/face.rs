//! Faces of a mesh (element + Abaqus face label S1…S6): points, area, the tributary
//! area of each face node and pressure loads. The reference shapes and the orientation
//! convention are in [`super::face_shape`].

use std::collections::BTreeMap;

use nalgebra::Vector3;

pub use super::face_shape::{FaceDef, FaceShape, MAX_FACE_NODES};
use super::ElementKind;

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
        let def = kind.face(face)?;
        Some(MeshFace {
            element,
            face,
            nodes: def.nodes.iter().map(|&i| conn[i]).collect(),
            shape: def.shape,
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
        let quadratic = self.shape.is_quadratic();
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
