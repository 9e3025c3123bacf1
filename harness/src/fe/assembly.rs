//! Global assembly of K and M (and Rayleigh D) in CSC form with fixed DOFs eliminated,
//! and the dynamic stiffness S(ω) = K − ω²M + iωD on the same pattern.
//!
//! Sign convention for harmonic analysis: u(t) = Re(û e^{iωt}), so
//! (K + iωD − ω²M) û = f̂. Fixed DOFs are held at zero (no prescribed motion).

use std::sync::Arc;

use nalgebra::{Complex, DMatrix};
use thiserror::Error;

use crate::fe::csc::{Csc, CscPattern};
pub use crate::fe::dofs::DofMap;
use crate::fe::elements::ElementError;
use crate::fe::mesh::Model;
use crate::fe::pair_blocks::{pair_coupling, Coupling, PairBlocks};

/// Errors of assembly.
#[derive(Debug, Error, PartialEq)]
pub enum AssemblyError {
    #[error("element {element}: {source}")]
    Element {
        element: usize,
        #[source]
        source: ElementError,
    },
    #[error("node pair {index} refers to node {node}, the model has {n_nodes} nodes")]
    UnknownPairNode {
        index: usize,
        node: usize,
        n_nodes: usize,
    },
    #[error("every DOF is fixed: nothing to assemble")]
    NoFreeDofs,
    #[error("matrices are on different sparsity patterns")]
    PatternMismatch,
}

/// The assembled linear system of a model: K (force/length) and M (mass), on one
/// pattern that already contains the node-pair blocks (zero in K and M), so contact
/// springs can be added per frequency without touching the pattern.
#[derive(Debug, Clone)]
pub struct System {
    pub dofs: DofMap,
    pub pattern: Arc<CscPattern>,
    pub k: Csc<f64>,
    pub m: Csc<f64>,
    /// Value slots of the node-pair blocks given to [`assemble`].
    pub pairs: PairBlocks,
}

/// Element `e`'s stiffness K (force/length) and consistent mass M (mass), 3n × 3n in
/// its node order, by the routines of its kind (`fe::elements`).
pub fn element_matrices(
    model: &Model,
    e: usize,
) -> Result<(DMatrix<f64>, DMatrix<f64>), AssemblyError> {
    let el = &model.elements[e];
    let x = model.element_coords(e);
    let mat = &model.materials[el.material];
    let wrap = |source| AssemblyError::Element { element: e, source };
    let routines = el.kind.element();
    let ke = routines.stiffness(&x, mat).map_err(wrap)?;
    let me = routines.mass(&x, mat.density).map_err(wrap)?;
    Ok((ke, me))
}

/// (local DOF, free DOF) of element `e`'s unconstrained DOFs.
pub fn element_free_dofs(model: &Model, dofs: &DofMap, e: usize) -> Vec<(usize, usize)> {
    let nodes = &model.elements[e].nodes;
    (0..3 * nodes.len())
        .filter_map(|l| dofs.free(3 * nodes[l / 3] + l % 3).map(|f| (l, f)))
        .collect()
}

/// Assembles K and M of all elements (each by its kind's routines), eliminating
/// `model.fixed` DOFs, with pattern room for a 6×6 block between each node pair of
/// `pairs` (`[a, b]`, see [`PairBlocks`]).
pub fn assemble(model: &Model, pairs: &[[usize; 2]]) -> Result<System, AssemblyError> {
    let couplings: Vec<Coupling> = pairs.iter().map(|&p| pair_coupling(p)).collect();
    assemble_couplings(model, &couplings)
}

/// [`assemble`] with room for the blocks of general couplings (a slave node and the
/// nodes of its master face, see [`Coupling`]).
pub fn assemble_couplings(model: &Model, pairs: &[Coupling]) -> Result<System, AssemblyError> {
    let dofs = DofMap::new(&model.fixed, &model.ties);
    if dofs.n_free() == 0 {
        return Err(AssemblyError::NoFreeDofs);
    }
    for (index, p) in pairs.iter().enumerate() {
        for &(node, _) in p {
            if node >= model.nodes.len() {
                return Err(AssemblyError::UnknownPairNode {
                    index,
                    node,
                    n_nodes: model.nodes.len(),
                });
            }
        }
    }
    let elem_free = |e: usize| element_free_dofs(model, &dofs, e);
    let mut entries = Vec::new();
    for e in 0..model.elements.len() {
        let fr = elem_free(e);
        for &(_, r) in &fr {
            for &(_, c) in &fr {
                entries.push((r, c));
            }
        }
    }
    entries.extend(PairBlocks::pattern_entries(pairs, &dofs));
    let pattern = Arc::new(CscPattern::from_entries(dofs.n_free(), entries));
    let mut k = Csc::<f64>::zeros(pattern.clone());
    let mut m = Csc::<f64>::zeros(pattern.clone());
    for e in 0..model.elements.len() {
        let (ke, me) = element_matrices(model, e)?;
        let fr = elem_free(e);
        for &(lc, c) in &fr {
            for &(lr, r) in &fr {
                // In the pattern by construction.
                let slot = pattern.find(r, c).expect("element entry in pattern");
                k.values[slot] += ke[(lr, lc)];
                m.values[slot] += me[(lr, lc)];
            }
        }
    }
    let pairs = PairBlocks::new(pairs, &dofs, &pattern);
    Ok(System {
        dofs,
        pattern,
        k,
        m,
        pairs,
    })
}

impl System {
    /// Rayleigh damping D = αM + βK (α in 1/time, β in time).
    pub fn rayleigh(&self, alpha: f64, beta: f64) -> Csc<f64> {
        let values = self
            .m
            .values
            .iter()
            .zip(&self.k.values)
            .map(|(m, k)| alpha * m + beta * k)
            .collect();
        Csc {
            pattern: self.pattern.clone(),
            values,
        }
    }

    /// A complex matrix on this system's pattern, all zero (allocate once per sweep).
    pub fn complex_zeros(&self) -> Csc<Complex<f64>> {
        Csc::zeros(self.pattern.clone())
    }

    /// Writes S(ω) = K − ω²M + iωD into `out` (ω in rad/time; `damping` None = no D).
    /// Overwrites every value, allocates nothing. Node-pair blocks are added afterwards
    /// with [`PairBlocks::add`].
    pub fn dynamic_stiffness_into(
        &self,
        omega: f64,
        damping: Option<&Csc<f64>>,
        out: &mut Csc<Complex<f64>>,
    ) -> Result<(), AssemblyError> {
        if !same_pattern(&out.pattern, &self.pattern)
            || damping.is_some_and(|d| !same_pattern(&d.pattern, &self.pattern))
        {
            return Err(AssemblyError::PatternMismatch);
        }
        let w2 = omega * omega;
        for (s, (k, m)) in out
            .values
            .iter_mut()
            .zip(self.k.values.iter().zip(&self.m.values))
        {
            *s = Complex::new(k - w2 * m, 0.0);
        }
        if let Some(d) = damping {
            for (s, dv) in out.values.iter_mut().zip(&d.values) {
                s.im += omega * dv;
            }
        }
        Ok(())
    }

    /// Free part of the model's nodal loads.
    pub fn load_vector(&self, model: &Model) -> Vec<f64> {
        self.dofs.restrict(&model.loads)
    }
}

/// Same pattern: the same `Arc`, or equal contents.
pub fn same_pattern(a: &Arc<CscPattern>, b: &Arc<CscPattern>) -> bool {
    Arc::ptr_eq(a, b) || a == b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::mesh::{BoxSpec, Face, Material};
    use nalgebra::DVector;

    fn steel() -> Material {
        Material::new(210_000.0, 0.3, 7.85e-9).unwrap()
    }

    fn free_box() -> Model {
        let mut m = Model::new(vec![steel()]);
        m.add_box(BoxSpec {
            origin: [0.0, 0.0, 0.0],
            size: [10.0, 4.0, 2.0],
            divisions: [5, 2, 1],
            material: 0,
        })
        .unwrap();
        m
    }

    #[test]
    fn total_mass_and_rigid_modes_of_free_body() {
        let model = free_box();
        let sys = assemble(&model, &[]).unwrap();
        let n = sys.dofs.n_free();
        assert_eq!(n, model.n_dofs());
        let mut ux = vec![0.0; n];
        for node in 0..model.nodes.len() {
            ux[3 * node] = 1.0;
        }
        // uᵀ M u for a unit translation = total mass ρ·V (consistent M, exact Gauss).
        let mu = sys.m.mul_vec(&ux);
        let total: f64 = mu.iter().zip(&ux).map(|(a, b)| a * b).sum();
        approx::assert_relative_eq!(total, 7.85e-9 * 80.0, max_relative = 1e-13);
        // Rigid rotation about z: K u = 0 to round-off (relative to ‖K‖·‖u‖).
        let mut rot = vec![0.0; n];
        for (node, p) in model.nodes.iter().enumerate() {
            rot[3 * node] = -p[1];
            rot[3 * node + 1] = p[0];
        }
        let f = sys.k.mul_vec(&rot);
        let kmax = sys.k.values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let fmax = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(fmax < 1e-11 * kmax * 10.0, "{fmax}");
        // Symmetric.
        let kd = sys.k.to_dense();
        assert!((&kd - kd.transpose()).abs().max() <= 1e-12 * kmax);
    }

    #[test]
    fn fixed_dofs_are_eliminated_and_map_round_trips() {
        let mut model = free_box();
        let body = model.bodies[0];
        model
            .fix(&body.face_nodes(Face::XMin), [true, true, true])
            .unwrap();
        model
            .fix(&[body.node(5, 0, 0)], [false, false, true])
            .unwrap();
        let sys = assemble(&model, &[]).unwrap();
        assert_eq!(sys.dofs.n_free(), model.n_dofs() - 3 * 6 - 1);
        let full: Vec<f64> = (0..model.n_dofs()).map(|d| d as f64 + 1.0).collect();
        let back = sys.dofs.expand(&sys.dofs.restrict(&full));
        for d in 0..model.n_dofs() {
            let expect = if model.fixed[d] { 0.0 } else { full[d] };
            assert_eq!(back[d], expect);
        }
        // The reduced K equals the full K with fixed rows/columns deleted.
        let mut free_model = model.clone();
        free_model.fixed.iter_mut().for_each(|f| *f = false);
        let kfull = assemble(&free_model, &[]).unwrap().k.to_dense();
        let kred = sys.k.to_dense();
        for a in 0..sys.dofs.n_free() {
            for b in 0..sys.dofs.n_free() {
                assert_eq!(kred[(a, b)], kfull[(sys.dofs.full(a), sys.dofs.full(b))]);
            }
        }
        // Positive definite once clamped: Cholesky of the dense copy succeeds.
        assert!(kred.cholesky().is_some());
    }

    #[test]
    fn tied_nodes_share_dofs_sum_forces_and_inherit_fixes() {
        // Nodes 0–1–2 tied in a chain, node 3 free; z fixed on node 2 only.
        let mut fixed = vec![false; 12];
        fixed[3 * 2 + 2] = true;
        let d = DofMap::new(&fixed, &[[1, 2], [0, 1]]);
        assert_eq!(d.n_free(), 2 + 3);
        for c in 0..2 {
            assert_eq!(d.free(c), d.free(3 + c));
            assert_eq!(d.free(c), d.free(6 + c));
            assert_eq!(d.full(d.free(c).unwrap()), c); // numbered at the lowest node
        }
        assert!((0..3).all(|n| d.free(3 * n + 2).is_none()));
        let f: Vec<f64> = (0..12).map(|i| i as f64).collect();
        let r = d.restrict(&f);
        assert_eq!(r, vec![0.0 + 3.0 + 6.0, 1.0 + 4.0 + 7.0, 9.0, 10.0, 11.0]);
        let e = d.expand(&r);
        assert_eq!(e[0], e[3]);
        assert_eq!(e[7], 12.0);
        assert_eq!(e[8], 0.0);
    }

    #[test]
    fn dynamic_stiffness_and_rayleigh() {
        let model = free_box();
        let sys = assemble(&model, &[]).unwrap();
        let d = sys.rayleigh(2.0, 1e-5);
        let mut s = sys.complex_zeros();
        let ptr = s.values.as_ptr();
        let w = 2.0 * std::f64::consts::PI * 1000.0;
        sys.dynamic_stiffness_into(w, Some(&d), &mut s).unwrap();
        assert_eq!(ptr, s.values.as_ptr(), "values must be updated in place");
        let x: Vec<f64> = (0..sys.dofs.n_free())
            .map(|i| (i as f64 * 0.37).sin())
            .collect();
        let xc: Vec<Complex<f64>> = x.iter().map(|&v| Complex::new(v, 0.0)).collect();
        let sx = s.mul_vec(&xc);
        let kx = sys.k.mul_vec(&x);
        let mx = sys.m.mul_vec(&x);
        for i in 0..x.len() {
            // Re = Kx − ω²Mx, Im = ω(αM + βK)x; same sums in another order → round-off.
            let re = kx[i] - w * w * mx[i];
            let im = w * (2.0 * mx[i] + 1e-5 * kx[i]);
            let scale = kx.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            assert!((sx[i].re - re).abs() < 1e-12 * scale);
            assert!((sx[i].im - im).abs() < 1e-12 * scale);
        }
        let other = Csc::<f64>::zeros(Arc::new(CscPattern::from_entries(1, [(0, 0)])));
        assert_eq!(
            sys.dynamic_stiffness_into(w, Some(&other), &mut s),
            Err(AssemblyError::PatternMismatch)
        );
    }

    #[test]
    fn static_cantilever_tip_deflection() {
        // Steel 100×4×4 mm, clamped at x=0, tip load P = 10 N in −z spread on the tip
        // face nodes. Timoshenko: δ = PL³/(3EI) + PL/(κGA), κ = 5/6 (square). The
        // clamped face also stops Poisson contraction (slightly stiffer) — allow 2 %.
        let mut model = Model::new(vec![steel()]);
        model
            .add_box(BoxSpec {
                origin: [0.0; 3],
                size: [100.0, 4.0, 4.0],
                divisions: [25, 2, 2],
                material: 0,
            })
            .unwrap();
        let body = model.bodies[0];
        model.fix(&body.face_nodes(Face::XMin), [true; 3]).unwrap();
        let tip = body.face_nodes(Face::XMax);
        // Uniform shear traction P/A on the tip face (A = 16 mm²): consistent nodal
        // force = P · (tributary area / A).
        let p = 10.0;
        let area =
            crate::fe::surface::nodal_areas(&model, &body.face_quads(Face::XMax, &model.elements));
        for (node, a) in area {
            model
                .add_nodal_load(node, [0.0, 0.0, -p * a / 16.0])
                .unwrap();
        }
        let sys = assemble(&model, &[]).unwrap();
        let f = DVector::from_vec(sys.load_vector(&model));
        let u = sys.k.to_dense().cholesky().unwrap().solve(&f);
        let u = sys.dofs.expand(u.as_slice());
        let mean_tip: f64 = tip.iter().map(|&n| u[3 * n + 2]).sum::<f64>() / tip.len() as f64;
        let (e, g) = (210_000.0, steel().shear_modulus());
        let i = 4.0f64.powi(4) / 12.0;
        let exact = -(p * 100.0f64.powi(3) / (3.0 * e * i) + p * 100.0 / (5.0 / 6.0 * g * 16.0));
        let rel = (mean_tip - exact).abs() / exact.abs();
        assert!(rel < 0.02, "tip {mean_tip} vs {exact}: {rel}");
    }

    /// Patch test on a graded box (all three axes graded, ratios 8/5/3): uniaxial stress
    /// σ from a traction on x = L with symmetry planes x = 0, y = 0, z = 0 has the exact
    /// solution u = (σx/E, −νσy/E, −νσz/E), which hex8 reproduces on any box mesh; so
    /// every node must match it to round-off (1e-9 relative), whatever the grading.
    #[test]
    fn graded_box_passes_the_patch_test() {
        use crate::fe::grading::{Grading, Toward};
        let mut model = Model::new(vec![steel()]);
        let g = |ratio, toward| Grading { ratio, toward };
        model
            .add_graded_box(
                BoxSpec {
                    origin: [0.0; 3],
                    size: [12.0, 3.0, 4.0],
                    divisions: [9, 4, 5],
                    material: 0,
                },
                [
                    g(8.0, Toward::Both),
                    g(5.0, Toward::Max),
                    g(3.0, Toward::Min),
                ],
            )
            .unwrap();
        let body = model.bodies[0];
        for (face, comp) in [(Face::XMin, 0), (Face::YMin, 1), (Face::ZMin, 2)] {
            let mut c = [false; 3];
            c[comp] = true;
            model.fix(&body.face_nodes(face), c).unwrap();
        }
        let sigma = 50.0;
        let quads = body.face_quads(Face::XMax, &model.elements);
        for (node, a) in crate::fe::surface::nodal_areas(&model, &quads) {
            model.add_nodal_load(node, [sigma * a, 0.0, 0.0]).unwrap();
        }
        let sys = assemble(&model, &[]).unwrap();
        let f = DVector::from_vec(sys.load_vector(&model));
        let u = sys.k.to_dense().cholesky().unwrap().solve(&f);
        let u = sys.dofs.expand(u.as_slice());
        let (e, nu) = (210_000.0, 0.3);
        let scale = sigma * 12.0 / e;
        for (n, x) in model.nodes.iter().enumerate() {
            let exact = [
                sigma * x[0] / e,
                -nu * sigma * x[1] / e,
                -nu * sigma * x[2] / e,
            ];
            for c in 0..3 {
                let err = (u[3 * n + c] - exact[c]).abs() / scale;
                assert!(err < 1e-9, "node {n} at {x:?}, comp {c}: {err:e}");
            }
        }
    }
}
