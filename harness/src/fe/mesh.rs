//! Structured 8-node hexahedral meshes of axis-aligned boxes, bodies stacked in z,
//! and the [`Model`] that holds nodes, elements (any kind of `fe::elements`: the boxes'
//! hexahedra, or a deck's elements), materials, fixed DOFs and nodal loads.
//!
//! Numbering inside a body with divisions (nx, ny, nz): grid node (i, j, k) is
//! `first_node + i + (nx+1)·(j + (ny+1)·k)`, element (i, j, k) is
//! `first_element + i + nx·(j + ny·k)`. Every body owns its nodes: two stacked bodies
//! have **coincident but distinct** nodes on their interface (to be tied or put in
//! contact by node-pair blocks, never merged).
//!
//! Element node order is Abaqus C3D8's: corners at (ξ, η, ζ) =
//! (−−−), (+−−), (++−), (−+−), (−−+), (+−+), (+++), (−++).

use crate::fe::elements::ElementKind;
pub use crate::fe::error::MeshError;
use crate::fe::grading::Grading;
pub use crate::fe::material::Material;

/// An axis-aligned box occupying `origin .. origin + size`, divided into
/// `divisions` hex8 elements per axis (equal ones, or graded by
/// [`Model::add_graded_box`]), of material index `material`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxSpec {
    pub origin: [f64; 3],
    pub size: [f64; 3],
    pub divisions: [usize; 3],
    pub material: usize,
}

/// A face of an axis-aligned box, named by its outward normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Face {
    XMin,
    XMax,
    YMin,
    YMax,
    ZMin,
    ZMax,
}

impl Face {
    /// The six faces.
    pub const ALL: [Face; 6] = [
        Face::XMin,
        Face::XMax,
        Face::YMin,
        Face::YMax,
        Face::ZMin,
        Face::ZMax,
    ];

    /// Axis (0, 1, 2) the face is normal to.
    pub fn axis(self) -> usize {
        match self {
            Face::XMin | Face::XMax => 0,
            Face::YMin | Face::YMax => 1,
            Face::ZMin | Face::ZMax => 2,
        }
    }

    /// Unit outward normal.
    pub fn outward_normal(self) -> [f64; 3] {
        let mut n = [0.0; 3];
        n[self.axis()] = if self.is_max() { 1.0 } else { -1.0 };
        n
    }

    fn is_max(self) -> bool {
        matches!(self, Face::XMax | Face::YMax | Face::ZMax)
    }

    /// Local corner indices (C3D8 order) of this face of an element, counter-clockwise
    /// seen from outside, so (p1−p0)×(p3−p0) points outward; reversed from the first
    /// corner, `[c0, c3, c2, c1]`, they are the element's Abaqus face S1…S6
    /// (`fe::elements::hex::FACES20`).
    pub fn element_corners(self) -> [usize; 4] {
        match self {
            Face::XMin => [3, 0, 4, 7],
            Face::XMax => [1, 2, 6, 5],
            Face::YMin => [0, 1, 5, 4],
            Face::YMax => [2, 3, 7, 6],
            Face::ZMin => [0, 3, 2, 1],
            Face::ZMax => [4, 5, 6, 7],
        }
    }
}

/// One body (box) of a [`Model`]: where its nodes and elements start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    pub spec: BoxSpec,
    /// Per axis: how the element sizes vary along it.
    pub grading: [Grading; 3],
    pub first_node: usize,
    pub first_element: usize,
}

impl Body {
    /// The smallest element edge along axis `a` (length).
    pub fn smallest_edge(&self, a: usize) -> f64 {
        self.spec.size[a] * self.grading[a].smallest_fraction(self.spec.divisions[a])
    }

    /// The smallest element edge over all axes (length).
    pub fn smallest_element_edge(&self) -> f64 {
        (0..3)
            .map(|a| self.smallest_edge(a))
            .fold(f64::INFINITY, f64::min)
    }

    /// Number of nodes (nx+1)(ny+1)(nz+1).
    pub fn n_nodes(&self) -> usize {
        let [nx, ny, nz] = self.spec.divisions;
        (nx + 1) * (ny + 1) * (nz + 1)
    }

    /// Number of elements nx·ny·nz.
    pub fn n_elements(&self) -> usize {
        let [nx, ny, nz] = self.spec.divisions;
        nx * ny * nz
    }

    /// Global node id of grid node (i, j, k), 0 ≤ i ≤ nx etc.
    pub fn node(&self, i: usize, j: usize, k: usize) -> usize {
        let [nx, ny, _] = self.spec.divisions;
        self.first_node + i + (nx + 1) * (j + (ny + 1) * k)
    }

    /// Global element id of grid element (i, j, k), 0 ≤ i < nx etc.
    pub fn element(&self, i: usize, j: usize, k: usize) -> usize {
        let [nx, ny, _] = self.spec.divisions;
        self.first_element + i + nx * (j + ny * k)
    }

    /// Global node ids on a face, ordered with the lower of the two in-face axes
    /// running fastest.
    pub fn face_nodes(&self, face: Face) -> Vec<usize> {
        let [nx, ny, nz] = self.spec.divisions;
        let fixed = if face.is_max() {
            self.spec.divisions[face.axis()]
        } else {
            0
        };
        let mut out = Vec::new();
        match face.axis() {
            0 => {
                for k in 0..=nz {
                    for j in 0..=ny {
                        out.push(self.node(fixed, j, k));
                    }
                }
            }
            1 => {
                for k in 0..=nz {
                    for i in 0..=nx {
                        out.push(self.node(i, fixed, k));
                    }
                }
            }
            _ => {
                for j in 0..=ny {
                    for i in 0..=nx {
                        out.push(self.node(i, j, fixed));
                    }
                }
            }
        }
        out
    }

    /// The element faces lying on a body face: 4 global node ids each,
    /// counter-clockwise seen from outside (for `fe::surface`).
    pub fn face_quads(&self, face: Face, elements: &[Element]) -> Vec<[usize; 4]> {
        let [nx, ny, nz] = self.spec.divisions;
        let axis = face.axis();
        let fixed = if face.is_max() {
            self.spec.divisions[axis] - 1
        } else {
            0
        };
        let corners = face.element_corners();
        let mut out = Vec::new();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let ijk = [i, j, k];
                    if ijk[axis] != fixed {
                        continue;
                    }
                    let e = self.element(i, j, k);
                    let en = &elements[e].nodes;
                    out.push(corners.map(|c| en[c]));
                }
            }
        }
        out
    }
}

/// A solid element: its formulation, global node ids in the Abaqus order of its kind
/// (C3D8 order for the boxes' hexahedra) and a material index.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    /// Which element routines assemble it (`fe::elements`); the boxes' hexahedra are
    /// C3D8I, the incompatible-modes element of [`crate::fe::hex8`].
    pub kind: ElementKind,
    pub nodes: Vec<usize>,
    pub material: usize,
}

/// One layer of a z-stack: thickness (length), divisions through it, material index.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layer {
    pub thickness: f64,
    pub nz: usize,
    pub material: usize,
}

/// All bodies' nodes (3 DOF each: full DOF `3n + c`), elements, materials, fixed DOFs
/// and nodal loads (force units, in global axes).
#[derive(Debug, Clone, Default)]
pub struct Model {
    pub nodes: Vec<[f64; 3]>,
    pub elements: Vec<Element>,
    pub materials: Vec<Material>,
    pub bodies: Vec<Body>,
    /// `fixed[3n + c]`: DOF held at zero displacement.
    pub fixed: Vec<bool>,
    /// `loads[3n + c]`: nodal force (static amplitude or harmonic amplitude).
    pub loads: Vec<f64>,
    /// Tied node pairs: coincident nodes of touching bodies that move as one (the
    /// assembly gives them one set of DOFs, see `fe::ties`).
    pub ties: Vec<[usize; 2]>,
}

impl Model {
    /// An empty model with these materials.
    pub fn new(materials: Vec<Material>) -> Self {
        Model {
            materials,
            ..Default::default()
        }
    }

    /// Total number of DOFs, 3 per node.
    pub fn n_dofs(&self) -> usize {
        3 * self.nodes.len()
    }

    /// Meshes a box of equal elements as a new body with its own nodes; returns the
    /// body index.
    pub fn add_box(&mut self, spec: BoxSpec) -> Result<usize, MeshError> {
        self.add_graded_box(spec, [Grading::UNIFORM; 3])
    }

    /// Meshes a box with the element sizes graded per axis as a new body with its own
    /// nodes; returns the body index.
    pub fn add_graded_box(
        &mut self,
        spec: BoxSpec,
        grading: [Grading; 3],
    ) -> Result<usize, MeshError> {
        if spec.size.iter().any(|&s| !(s.is_finite() && s > 0.0))
            || spec.origin.iter().any(|o| !o.is_finite())
        {
            return Err(MeshError::BadSize(spec.size));
        }
        if spec.divisions.contains(&0) {
            return Err(MeshError::BadDivisions(spec.divisions));
        }
        if let Some(g) = grading.iter().find(|g| !g.is_valid()) {
            return Err(MeshError::BadGrading(g.ratio));
        }
        if spec.material >= self.materials.len() {
            return Err(MeshError::UnknownMaterial(spec.material));
        }
        let body = Body {
            spec,
            grading,
            first_node: self.nodes.len(),
            first_element: self.elements.len(),
        };
        let [nx, ny, nz] = spec.divisions;
        // Grid lines per axis; the last fraction is exactly 1, so the last line is
        // exactly origin + size and stacked bodies' interface nodes coincide bit for bit.
        let lines: [Vec<f64>; 3] = std::array::from_fn(|a| {
            grading[a]
                .fractions(spec.divisions[a])
                .iter()
                .map(|t| spec.origin[a] + t * spec.size[a])
                .collect()
        });
        for k in 0..=nz {
            for j in 0..=ny {
                for i in 0..=nx {
                    self.nodes.push([lines[0][i], lines[1][j], lines[2][k]]);
                }
            }
        }
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let n = |di: usize, dj: usize, dk: usize| body.node(i + di, j + dj, k + dk);
                    self.elements.push(Element {
                        kind: ElementKind::C3D8I,
                        nodes: vec![
                            n(0, 0, 0),
                            n(1, 0, 0),
                            n(1, 1, 0),
                            n(0, 1, 0),
                            n(0, 0, 1),
                            n(1, 0, 1),
                            n(1, 1, 1),
                            n(0, 1, 1),
                        ],
                        material: spec.material,
                    });
                }
            }
        }
        self.fixed.resize(self.n_dofs(), false);
        self.loads.resize(self.n_dofs(), 0.0);
        self.bodies.push(body);
        Ok(self.bodies.len() - 1)
    }

    /// Stacks boxes of common footprint `lx × ly` (divided `nx × ny`) in +z from
    /// `origin`, one body per layer; returns the body indices bottom to top.
    /// Interface nodes of neighbouring layers coincide exactly but stay distinct.
    pub fn add_stack(
        &mut self,
        origin: [f64; 3],
        footprint: [f64; 2],
        divisions: [usize; 2],
        layers: &[Layer],
    ) -> Result<Vec<usize>, MeshError> {
        let mut z = origin[2];
        let mut ids = Vec::with_capacity(layers.len());
        for layer in layers {
            let id = self.add_box(BoxSpec {
                origin: [origin[0], origin[1], z],
                size: [footprint[0], footprint[1], layer.thickness],
                divisions: [divisions[0], divisions[1], layer.nz],
                material: layer.material,
            })?;
            ids.push(id);
            // The next layer starts exactly at this layer's top grid line.
            let b = self.bodies[id];
            z = self.nodes[b.first_node + b.n_nodes() - 1][2];
        }
        Ok(ids)
    }

    /// Body by index.
    pub fn body(&self, id: usize) -> Result<&Body, MeshError> {
        self.bodies.get(id).ok_or(MeshError::UnknownBody(id))
    }

    /// Node ids whose coordinates satisfy `pred`.
    pub fn nodes_where(&self, pred: impl Fn([f64; 3]) -> bool) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&n| pred(self.nodes[n]))
            .collect()
    }

    /// Holds components `comps` (x, y, z) of these nodes at zero.
    pub fn fix(&mut self, nodes: &[usize], comps: [bool; 3]) -> Result<(), MeshError> {
        for &n in nodes {
            if n >= self.nodes.len() {
                return Err(MeshError::UnknownNode(n));
            }
            for c in 0..3 {
                if comps[c] {
                    self.fixed[3 * n + c] = true;
                }
            }
        }
        Ok(())
    }

    /// Adds force `f` (global axes) to node `n`'s load.
    pub fn add_nodal_load(&mut self, n: usize, f: [f64; 3]) -> Result<(), MeshError> {
        if n >= self.nodes.len() {
            return Err(MeshError::UnknownNode(n));
        }
        for c in 0..3 {
            self.loads[3 * n + c] += f[c];
        }
        Ok(())
    }

    /// The node coordinates of element `e`, in its node order.
    pub fn element_coords(&self, e: usize) -> Vec<[f64; 3]> {
        self.elements[e]
            .nodes
            .iter()
            .map(|&n| self.nodes[n])
            .collect()
    }
}

#[cfg(test)]
#[path = "mesh_tests.rs"]
mod tests;
