//! A contact point in three directions: a unilateral normal law and two tangential
//! directions with a coupled, circular slip limit ‖t‖ ≤ μN(t) (docs/contact3d.md).
//!
//! The thesis treats the two tangential directions independently at a held normal load
//! (model.md §2, §9; Fig. 4.26). Here the normal force follows the normal law at every step
//! (linear penalty or Hertz (2.34), zero when the gap is open), and the tangential force is
//! carried by Jenkins cells in the tangent plane, each with a circular limit:
//! * [`Tangential3d::Jenkins`]: one cell (k_T0, μN) (model.md §10);
//! * [`Tangential3d::MindlinMasing`]: n parallel cells ([`cells`]) that reproduce Mindlin's
//!   virgin curve (2.47) and Masing's rule (model.md §4) on a straight path.
//!
//! Like [`crate::hysteresis`], a state is plain data and [`Contact3d::step`] is pure.

pub mod cell;
pub mod cells;
pub mod describing;
mod ellipse;
pub mod phasors;
#[cfg(test)]
mod phasors_tests;
pub mod table;
#[cfg(test)]
mod table_tests;
pub mod unit_cell;

pub use cells::{Cells, DEFAULT_CELLS, MAX_CELLS};

use crate::error::{finite, Error};
use crate::law::hertz::NormalLaw;
use crate::linearize::Regime;

/// Tangential model of a three-direction point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tangential3d {
    /// Spring k_T0 in series with a slider whose limit is the circle of radius μN.
    Jenkins,
    /// `cells` parallel Jenkins cells (1..=MAX_CELLS) reproducing Mindlin–Masing.
    MindlinMasing { cells: usize },
}

/// One contact point: normal law, friction coefficient, full-stick tangential stiffness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact3d {
    pub tangential: Tangential3d,
    /// Friction coefficient μ ≥ 0.
    pub mu: f64,
    /// Full-stick tangential stiffness k_T0 > 0 (force/length), the same in both
    /// tangential directions and independent of the normal load.
    pub k_t0: f64,
    /// Normal force N(h) of the overclosure h (force form: `NormalLaw::Linear` stiffness in
    /// force/length, `NormalLaw::Hertz` with area 1).
    pub normal: NormalLaw,
}

/// Number of f64 slots of a stored [`State3d`].
pub const STATE3D_LEN: usize = 5 + 2 * MAX_CELLS;

/// History of a point: the displacement of the last step and each cell's slider position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State3d {
    /// Tangential displacement (u₁, u₂) of the last step (length).
    pub tangential: [f64; 2],
    /// Overclosure h of the last step (length, > 0 closed).
    pub overclosure: f64,
    /// Energy dissipated since the virgin state (force × length).
    pub dissipated: f64,
    /// Slider position of each cell (length); the cell's force is kᵢ (u − pᵢ).
    pub sliders: [[f64; 2]; MAX_CELLS],
}

impl Default for State3d {
    fn default() -> Self {
        Self {
            tangential: [0.0; 2],
            overclosure: 0.0,
            dissipated: 0.0,
            sliders: [[0.0; 2]; MAX_CELLS],
        }
    }
}

/// Result of one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step3d {
    /// Forces (t₁, t₂, N): tangential forces with the sign of the displacement (positive
    /// stiffness convention) and the normal force, ≥ 0 in compression.
    pub force: [f64; 3],
    /// d force / d (u₁, u₂, h) for continued motion, row-major (rows t₁, t₂, N). A sliding
    /// cell contributes kᵢ(I − t̂t̂ᵀ) and μ N'(h) φᵢ t̂ in the h column.
    pub stiffness: [[f64; 3]; 3],
    /// Energy dissipated during the step (≥ 0, force × length).
    pub dissipated: f64,
    /// Open (N = 0 or μ = 0), stick (no cell slipped), microslip (some), sliding (all).
    pub regime: Regime,
}

impl Contact3d {
    /// Checks the data: μ ≥ 0, k_T0 > 0, finite; cells in 1..=MAX_CELLS; a normal law with
    /// positive finite constants.
    pub fn validate(&self) -> Result<(), Error> {
        finite(self.mu, "mu")?;
        finite(self.k_t0, "k_T0")?;
        if self.mu < 0.0 {
            return Err(Error::OutOfRange("mu must be >= 0"));
        }
        if self.k_t0 <= 0.0 {
            return Err(Error::OutOfRange("k_T0 must be > 0"));
        }
        if let Tangential3d::MindlinMasing { cells } = self.tangential {
            if !(1..=MAX_CELLS).contains(&cells) {
                return Err(Error::OutOfRange("cells must be in 1..=128"));
            }
        }
        match self.normal {
            NormalLaw::Linear { stiffness_per_area } => {
                finite(stiffness_per_area, "normal stiffness")?;
                if stiffness_per_area <= 0.0 {
                    return Err(Error::OutOfRange("normal stiffness must be > 0"));
                }
            }
            NormalLaw::Hertz { hertz, area } => {
                finite(area, "area")?;
                crate::law::hertz::Hertz::new(hertz.r_star, hertz.e_star)?;
                if area <= 0.0 {
                    return Err(Error::OutOfRange("area must be > 0"));
                }
            }
        }
        Ok(())
    }

    /// The cells of the tangential model.
    pub fn cells(&self) -> Cells {
        match self.tangential {
            Tangential3d::Jenkins => Cells::jenkins(),
            Tangential3d::MindlinMasing { cells } => Cells::mindlin(cells),
        }
    }

    /// Number of cells a state of this contact holds.
    pub fn cell_count(&self) -> usize {
        match self.tangential {
            Tangential3d::Jenkins => 1,
            Tangential3d::MindlinMasing { cells } => cells,
        }
    }

    /// Moves the point from `state` to the displacement `disp` = (u₁, u₂, h): tangential
    /// relative displacements and the overclosure h (> 0 penetration, ≤ 0 open). The normal
    /// force N(h) is the normal law's; each cell's limit is its share of μN(h) at the end of
    /// the step, and each cell moves along the straight segment from the last tangential
    /// displacement to the new one (exactly, [`cell::advance`]). Pure: `state` is unchanged.
    pub fn step(&self, state: &State3d, disp: [f64; 3]) -> Result<(State3d, Step3d), Error> {
        self.validate()?;
        for v in disp {
            finite(v, "displacement")?;
        }
        let normal = self.normal.response(disp[2]);
        let n_force = normal.pressure;
        let limit = self.mu * n_force;
        if !limit.is_finite() || !n_force.is_finite() {
            return Err(Error::Overflow("normal force (overclosure too large)"));
        }
        let u = [disp[0], disp[1]];
        let du = [u[0] - state.tangential[0], u[1] - state.tangential[1]];
        let cells = self.cells();
        let mut next = *state;
        next.tangential = u;
        next.overclosure = disp[2];
        let mut force = [0.0, 0.0, n_force];
        let mut stiffness = [[0.0; 3]; 3];
        stiffness[2][2] = normal.stiffness;
        let mut dissipated = 0.0;
        let mut slipping = 0;
        for i in 0..cells.n {
            let k = self.k_t0 * cells.stiffness[i];
            let share = cells.strength[i];
            let p = state.sliders[i];
            let t = [
                k * (state.tangential[0] - p[0]),
                k * (state.tangential[1] - p[1]),
            ];
            let r = cell::advance(t, k, share * limit, du);
            next.sliders[i] = [u[0] - r.force[0] / k, u[1] - r.force[1] / k];
            dissipated += r.dissipated;
            force[0] += r.force[0];
            force[1] += r.force[1];
            let mag = r.force[0].hypot(r.force[1]);
            if r.slipped {
                slipping += 1;
            }
            if r.sliding && mag > 0.0 {
                let n = [r.force[0] / mag, r.force[1] / mag];
                for a in 0..2 {
                    for b in 0..2 {
                        let id = if a == b { 1.0 } else { 0.0 };
                        stiffness[a][b] += k * (id - n[a] * n[b]);
                    }
                    stiffness[a][2] += self.mu * normal.stiffness * share * n[a];
                }
            } else if limit > 0.0 {
                stiffness[0][0] += k;
                stiffness[1][1] += k;
                if r.returned {
                    // Returned to the circle μN share, then elastic: the end force moves
                    // with the limit along the start force's direction.
                    let mag = t[0].hypot(t[1]);
                    for a in 0..2 {
                        stiffness[a][2] += self.mu * normal.stiffness * share * t[a] / mag;
                    }
                }
            }
        }
        next.dissipated = state.dissipated + dissipated;
        let regime = if limit == 0.0 {
            Regime::Open
        } else if slipping == 0 {
            Regime::Stick
        } else if slipping < cells.n {
            Regime::Microslip
        } else {
            Regime::Sliding
        };
        let out = Step3d {
            force,
            stiffness,
            dissipated,
            regime,
        };
        let finite_out = out
            .force
            .iter()
            .chain(out.stiffness.iter().flatten())
            .all(|v| v.is_finite())
            && dissipated.is_finite()
            && next.dissipated.is_finite()
            && next.sliders[..cells.n]
                .iter()
                .flatten()
                .all(|v| v.is_finite());
        if !finite_out {
            return Err(Error::Overflow(
                "displacement too large: the state is not representable",
            ));
        }
        Ok((next, out))
    }
}

impl State3d {
    /// Writes the state into `out` (STATE3D_LEN slots): slot 0 the cell count, 1–2 the
    /// tangential displacement, 3 the overclosure, 4 the accumulated dissipation, then the
    /// slider positions (2 per cell; unused cells 0).
    pub fn write(&self, cells: usize, out: &mut [f64; STATE3D_LEN]) {
        *out = [0.0; STATE3D_LEN];
        out[0] = cells as f64;
        out[1] = self.tangential[0];
        out[2] = self.tangential[1];
        out[3] = self.overclosure;
        out[4] = self.dissipated;
        for (i, p) in self.sliders[..cells].iter().enumerate() {
            out[5 + 2 * i] = p[0];
            out[6 + 2 * i] = p[1];
        }
    }

    /// Reads a state written by [`State3d::write`] for a contact with `cells` cells. An
    /// all-zero block is the virgin state at displacement 0. Corrupt blocks (non-finite
    /// values, another cell count, a negative dissipation) give an error.
    pub fn read(slots: &[f64; STATE3D_LEN], cells: usize) -> Result<Self, Error> {
        if slots.iter().any(|v| !v.is_finite()) {
            return Err(Error::NonFinite("stored point state"));
        }
        if slots.iter().all(|&v| v == 0.0) {
            return Ok(Self::default());
        }
        if slots[0] != cells as f64 {
            return Err(Error::OutOfRange(
                "stored point state belongs to another cell count",
            ));
        }
        if slots[4] < 0.0 || slots[5 + 2 * cells..].iter().any(|&v| v != 0.0) {
            return Err(Error::OutOfRange("stored point state is corrupt"));
        }
        let mut s = Self {
            tangential: [slots[1], slots[2]],
            overclosure: slots[3],
            dissipated: slots[4],
            ..Self::default()
        };
        for i in 0..cells {
            s.sliders[i] = [slots[5 + 2 * i], slots[6 + 2 * i]];
        }
        Ok(s)
    }
}

#[cfg(test)]
mod prop_tests;
#[cfg(test)]
mod tests;
