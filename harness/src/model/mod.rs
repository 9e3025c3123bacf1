//! The assembled problem of a scene: mesh and lumped bodies, K, M, material damping,
//! contact points with frames and areas, preload and excitation vectors, outputs.
//!
//! Built by [`build()`] from a validated [`crate::input::scene::Scene`]. Units are the scene's. Contact points
//! follow `fe::contact_pairs`: δ = u_upper − u_lower, frame Q = [n t₁ t₂] with n from the
//! lower body into the upper one; a ground–mass interface has the fixed ground node as
//! its lower side.

mod build;
pub mod craig_bampton;
mod damping;
pub mod deck;
pub mod job;
mod kind;
mod locate;
pub mod lumped;
mod lumped_ends;
pub mod lumped_joints;
pub mod lumped_static;
pub mod lumped_system;
pub mod screw_load;
pub mod subgrid;
mod variants;

pub use build::{mesh_face, PAIR_TOL};
pub use job::Job;
pub use kind::{kind, model, Built, Kind};
pub use locate::locate;

/// The problem of a scene or deck ([`build::build`]; a lumped scene is refused), its warnings joined by a note on
/// each material whose E or ρ lies far outside those of solids in the stated units
/// ([`unit_names::implausible_material`]).
pub fn build(scene: &Scene) -> Result<Problem, BuildError> {
    if kind(scene) == Kind::Lumped {
        return Err(BuildError::Other(
            "a lumped system ([[matrices]], [[joints]], springs `between` two bodies) has no FE model: `jointlin run` (first order, harmonic balance or --time-domain), `tradeoff`, `modes` and `backbone` take it"
                .into(),
        ));
    }
    let mut p = build::build(scene)?;
    let units = &scene.spec.units;
    let materials: Vec<(String, f64, f64)> = match &scene.deck {
        Some(job) => job
            .deck
            .materials
            .values()
            .filter_map(|m| Some((m.name.clone(), m.elastic?.0, m.density.unwrap_or(0.0))))
            .collect(),
        None => scene
            .spec
            .materials
            .iter()
            .map(|(name, m)| (name.clone(), m.e, m.rho))
            .collect(),
    };
    p.warnings.extend(
        materials
            .iter()
            .filter_map(|(name, e, rho)| unit_names::implausible_material(units, name, *e, *rho)),
    );
    Ok(p)
}

/// The id of each model node as the user knows it: a deck's own node ids (node i is the
/// deck's i-th), else i + 1 (the numbering `jointlin export` writes).
pub fn node_ids(scene: &Scene, p: &Problem) -> Vec<u64> {
    match &scene.deck {
        Some(job) => job.deck.nodes.iter().map(|n| n.id).collect(),
        None => (1..=p.model.nodes.len() as u64).collect(),
    }
}

use nalgebra::{Complex, Matrix3};
use thiserror::Error;

use crate::fe::assembly::{AssemblyError, System};
use crate::fe::contact_pairs::PairError;
use crate::fe::csc::Csc;
use crate::fe::mesh::{MeshError, Model};
use crate::input::scene::Scene;
use crate::names::ContactLaw;
use crate::settings::unit_names;

/// Errors building a problem from a (valid) scene: mesh-level inconsistencies.
#[derive(Debug, Error)]
pub enum BuildError {
    #[error(transparent)]
    Mesh(#[from] MeshError),
    #[error("interface `{name}`: {source}")]
    Pairs {
        name: String,
        #[source]
        source: PairError,
    },
    #[error(transparent)]
    Assembly(#[from] AssemblyError),
    #[error("tie {a}–{b}: {source}")]
    Tie {
        a: String,
        b: String,
        #[source]
        source: crate::fe::ties::TieError,
    },
    #[error("screw `{name}`: {source}")]
    Screw {
        name: String,
        #[source]
        source: crate::capi::CapiError,
    },
    #[error(transparent)]
    Deck(#[from] crate::input::deck::DeckError),
    /// A lumped system's (`lumped::build`): the `[[matrices]]` files name file:line.
    #[error("{0}")]
    Lumped(String),
    #[error("{0}")]
    Other(String),
}

/// One interface: its name, contact law and initial gap.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    pub name: String,
    /// The law in stress form (per unit area).
    pub contact: ContactLaw,
    /// Initial normal gap g₀ (length): overclosure h = −δ_n − g₀.
    pub initial_gap: f64,
}

/// One contact point: a node pair with a local frame and a tributary area.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPoint {
    /// Index of the pair in `System::pairs`.
    pub pair: usize,
    /// `[lower, upper]` node ids.
    pub nodes: [usize; 2],
    /// Columns n, t₁, t₂ (global axes).
    pub frame: Matrix3<f64>,
    /// Tributary area (length²).
    pub area: f64,
    /// Index into `Problem::interfaces`.
    pub interface: usize,
    /// Position (length), for reports.
    pub position: [f64; 3],
    /// Local relative displacement component c (n, t₁, t₂) = Σ w·u_free: the sparse rows
    /// of the map B (u_free → Qᵀ(u_upper − u_lower)); fixed DOFs are left out.
    pub rows: [Vec<(usize, f64)>; 3],
    /// Sub-grid samples of the tributary area (empty: the node value stands for all of
    /// it), see [`subgrid`].
    pub samples: Vec<subgrid::AreaSample>,
}

impl ContactPoint {
    /// Local component `c` of the relative displacement for free-DOF vector `u`.
    pub fn relative<T>(&self, c: usize, u: &[T]) -> T
    where
        T: Copy + std::ops::Mul<f64, Output = T> + std::iter::Sum<T>,
    {
        self.rows[c].iter().map(|&(i, w)| u[i] * w).sum()
    }
}

/// A grounded spring with a cubic term α (scene `[[springs]]` with `cubic`): its linear
/// stiffness k is in K (static step, stuck modes); the steady-state step adds
/// (k* − k)·d dᵀ with k* = k + ¾αA² from the C API for its amplitude A (3.8).
#[derive(Debug, Clone, PartialEq)]
pub struct CubicSpring {
    /// Index in the scene's `[[springs]]`.
    pub spring: usize,
    /// Index of the mass's ground pair in `System::pairs`.
    pub pair: usize,
    /// The mass node.
    pub node: usize,
    /// Position (length), the key of the spring in the iteration store.
    pub position: [f64; 3],
    /// k (force/length).
    pub stiffness: f64,
    /// α (force/length³).
    pub cubic: f64,
    /// d dᵀ (unit direction d).
    pub block: Matrix3<f64>,
    /// Elongation x = Σ w·u_free along d (fixed DOFs left out).
    pub row: Vec<(usize, f64)>,
}

/// A named output: displacement along a direction at one node, as free-DOF weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    pub name: String,
    pub node: usize,
    pub dofs: Vec<(usize, f64)>,
}

impl Output {
    /// The output's complex displacement for free-DOF vector `u`.
    pub fn value(&self, u: &[Complex<f64>]) -> Complex<f64> {
        self.dofs.iter().map(|&(i, w)| u[i] * w).sum()
    }
}

/// A screw's preload as built: the force from its torque and where it acts.
#[derive(Debug, Clone, PartialEq)]
pub struct Screw {
    pub name: String,
    /// Axial preload of the whole screw from the torque (force).
    pub preload: f64,
    /// Force applied in this model: preload × share (force).
    pub applied: f64,
    /// Nodes of the head side and their shares of the force (summing to 1).
    pub head: Vec<(usize, f64)>,
    /// Nodes of the nut (thread) side and their shares of the force (summing to 1).
    pub nut: Vec<(usize, f64)>,
}

/// Everything the static and steady-state steps need.
#[derive(Debug, Clone)]
pub struct Problem {
    pub model: Model,
    /// K and M (with lumped masses and springs), pattern with room for all pair blocks.
    pub sys: System,
    /// Material (Rayleigh, per material) plus dashpot damping; `None` when the
    /// `material_damping` effect is off or nothing damps.
    pub damping: Option<Csc<f64>>,
    /// Structural (hysteretic) damping Σ sₘ Kₘ of the materials (a deck's `*DAMPING,
    /// STRUCTURAL=`): i times it joins the dynamic stiffness at every frequency ω > 0
    /// (force/length); `None` when nothing damps so or `material_damping` is off. It has
    /// no time-domain form.
    pub structural: Option<Csc<f64>>,
    /// Modal damping of the stuck modes (`[sweep] modal_damping`, a deck's `*MODAL
    /// DAMPING`): applied by the modal route only.
    pub modal_damping: Vec<crate::settings::ModalDampingSpec>,
    pub interfaces: Vec<Interface>,
    pub contacts: Vec<ContactPoint>,
    pub cubic_springs: Vec<CubicSpring>,
    /// Static preload on the free DOFs (force).
    pub preload: Vec<f64>,
    /// Harmonic excitation amplitude on the free DOFs (force, complex for phase).
    pub excitation: Vec<Complex<f64>>,
    pub outputs: Vec<Output>,
    pub screws: Vec<Screw>,
    /// What the build could not honour exactly and says so (a deck's slave nodes that
    /// project onto no master face, contact gaps taken as closed), for the run log.
    pub warnings: Vec<String>,
    /// What a deck asks that a run has no use for and loses nothing by (output requests
    /// for Abaqus's own files), for the run log.
    pub notes: Vec<String>,
}

impl Problem {
    /// Whether any contact point is sampled over its area (`area_samples`).
    pub fn has_area_samples(&self) -> bool {
        self.contacts.iter().any(|c| !c.samples.is_empty())
    }
}

#[cfg(test)]
pub(crate) mod tests;
