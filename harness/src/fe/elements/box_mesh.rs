//! Structured meshes of a box in any supported element type: the reference meshes of
//! the element tests and of the decks the CalculiX comparisons write.

use std::collections::HashMap;

use super::ElementKind;
use crate::util::rng::Rng;

/// Nodes (length units) and element connectivities (0-based node indices, Abaqus order).
#[derive(Debug, Clone, PartialEq)]
pub struct SolidMesh {
    pub kind: ElementKind,
    pub nodes: Vec<[f64; 3]>,
    pub elements: Vec<Vec<usize>>,
}

/// The 6 tetrahedra of a cube split along its diagonal corner 0 → corner 6 (C3D8 local
/// numbering), one per path 0 → 6 along the edges; neighbouring cubes split their shared
/// faces alike, so the tetrahedra conform.
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 2, 6],
    [0, 2, 3, 6],
    [0, 3, 7, 6],
    [0, 7, 4, 6],
    [0, 4, 5, 6],
    [0, 5, 1, 6],
];

/// The 2 wedges of a cube split by the vertical plane through corners 0, 2, 4, 6 (C3D8
/// local numbering), their triangles counter-clockwise seen from +z; every cube is split
/// alike, so the wedges conform.
const PRISMS: [[usize; 6]; 2] = [[0, 1, 2, 4, 5, 6], [0, 2, 3, 4, 6, 7]];

/// Box [0, size] divided into `cells` hexahedral cells (tetrahedral types: 6 tets per
/// cell, wedges: 2 per cell). `jitter` moves every corner node not on the boundary by up to ±jitter × cell
/// size per component (random, seed `seed`); mid-edge nodes sit at the middle of their
/// straight edge.
pub fn box_mesh(
    kind: ElementKind,
    size: [f64; 3],
    cells: [usize; 3],
    jitter: f64,
    seed: u64,
) -> SolidMesh {
    let element = kind.element();
    let [nx, ny, nz] = cells.map(|c| c.max(1));
    let h = [
        size[0] / nx as f64,
        size[1] / ny as f64,
        size[2] / nz as f64,
    ];
    let id = |i: usize, j: usize, k: usize| i + (nx + 1) * (j + (ny + 1) * k);
    let mut rng = Rng::new(seed);
    let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1) * (nz + 1));
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let interior = [(i, nx), (j, ny), (k, nz)]
                    .iter()
                    .all(|&(a, n)| a > 0 && a < n);
                let mut p = [i as f64 * h[0], j as f64 * h[1], k as f64 * h[2]];
                if interior && jitter > 0.0 {
                    for c in 0..3 {
                        p[c] += rng.uniform(-jitter, jitter) * h[c];
                    }
                }
                nodes.push(p);
            }
        }
    }
    let mut corner_sets: Vec<Vec<usize>> = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let hex = [
                    id(i, j, k),
                    id(i + 1, j, k),
                    id(i + 1, j + 1, k),
                    id(i, j + 1, k),
                    id(i, j, k + 1),
                    id(i + 1, j, k + 1),
                    id(i + 1, j + 1, k + 1),
                    id(i, j + 1, k + 1),
                ];
                match element.corner_count() {
                    4 => {
                        for t in KUHN {
                            let mut tet: Vec<usize> = t.iter().map(|&a| hex[a]).collect();
                            if signed_volume(&nodes, &tet) < 0.0 {
                                tet.swap(1, 2);
                            }
                            corner_sets.push(tet);
                        }
                    }
                    6 => {
                        for w in PRISMS {
                            corner_sets.push(w.iter().map(|&a| hex[a]).collect());
                        }
                    }
                    _ => corner_sets.push(hex.to_vec()),
                }
            }
        }
    }
    let mut mesh = SolidMesh {
        kind,
        nodes,
        elements: Vec::new(),
    };
    let mut mids: HashMap<(usize, usize), usize> = HashMap::new();
    for corners in corner_sets {
        let mut conn = corners.clone();
        for &(a, b) in element.edges() {
            let key = (corners[a].min(corners[b]), corners[a].max(corners[b]));
            let next = mesh.nodes.len();
            let m = *mids.entry(key).or_insert(next);
            if m == next {
                let (p, q) = (mesh.nodes[key.0], mesh.nodes[key.1]);
                mesh.nodes
                    .push(std::array::from_fn(|c| 0.5 * (p[c] + q[c])));
            }
            conn.push(m);
        }
        mesh.elements.push(conn);
    }
    mesh
}

/// Six times the signed volume of the tetrahedron of the first 4 nodes of `t`.
fn signed_volume(nodes: &[[f64; 3]], t: &[usize]) -> f64 {
    let d = |a: usize| std::array::from_fn::<f64, 3, _>(|c| nodes[t[a]][c] - nodes[t[0]][c]);
    let (a, b, c) = (d(1), d(2), d(3));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

impl SolidMesh {
    /// Dense global stiffness and consistent mass (3 DOFs per node, DOF `3n + c`); for
    /// the small reference meshes of tests and comparisons.
    pub fn dense_matrices(
        &self,
        mat: &crate::fe::material::Material,
    ) -> Result<(nalgebra::DMatrix<f64>, nalgebra::DMatrix<f64>), super::ElementError> {
        self.dense_matrices_of(self.kind.element(), mat)
    }

    /// [`Self::dense_matrices`] with the element routines `e` (of this mesh's type).
    pub fn dense_matrices_of(
        &self,
        e: &dyn super::SolidElement,
        mat: &crate::fe::material::Material,
    ) -> Result<(nalgebra::DMatrix<f64>, nalgebra::DMatrix<f64>), super::ElementError> {
        let ndof = 3 * self.nodes.len();
        let mut k = nalgebra::DMatrix::zeros(ndof, ndof);
        let mut m = nalgebra::DMatrix::zeros(ndof, ndof);
        for conn in &self.elements {
            let x: Vec<[f64; 3]> = conn.iter().map(|&n| self.nodes[n]).collect();
            let ke = e.stiffness(&x, mat)?;
            let me = e.mass(&x, mat.density)?;
            for (a, &na) in conn.iter().enumerate() {
                for (b, &nb) in conn.iter().enumerate() {
                    for c in 0..3 {
                        for d in 0..3 {
                            k[(3 * na + c, 3 * nb + d)] += ke[(3 * a + c, 3 * b + d)];
                            m[(3 * na + c, 3 * nb + d)] += me[(3 * a + c, 3 * b + d)];
                        }
                    }
                }
            }
        }
        Ok((k, m))
    }
}
