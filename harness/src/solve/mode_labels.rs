//! The character of a mode shape φ (free DOFs, from K φ = λ M φ):
//!
//! - **direction shares**: the kinetic energy φᵀMφ split by displacement direction,
//!   eᵈ = Σ_{f along d} φ_f (Mφ)_f / φᵀMφ (M couples no directions, so each is ≥ 0);
//!   the largest names the dominant direction;
//! - **effective masses** (mass): m_d = (φᵀ M r_d)² / φᵀMφ with r_d the unit rigid
//!   translation along d on the free DOFs, and **effective inertias** (mass·length²) the
//!   same with r the unit rigid rotation about axis d through the mass centre; over all
//!   modes the m_d add up to the free mass (the participation of base excitation);
//! - **kind shares**: the body's axis a is the direction of the model's largest extent;
//!   the nodes fall into cross-sections across a: one per axial node coordinate where
//!   the mesh has such planes (box meshes: on average 3 or more nodes per plane), else
//!   slabs of equal width holding about N^(2/3) of the N nodes each (graded, perturbed,
//!   tetrahedral and Gmsh meshes). Per section a rigid motion u ≈ t + θ × s (s from the
//!   section's mass centre) is fitted to the nodal displacements by weighted least
//!   squares (weights: lumped masses by diagonal scaling, HRZ: w ∝ M_ii, positive for
//!   every element — row sums are not: a C3D10's corner rows sum to less than zero). The
//!   lumped kinetic energy Σ wᵢ |uᵢ|² then splits into the fit's W|t|² + θᵀJθ (J the
//!   section's inertia tensor; the fit is an orthogonal projection in the weighted norm)
//!   and the rest: longitudinal (W t_a²), bending (W(t₁² + t₂²) and the rotation about
//!   the transverse axes, θ_t·(Jθ)_t: the section's tilt), torsion (the rotation about
//!   a, θ_a (Jθ)_a) and section (the rest: the section deforms — plate, breathing
//!   modes). On a plane section J couples no axis with a transverse one and the split is
//!   exact; on a slab the small coupling is clipped at 0. The largest share names the
//!   kind; a bending mode's plane holds the axis and the transverse direction with the
//!   larger mean-displacement energy.

use nalgebra::{Matrix3, Vector3};

use crate::fe::csc::Csc;
use crate::fe::dofs::DofMap;

/// What a mode does, by the largest kinetic-energy share of its cross-sections.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Sections move along the axis.
    Longitudinal,
    /// Sections move across the axis (and tilt), in the plane of the axis and the
    /// given transverse direction (0 x, 1 y, 2 z).
    Bending { across: usize },
    /// Sections rotate about the axis.
    Torsion,
    /// Sections deform (plate, breathing modes).
    Section,
    /// The model has one cross-section (lumped masses): no axis to speak of.
    Translation,
}

/// The character of one mode (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Character {
    /// Kinetic-energy share per direction x, y, z (sums to 1).
    pub direction_share: [f64; 3],
    /// Index (0 x, 1 y, 2 z) of the largest direction share.
    pub dominant: usize,
    /// Effective mass per translation direction x, y, z (mass).
    pub effective_mass: [f64; 3],
    /// Effective inertia per rotation axis x, y, z through the mass centre (mass·length²).
    pub effective_inertia: [f64; 3],
    /// Lumped kinetic-energy shares: longitudinal, bending, torsion, section (sum 1;
    /// all 0 for [`Kind::Translation`]: no axis).
    pub kind_share: [f64; 4],
    pub kind: Kind,
    /// The body's axis (0 x, 1 y, 2 z): the direction of the model's largest extent.
    pub axis: usize,
}

const AXES: [char; 3] = ['x', 'y', 'z'];

impl Character {
    /// Short label for tables and CSV (no spaces or commas): `longitudinal_x`,
    /// `bending_xz` (axis x, moving along z), `torsion_x`, `section`, `translation_y`.
    pub fn label(&self) -> String {
        let a = AXES[self.axis];
        match self.kind {
            Kind::Longitudinal => format!("longitudinal_{a}"),
            Kind::Bending { across } => format!("bending_{a}{}", AXES[across]),
            Kind::Torsion => format!("torsion_{a}"),
            Kind::Section => "section".to_string(),
            Kind::Translation => format!("translation_{}", AXES[self.dominant]),
        }
    }

    /// The dominant direction's name: `x`, `y` or `z`.
    pub fn dominant_name(&self) -> char {
        AXES[self.dominant]
    }
}

/// The model's geometry as the labels need it: free DOFs grouped by node.
pub struct ModeGeometry {
    /// Per representative node (the lowest of a tied group, with a free DOF): its
    /// position and its free DOF per component (None: fixed).
    nodes: Vec<([f64; 3], [Option<usize>; 3])>,
    /// Per free DOF: its component (0 x, 1 y, 2 z) and the position of its node.
    dof_comp: Vec<usize>,
    dof_pos: Vec<[f64; 3]>,
    /// Lumped mass per node: the mean of its free DOFs' row sums of M.
    node_mass: Vec<f64>,
    /// Sections: node indices (into `nodes`) per axial plane or slab, and the axis.
    sections: Vec<Vec<usize>>,
    axis: usize,
    /// Mass centre (length).
    centre: [f64; 3],
    /// Free mass per translation direction and free inertia per rotation axis: rᵀMr of
    /// the unit rigid motions, the scales below which a value is round-off.
    rigid: [[f64; 3]; 2],
}

/// Relative round-off level of a share or an effective mass.
const NOISE: f64 = 1e-12;

/// `v` with entries below `NOISE` × their scale set to 0 (round-off, e.g. 1e-35 t).
fn clip<const N: usize>(v: [f64; N], scale: [f64; N]) -> [f64; N] {
    std::array::from_fn(|i| {
        if v[i].abs() < NOISE * scale[i] {
            0.0
        } else {
            v[i]
        }
    })
}

/// Diagonal-scaled (HRZ) lumped masses of `m`: M_ii scaled so that they add up to the
/// row sums' total (the free mass); positive whenever the diagonal is.
fn hrz_lumped(m: &Csc<f64>) -> Vec<f64> {
    let p = &m.pattern;
    let diag: Vec<f64> = (0..p.n)
        .map(|i| p.find(i, i).map_or(0.0, |k| m.values[k]))
        .collect();
    let total: f64 = m.mul_vec(&vec![1.0; p.n]).iter().sum();
    let sum: f64 = diag.iter().sum();
    let scale = if sum > 0.0 { total / sum } else { 0.0 };
    diag.iter().map(|d| d * scale).collect()
}

impl ModeGeometry {
    /// `positions` per node (length), `dofs` the free-DOF map, `m` the mass matrix on
    /// the free DOFs.
    pub fn new(positions: &[[f64; 3]], dofs: &DofMap, m: &Csc<f64>) -> Self {
        let n_free = dofs.n_free();
        let lumped = hrz_lumped(m);
        let dof_comp: Vec<usize> = (0..n_free).map(|f| dofs.full(f) % 3).collect();
        let dof_pos: Vec<[f64; 3]> = (0..n_free).map(|f| positions[dofs.full(f) / 3]).collect();
        let mut nodes = Vec::new();
        let mut node_mass = Vec::new();
        for (n, &x) in positions.iter().enumerate() {
            let free: [Option<usize>; 3] = std::array::from_fn(|c| {
                dofs.free(3 * n + c).filter(|&f| dofs.full(f) == 3 * n + c)
            });
            let own: Vec<f64> = free.iter().flatten().map(|&f| lumped[f]).collect();
            if !own.is_empty() {
                nodes.push((x, free));
                node_mass.push(own.iter().sum::<f64>() / own.len() as f64);
            }
        }
        let total: f64 = node_mass.iter().sum();
        let centre: [f64; 3] = std::array::from_fn(|c| {
            if total > 0.0 {
                nodes
                    .iter()
                    .zip(&node_mass)
                    .map(|((x, _), w)| w * x[c])
                    .sum::<f64>()
                    / total
            } else {
                0.0
            }
        });
        let extent = |c: usize| {
            let (lo, hi) = nodes
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), (x, _)| {
                    (l.min(x[c]), h.max(x[c]))
                });
            (hi - lo).max(0.0)
        };
        let ext = [extent(0), extent(1), extent(2)];
        let axis = (0..3).fold(0, |b, c| if ext[c] > ext[b] { c } else { b });
        let sections = sections_along(&nodes, axis, ext[axis]);
        let mut geo = ModeGeometry {
            nodes,
            dof_comp,
            dof_pos,
            node_mass,
            sections,
            axis,
            centre,
            rigid: [[0.0; 3]; 2],
        };
        for d in 0..3 {
            for (kind, r) in [geo.translation(d), geo.rotation(d)].iter().enumerate() {
                let mr = m.mul_vec(r);
                geo.rigid[kind][d] = r.iter().zip(&mr).map(|(a, b)| a * b).sum();
            }
        }
        geo
    }

    /// Unit rigid translation along `d` on the free DOFs.
    fn translation(&self, d: usize) -> Vec<f64> {
        self.dof_comp
            .iter()
            .map(|&c| if c == d { 1.0 } else { 0.0 })
            .collect()
    }

    /// Unit rigid rotation about axis `d` through the mass centre on the free DOFs:
    /// e_d × (x − centre).
    fn rotation(&self, d: usize) -> Vec<f64> {
        self.dof_pos
            .iter()
            .zip(&self.dof_comp)
            .map(|(x, &c)| {
                let r = Vector3::from(std::array::from_fn(|i| x[i] - self.centre[i]));
                Vector3::ith(d, 1.0).cross(&r)[c]
            })
            .collect()
    }

    /// The character of mode shape `phi` (free DOFs; any scaling), `m` the mass matrix
    /// given to [`ModeGeometry::new`].
    pub fn character(&self, m: &Csc<f64>, phi: &[f64]) -> Character {
        let mphi = m.mul_vec(phi);
        let norm: f64 = phi.iter().zip(&mphi).map(|(a, b)| a * b).sum();
        let norm = norm.max(f64::MIN_POSITIVE);
        let mut direction_share = [0.0; 3];
        for (f, (&p, &mp)) in phi.iter().zip(&mphi).enumerate() {
            direction_share[self.dof_comp[f]] += p * mp / norm;
        }
        let dot = |r: Vec<f64>| r.iter().zip(&mphi).map(|(a, b)| a * b).sum::<f64>();
        let gamma_t: [f64; 3] = std::array::from_fn(|d| dot(self.translation(d)));
        let gamma_r: [f64; 3] = std::array::from_fn(|d| dot(self.rotation(d)));
        let dominant = (0..3).fold(0, |b, c| {
            if direction_share[c] > direction_share[b] {
                c
            } else {
                b
            }
        });
        let effective_mass = clip(gamma_t.map(|g| g * g / norm), self.rigid[0]);
        let effective_inertia = clip(gamma_r.map(|g| g * g / norm), self.rigid[1]);
        let direction_share = clip(direction_share, [1.0; 3]);
        let (kind_share, across) = self.kind_shares(phi);
        let kind_share = clip(kind_share, [1.0; 4]);
        let (kind, kind_share) = if self.sections.len() < 2 {
            (Kind::Translation, [0.0; 4])
        } else {
            let k = (0..4).fold(0, |b, c| if kind_share[c] > kind_share[b] { c } else { b });
            let kinds = [
                Kind::Longitudinal,
                Kind::Bending { across },
                Kind::Torsion,
                Kind::Section,
            ];
            (kinds[k], kind_share)
        };
        Character {
            direction_share,
            dominant,
            effective_mass,
            effective_inertia,
            kind_share,
            kind,
            axis: self.axis,
        }
    }

    /// Lumped kinetic-energy shares (longitudinal, bending, torsion, section) and the
    /// transverse direction of the larger mean-displacement energy.
    fn kind_shares(&self, phi: &[f64]) -> ([f64; 4], usize) {
        let a = self.axis;
        let (t1, t2) = ((a + 1) % 3, (a + 2) % 3);
        let u = |i: usize| {
            Vector3::from(std::array::from_fn(|c| {
                self.nodes[i].1[c].map_or(0.0, |f| phi[f])
            }))
        };
        let (mut long, mut bend, mut tors, mut total) = (0.0, 0.0, 0.0, 0.0);
        let mut across = [0.0; 3];
        for sec in &self.sections {
            let w: f64 = sec.iter().map(|&i| self.node_mass[i]).sum();
            if w <= 0.0 {
                continue;
            }
            let weighted = |g: &dyn Fn(usize) -> Vector3<f64>| {
                sec.iter()
                    .map(|&i| self.node_mass[i] * g(i))
                    .sum::<Vector3<f64>>()
                    / w
            };
            let centre = weighted(&|i| Vector3::from(self.nodes[i].0));
            let s = |i: usize| Vector3::from(self.nodes[i].0) - centre;
            // Rigid fit: t the weighted mean, θ = J⁺ Σ w s × u.
            let t = weighted(&u);
            let (mut j, mut moment) = (Matrix3::zeros(), Vector3::zeros());
            for &i in sec {
                let (wi, si) = (self.node_mass[i], s(i));
                j += wi * (si.norm_squared() * Matrix3::identity() - si * si.transpose());
                moment += wi * si.cross(&u(i));
                total += wi * u(i).norm_squared();
            }
            let theta = j
                .pseudo_inverse(1e-12 * j.norm().max(f64::MIN_POSITIVE))
                .map_or(Vector3::zeros(), |ji| ji * moment);
            let h = j * theta;
            long += w * t[a] * t[a];
            across[t1] += w * t[t1] * t[t1];
            across[t2] += w * t[t2] * t[t2];
            bend += w * (t[t1] * t[t1] + t[t2] * t[t2])
                + (theta[t1] * h[t1] + theta[t2] * h[t2]).max(0.0);
            tors += (theta[a] * h[a]).max(0.0);
        }
        let total = total.max(f64::MIN_POSITIVE);
        let (long, bend, tors) = (long / total, bend / total, tors / total);
        let section = (1.0 - long - bend - tors).max(0.0);
        let across = if across[t1] >= across[t2] { t1 } else { t2 };
        ([long, bend, tors, section], across)
    }
}

/// Mean nodes per axial plane from which the planes are the sections (box meshes).
const PLANE_NODES_MIN: f64 = 3.0;

/// The cross-sections of `nodes` across `axis` (extent `length`): the planes of equal
/// axial coordinate (to 1e-9 of the length) where they hold [`PLANE_NODES_MIN`] nodes
/// or more on average, else slabs of equal width holding about N^(2/3) nodes each.
fn sections_along(
    nodes: &[([f64; 3], [Option<usize>; 3])],
    axis: usize,
    length: f64,
) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..nodes.len()).collect();
    order.sort_by(|&i, &j| nodes[i].0[axis].total_cmp(&nodes[j].0[axis]));
    let tol = 1e-9 * length.max(f64::MIN_POSITIVE);
    let mut planes: Vec<Vec<usize>> = Vec::new();
    let mut last = f64::NEG_INFINITY;
    for &i in &order {
        let s = nodes[i].0[axis];
        match planes.last_mut() {
            Some(sec) if s - last <= tol => sec.push(i),
            _ => planes.push(vec![i]),
        }
        last = s;
    }
    if planes.is_empty() || nodes.len() as f64 >= PLANE_NODES_MIN * planes.len() as f64 {
        return planes;
    }
    let n = nodes.len() as f64;
    let count = (n / n.powf(2.0 / 3.0)).round().max(2.0) as usize;
    let start = nodes[order[0]].0[axis];
    let width = length.max(f64::MIN_POSITIVE) / count as f64;
    let mut slabs = vec![Vec::new(); count];
    for i in order {
        let k = ((nodes[i].0[axis] - start) / width).floor() as usize;
        slabs[k.min(count - 1)].push(i);
    }
    slabs.retain(|s| !s.is_empty());
    slabs
}

#[cfg(test)]
#[path = "mode_labels_tests.rs"]
mod tests;
