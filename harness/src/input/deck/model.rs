//! The deck's data model: plain data as read, ids as in the deck (instances renumbered,
//! see [`super`]), names upper case (Abaqus names are case-insensitive), lengths,
//! forces and times in the deck's own consistent units.

use std::collections::{BTreeMap, HashMap};

use crate::fe::elements::ElementKind;

use super::error::Origin;
use crate::util::provenance::SourceFile;

/// A whole deck.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Deck {
    /// Text of `*HEADING`.
    pub heading: String,
    /// Every file the deck was read from (the deck, its `*INCLUDE` and `INPUT=` files),
    /// in reading order; empty for a deck read from text.
    pub sources: Vec<SourceFile>,
    pub nodes: Vec<Node>,
    pub elements: Vec<Element>,
    /// Node id → index in `nodes`.
    pub node_index: HashMap<u64, usize>,
    /// Element id → index in `elements`.
    pub element_index: HashMap<u64, usize>,
    /// Node set name → node ids (in the order given, without repeats).
    pub node_sets: BTreeMap<String, Vec<u64>>,
    /// Element set name → element ids.
    pub element_sets: BTreeMap<String, Vec<u64>>,
    pub surfaces: BTreeMap<String, Surface>,
    pub materials: BTreeMap<String, MaterialDef>,
    pub sections: Vec<Section>,
    pub interactions: BTreeMap<String, Interaction>,
    pub contact_pairs: Vec<ContactPair>,
    pub ties: Vec<Tie>,
    /// Boundary conditions given before the first step (model data).
    pub boundaries: Vec<Boundary>,
    pub steps: Vec<Step>,
}

/// A node: id and coordinates (length).
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    pub id: u64,
    pub x: [f64; 3],
}

/// An element: id, type, node ids in Abaqus order, and where it was defined.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    pub id: u64,
    pub kind: ElementKind,
    pub nodes: Vec<u64>,
    pub origin: Origin,
}

/// A surface: element faces or nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    pub name: String,
    pub kind: SurfaceKind,
    pub origin: Origin,
}

/// The two `*SURFACE` types.
#[derive(Debug, Clone, PartialEq)]
pub enum SurfaceKind {
    /// TYPE=ELEMENT: (element id, face index 0 = S1).
    Element(Vec<(u64, usize)>),
    /// TYPE=NODE: (node id, area or None for 1).
    Node(Vec<(u64, Option<f64>)>),
}

/// `*MATERIAL` with its `*ELASTIC`, `*DENSITY`, `*DAMPING`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MaterialDef {
    pub name: String,
    /// (E in force/length², ν).
    pub elastic: Option<(f64, f64)>,
    /// Mass per volume.
    pub density: Option<f64>,
    /// Rayleigh damping: α (1/time, mass-proportional), β (time, stiffness-proportional).
    pub damping: Option<(f64, f64)>,
    /// Structural (hysteretic) damping factor s: i·s times the material's stiffness in
    /// a steady-state step (`*DAMPING, STRUCTURAL=`), dimensionless.
    pub structural: Option<f64>,
    pub origin: Origin,
}

/// `*SOLID SECTION, ELSET=, MATERIAL=`.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    pub element_set: String,
    pub material: String,
    pub origin: Origin,
}

/// `*SURFACE INTERACTION` (USER: the PROPS table of fortran-shim/README.md).
#[derive(Debug, Clone, PartialEq)]
pub struct Interaction {
    pub name: String,
    pub user: bool,
    /// DEPVAR= (solution-dependent state variables per point).
    pub depvar: usize,
    /// The property table PROPS(1…PROPERTIES).
    pub properties: Vec<f64>,
    /// The first data line (out-of-plane thickness as Abaqus/CAE writes it), if given.
    pub thickness: Option<f64>,
    pub origin: Origin,
}

/// `*CONTACT PAIR, INTERACTION=`: slave surface, master surface.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPair {
    pub interaction: String,
    pub slave: String,
    pub master: String,
    pub small_sliding: bool,
    pub origin: Origin,
}

/// `*TIE, NAME=`: slave surface tied to the master surface in all DOFs.
#[derive(Debug, Clone, PartialEq)]
pub struct Tie {
    pub name: String,
    pub slave: String,
    pub master: String,
    /// POSITION TOLERANCE= (length), if given.
    pub position_tolerance: Option<f64>,
    /// `TYPE=SURFACE TO SURFACE`: allowed only where the tie is conforming.
    pub surface_to_surface: bool,
    pub origin: Origin,
}

/// A node or a node set.
#[derive(Debug, Clone, PartialEq)]
pub enum NodeTarget {
    Node(u64),
    Set(String),
}

/// `*BOUNDARY`: DOFs `first..=last` (1 = x … 6 = rotation z) of a target held at `value`.
#[derive(Debug, Clone, PartialEq)]
pub struct Boundary {
    pub target: NodeTarget,
    pub first: u8,
    pub last: u8,
    /// Prescribed displacement (length); 0 for the named conditions.
    pub value: f64,
    pub origin: Origin,
}

/// `*CLOAD`: force (force units) in DOF `dof` at a node or on every node of a set.
#[derive(Debug, Clone, PartialEq)]
pub struct CLoad {
    pub target: NodeTarget,
    pub dof: u8,
    pub value: f64,
    /// The imaginary (out-of-phase) part of a steady-state load (`IMAGINARY`): a load
    /// Re + i Im acts as Re cos ωt − Im sin ωt.
    pub imaginary: bool,
    pub origin: Origin,
}

/// `*DLOAD, Pn`: pressure (force/length², positive into the face) on face n of an
/// element or of every element of a set.
#[derive(Debug, Clone, PartialEq)]
pub struct DLoad {
    /// Element id or element set.
    pub elements: ElementTarget,
    /// Face index, 0 = S1.
    pub face: usize,
    pub pressure: f64,
    /// The imaginary part (`IMAGINARY`), as for [`CLoad`].
    pub imaginary: bool,
    pub origin: Origin,
}

/// An element or an element set.
#[derive(Debug, Clone, PartialEq)]
pub enum ElementTarget {
    Element(u64),
    Set(String),
}

/// `*DSLOAD, P`: pressure (force/length², positive into the surface) on a surface.
#[derive(Debug, Clone, PartialEq)]
pub struct DsLoad {
    pub surface: String,
    pub pressure: f64,
    /// The imaginary part (`IMAGINARY`), as for [`CLoad`].
    pub imaginary: bool,
    pub origin: Origin,
}

/// Spacing of the steady-state frequency points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrequencyScale {
    Linear,
    Logarithmic,
}

/// The analysis of a step.
#[derive(Debug, Clone, PartialEq)]
pub enum Procedure {
    /// `*STATIC`: the preload step.
    Static,
    /// `*FREQUENCY`: the lowest `modes` eigenpairs.
    Frequency { modes: usize },
    /// `*STEADY STATE DYNAMICS`: one frequency range per data line, run in the order
    /// given, spaced by `scale`; `direct` (DIRECT: a solve per frequency) or mode-based
    /// on the preceding `*FREQUENCY` step's modes; each range divided at the
    /// eigenfrequencies inside it (`eigen_intervals`, INTERVAL=EIGENFREQUENCY, the
    /// default without DIRECT) or as a whole.
    SteadyState {
        ranges: Vec<FrequencyRange>,
        scale: FrequencyScale,
        direct: bool,
        eigen_intervals: bool,
    },
}

/// One data line of `*MODAL DAMPING` (viscous, by mode numbers): modes `first`…`last`
/// (blank: every mode) get the fraction of critical damping `ratio`, or with RAYLEIGH
/// ζ_r = α/(2ω_r) + βω_r/2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalDamping {
    pub first: Option<usize>,
    pub last: Option<usize>,
    pub ratio: f64,
    pub alpha: f64,
    pub beta: f64,
}

/// One data line of `*STEADY STATE DYNAMICS, DIRECT` as Abaqus reads it: f_low … f_high
/// (cycles/time) at `points` points including both ends, `bias` (1 = uniform); an upper
/// limit given as zero or left blank asks for the single frequency f_low (`points` 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrequencyRange {
    pub f_low: f64,
    pub f_high: f64,
    pub points: usize,
    pub bias: f64,
}

/// Node output request: the variables (e.g. U) of a node set.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    pub node_set: String,
    pub variables: Vec<String>,
    pub origin: Origin,
}

/// `*STEP … *END STEP`.
#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    pub name: String,
    pub perturbation: bool,
    pub procedure: Procedure,
    pub boundaries: Vec<Boundary>,
    pub cloads: Vec<CLoad>,
    pub dloads: Vec<DLoad>,
    pub dsloads: Vec<DsLoad>,
    pub outputs: Vec<Output>,
    /// `*MODAL DAMPING` lines of the step, with the card's origin.
    pub modal_damping: Vec<(ModalDamping, Origin)>,
    pub origin: Origin,
}

impl Deck {
    /// Number of elements of each type.
    pub fn element_counts(&self) -> BTreeMap<ElementKind, usize> {
        let mut out = BTreeMap::new();
        for e in &self.elements {
            *out.entry(e.kind).or_insert(0) += 1;
        }
        out
    }

    /// Coordinates of node `id`, if defined.
    pub fn node(&self, id: u64) -> Option<[f64; 3]> {
        self.node_index.get(&id).map(|&i| self.nodes[i].x)
    }
}
