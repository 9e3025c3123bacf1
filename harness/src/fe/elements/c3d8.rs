//! C3D8 and C3D8I: the 8-node hexahedron, 2×2×2 Gauss, as the structured meshes' element
//! (`fe::hex8`) computes it, so a deck's hexahedra and the box scenes' are the same
//! matrices bit for bit; C3D8I adds the 9 incompatible modes to the stiffness.
//! VTK_HEXAHEDRON (12) has its node order.

use std::sync::LazyLock;

use nalgebra::DMatrix;

use super::face_shape::FaceDef;
use super::isoparametric::{check_nodes, hex8_error, integrated_stiffness, Isoparametric};
use super::rules::{self, QuadPoint};
use super::{hex, ElementError, ElementKind, SolidElement};
use crate::fe::hex8;
use crate::fe::material::Material;

/// The 8-node hexahedron with or without incompatible modes.
pub struct Hex8 {
    base: Isoparametric,
    /// C3D8I: the stiffness with the incompatible modes.
    incompatible: bool,
}

/// The C3D8 routines (full integration).
pub static C3D8: LazyLock<Hex8> = LazyLock::new(|| Hex8::new(ElementKind::C3D8));

/// The C3D8I routines (incompatible modes).
pub static C3D8I: LazyLock<Hex8> = LazyLock::new(|| Hex8::new(ElementKind::C3D8I));

impl Hex8 {
    fn new(kind: ElementKind) -> Self {
        Hex8 {
            base: Isoparametric {
                kind,
                corner_count: 8,
                edges: &[],
                faces: &hex::FACES8,
                vtk_cell: 12,
                shape: hex::shape8,
                stiffness_rule: rules::hex_gauss(2),
                mass_rule: rules::hex_gauss(2),
            },
            incompatible: kind == ElementKind::C3D8I,
        }
    }

    /// The corner coordinates, checked for their count.
    fn corners(&self, x: &[[f64; 3]]) -> Result<[[f64; 3]; 8], ElementError> {
        check_nodes(self.base.kind, x)?;
        Ok(std::array::from_fn(|i| x[i]))
    }
}

impl SolidElement for Hex8 {
    fn kind(&self) -> ElementKind {
        self.base.kind
    }

    fn corner_count(&self) -> usize {
        self.base.corner_count
    }

    fn edges(&self) -> &'static [(usize, usize)] {
        self.base.edges
    }

    fn faces(&self) -> &'static [FaceDef] {
        self.base.faces
    }

    fn vtk_cell(&self) -> u8 {
        self.base.vtk_cell
    }

    fn shape(&self, p: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        self.base.shape(p, n, dn)
    }

    fn stiffness_rule(&self) -> &[QuadPoint] {
        self.base.stiffness_rule()
    }

    fn mass_rule(&self) -> &[QuadPoint] {
        self.base.mass_rule()
    }

    fn mass(&self, x: &[[f64; 3]], density: f64) -> Result<DMatrix<f64>, ElementError> {
        let m = hex8::mass(&self.corners(x)?, density).map_err(|e| hex8_error(self.kind(), e))?;
        Ok(DMatrix::from_column_slice(24, 24, m.as_slice()))
    }

    fn stiffness(&self, x: &[[f64; 3]], mat: &Material) -> Result<DMatrix<f64>, ElementError> {
        if !self.incompatible {
            return integrated_stiffness(self, x, mat);
        }
        let k = hex8::stiffness(&self.corners(x)?, mat, hex8::Formulation::IncompatibleModes)
            .map_err(|e| hex8_error(self.kind(), e))?;
        Ok(DMatrix::from_column_slice(24, 24, k.as_slice()))
    }
}
