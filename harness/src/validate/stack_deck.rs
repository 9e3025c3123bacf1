//! The non-conforming three-layer stack of the deck comparisons with CalculiX: three
//! steel plates 100 × 10 × 2 mm stacked in z (N, mm, s, t), each meshed with its own
//! density of C3D20 elements so that no interface conforms, clamped at x = 0; the
//! layers joined by `*TIE`, by `*CONTACT PAIR` with the jointlin USER interaction, or
//! not at all (one layer alone: the free-sliding bound, the layers bending each about
//! its own axis).

use std::fmt::Write as _;

use crate::fe::elements::box_mesh::box_mesh;
use crate::fe::elements::ElementKind;

use super::mesh_cards::mesh_cards;

/// Plate length, width, thickness (mm).
pub const SIZE: [f64; 3] = [100.0, 10.0, 2.0];
/// Elements (x, y) per layer, bottom to top: different, so the interfaces do not conform.
pub const CELLS: [[usize; 2]; 3] = [[10, 2], [13, 3], [16, 2]];
/// Steel: E (MPa), ν, ρ (t/mm³).
pub const STEEL: (f64, f64, f64) = (210_000.0, 0.3, 7.85e-9);

/// How the layers are joined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Joining {
    /// `*TIE`, each upper layer's bottom (slave) to the lower layer's top (master).
    Tie,
    /// `*CONTACT PAIR` with the USER interaction (Jenkins, thesis rule, linear normal law):
    /// μ, k_T0 and k_N per area (N/mm³), pressed by `pressure` (MPa) on the top and the
    /// bottom face in a static step.
    Contact {
        mu: f64,
        k_t0: f64,
        k_n: f64,
        pressure: f64,
    },
    /// The bottom layer alone.
    Single,
}

/// The deck: `modes` eigenpairs in a `*FREQUENCY` step, and with `sweep` = (f_low,
/// f_high, points) a `*STEADY STATE DYNAMICS, DIRECT` step with 1 N along z at the top
/// layer's tip corner (node set TIP, printed as U).
pub fn stack_deck(joining: Joining, modes: usize, sweep: Option<(f64, f64, usize)>) -> String {
    let layers = if joining == Joining::Single { 1 } else { 3 };
    let mut s = String::from(
        "*HEADING\nthree-layer stack, non-conforming C3D20 meshes\n** jointlin units: length=mm force=N time=s mass=t\n",
    );
    let (mut node_base, mut elem_base) = (0usize, 0usize);
    let mut clamp = Vec::new();
    let mut tip = 0;
    for (l, cells) in CELLS.iter().take(layers).enumerate() {
        let m = box_mesh(ElementKind::C3D20, SIZE, [cells[0], cells[1], 1], 0.0, 0);
        let z0 = l as f64 * SIZE[2];
        let elset = format!("L{}", l + 1);
        mesh_cards(&mut s, &m, &elset, (node_base, elem_base), [0.0, 0.0, z0]);
        for (i, p) in m.nodes.iter().enumerate() {
            let id = node_base + i + 1;
            if p[0] == 0.0 {
                clamp.push(id);
            }
            if p[0] == SIZE[0] && p[1] == 0.0 && p[2] == SIZE[2] {
                tip = id;
            }
        }
        let _ = writeln!(
            s,
            "*SURFACE, NAME=L{0}-BOT, TYPE=ELEMENT\nL{0}, S1\n*SURFACE, NAME=L{0}-TOP, TYPE=ELEMENT\nL{0}, S2",
            l + 1
        );
        node_base += m.nodes.len();
        elem_base += m.elements.len();
    }
    let _ = writeln!(s, "*NSET, NSET=CLAMP");
    for chunk in clamp.chunks(16) {
        let ids: Vec<String> = chunk.iter().map(usize::to_string).collect();
        let _ = writeln!(s, "{}", ids.join(", "));
    }
    let all: Vec<String> = (1..=layers).map(|l| format!("L{l}")).collect();
    let (e, nu, rho) = STEEL;
    let _ = writeln!(
        s,
        "*NSET, NSET=TIP\n{tip}\n*ELSET, ELSET=ALL\n{}\n*MATERIAL, NAME=STEEL\n*ELASTIC\n{e:e}, {nu}\n*DENSITY\n{rho:e}\n*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL\n*BOUNDARY\nCLAMP, 1, 3",
        all.join(", ")
    );
    match joining {
        Joining::Tie => {
            for l in 1..layers {
                let _ = writeln!(s, "*TIE, NAME=T{l}\nL{}-BOT, L{l}-TOP", l + 1);
            }
        }
        Joining::Contact { mu, k_t0, k_n, .. } => {
            let _ = writeln!(
                s,
                "*SURFACE INTERACTION, NAME=JOINT, USER, DEPVAR=57, PROPERTIES=7\n1.\n1, 0, {mu:e}, {k_t0:e}, 0, {k_n:e}, 0"
            );
            for l in 1..layers {
                let _ = writeln!(
                    s,
                    "*CONTACT PAIR, INTERACTION=JOINT, SMALL SLIDING\nL{}-BOT, L{l}-TOP",
                    l + 1
                );
            }
        }
        Joining::Single => {}
    }
    if let Joining::Contact { pressure, .. } = joining {
        let _ = writeln!(
            s,
            "*STEP\n*STATIC\n*DSLOAD\nL{layers}-TOP, P, {pressure:e}\nL1-BOT, P, {pressure:e}\n*END STEP"
        );
    }
    let _ = writeln!(s, "*STEP\n*FREQUENCY\n{modes}\n*END STEP");
    if let Some((lo, hi, n)) = sweep {
        let _ = writeln!(
            s,
            "*STEP\n*STEADY STATE DYNAMICS, DIRECT\n{lo:e}, {hi:e}, {n}\n*CLOAD\nTIP, 3, 1.\n*NODE PRINT, NSET=TIP\nU\n*END STEP"
        );
    }
    s
}
