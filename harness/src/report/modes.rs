//! The outputs of `jointlin modes`: the table on stdout, modes.csv and modes.vtu, every
//! header in the scene's units (frequency in Hz when `[units].time` = "s", else per the
//! time unit; effective masses in the mass unit, effective inertias in mass·length²).

use std::fmt::Write;

use crate::fe::elements::ElementKind;
use crate::fe::mesh::Model;
use crate::report::vtu::{unstructured_grid, CellType, PointField};
use crate::settings::units::frequency_unit;
use crate::settings::Units;
use crate::solve::modal_stuck::StuckModes;
use crate::solve::mode_labels::{Character, Kind, ModeGeometry};
use crate::util::csv_table::CsvTable;
use crate::util::number::{exact, sig};

/// An eigenvalue at most this fraction of the table's largest is a rigid-body mode's
/// (three-beams-coarse unclamped: its six rigid ones are 1e-11 of the largest; the
/// lowest flexible modes of the scenes here are 2.4e-4 of their table's largest or more).
const RIGID_REL: f64 = 1e-8;

/// The modes with their characters.
pub struct ModeTable<'a> {
    pub modes: &'a StuckModes,
    pub units: &'a Units,
    pub characters: Vec<Character>,
}

impl<'a> ModeTable<'a> {
    /// Labels every mode of `modes`.
    pub fn new(modes: &'a StuckModes, units: &'a Units) -> Self {
        let p = &modes.problem;
        let geo = ModeGeometry::new(&p.model.nodes, &p.sys.dofs, &p.sys.m);
        let characters = modes
            .band
            .modes
            .shapes
            .iter()
            .map(|phi| geo.character(&p.sys.m, phi))
            .collect();
        ModeTable {
            modes,
            units,
            characters,
        }
    }

    /// The modes' frequencies as the scene shows them ([`frequency_unit`]).
    fn frequencies(&self) -> Vec<f64> {
        let fu = frequency_unit(self.units);
        let f = self.modes.band.modes.frequencies_hz();
        f.into_iter().map(|f| fu.show(f)).collect()
    }

    /// The label of mode `i`: `rigid_body` when its eigenvalue is round-off beside the
    /// largest of the table ([`RIGID_REL`]: a structure held nowhere), else its
    /// character's.
    fn label(&self, i: usize) -> String {
        let l = &self.modes.band.modes.eigenvalues;
        let top = l.iter().copied().fold(0.0f64, f64::max);
        if top > 0.0 && l[i].abs() <= RIGID_REL * top {
            "rigid_body".into()
        } else {
            self.characters[i].label()
        }
    }

    /// Markdown table: mode, frequency, label, dominant direction, kind shares (%),
    /// effective masses.
    pub fn markdown(&self) -> String {
        let fu = frequency_unit(self.units).text;
        let mu = &self.units.mass;
        let mut s = format!(
            "| mode | frequency ({fu}) | label | dominant | longitudinal % | bending % | torsion % | section % | m_eff,x ({mu}) | m_eff,y ({mu}) | m_eff,z ({mu}) |\n|---:|---:|---|:---:|---:|---:|---:|---:|---:|---:|---:|\n"
        );
        for (i, (f, c)) in self.frequencies().iter().zip(&self.characters).enumerate() {
            let pct = shares(c).map(|v| v.map_or("–".into(), |v| format!("{:.1}", 100.0 * v)));
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                i + 1,
                sig(*f),
                self.label(i),
                c.dominant_name(),
                pct[0],
                pct[1],
                pct[2],
                pct[3],
                sig(c.effective_mass[0]),
                sig(c.effective_mass[1]),
                sig(c.effective_mass[2]),
            );
        }
        s
    }

    /// modes.csv: mode, frequency, label, dominant, the four kind shares (fractions;
    /// empty for lumped masses), effective masses and inertias per direction, the
    /// eigen-residual; every number in the shortest round-trip form, as in every CSV.
    pub fn csv(&self) -> String {
        let fcol = frequency_unit(self.units).column;
        let (m, l) = (&self.units.mass, &self.units.length);
        let mut header: Vec<String> = ["mode", fcol.as_str(), "label", "dominant"]
            .iter()
            .map(|h| h.to_string())
            .collect();
        for kind in ["longitudinal", "bending", "torsion", "section"] {
            header.push(format!("share_{kind}"));
        }
        for d in ['x', 'y', 'z'] {
            header.push(format!("effective_mass_{d}_{m}"));
        }
        for d in ['x', 'y', 'z'] {
            header.push(format!("effective_inertia_{d}_{m}_{l}2"));
        }
        header.push("backward_error".into());
        let mut t = CsvTable::new(&header);
        let modes = &self.modes.band.modes;
        for (i, (f, c)) in self.frequencies().iter().zip(&self.characters).enumerate() {
            let mut row = vec![
                (i + 1).to_string(),
                exact(*f),
                self.label(i),
                c.dominant_name().to_string(),
            ];
            row.extend(shares(c).map(|v| v.map_or(String::new(), exact)));
            let values = c
                .effective_mass
                .iter()
                .chain(&c.effective_inertia)
                .chain(std::iter::once(&modes.residuals[i]));
            row.extend(values.map(|v| exact(*v)));
            t.row(&row);
        }
        t.finish()
    }

    /// modes.vtu: the mesh (hexahedra, and a vertex per node outside every element:
    /// lumped masses) with one point vector per mode, `mode_<i>_<f>_<unit>`, scaled to a
    /// largest nodal displacement of 1 (a shape: the modes have no amplitude), its
    /// largest component positive.
    pub fn vtu(&self) -> String {
        let p = &self.modes.problem;
        let model = &p.model;
        let fu = frequency_unit(self.units);
        let unit = fu.suffix();
        let shapes: Vec<Vec<f64>> = self
            .modes
            .band
            .modes
            .shapes
            .iter()
            .map(|phi| nodal_shape(&p.sys.dofs.expand(phi)))
            .collect();
        let names: Vec<String> = self
            .frequencies()
            .iter()
            .enumerate()
            .map(|(i, f)| format!("mode_{}_{}_{unit}", i + 1, sig(*f)))
            .collect();
        let fields: Vec<PointField> = names
            .iter()
            .zip(&shapes)
            .map(|(name, values)| PointField {
                name,
                components: 3,
                values,
            })
            .collect();
        unstructured_grid(&model.nodes, &cells(model), &fields)
    }
}

/// The kind shares of `c`, None (printed "–", empty in CSV) for a model with one
/// cross-section (lumped masses: no axis).
fn shares(c: &Character) -> [Option<f64>; 4] {
    c.kind_share
        .map(|v| (c.kind != Kind::Translation).then_some(v))
}

/// A full displacement vector scaled to a largest nodal magnitude of 1, its largest
/// component positive (all zero stays zero).
fn nodal_shape(full: &[f64]) -> Vec<f64> {
    let largest = full
        .chunks(3)
        .map(|u| (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt())
        .fold(0.0, f64::max);
    let peak = full
        .iter()
        .fold(0.0, |a: f64, &v| if v.abs() > a.abs() { v } else { a });
    if largest == 0.0 || !largest.is_finite() {
        return vec![0.0; full.len()];
    }
    let scale = peak.signum() / largest;
    full.iter().map(|v| v * scale).collect()
}

/// The VTK cell of an element type (its node order is VTK's).
fn cell_type(kind: ElementKind) -> CellType {
    CellType::Solid(kind.element().vtk_cell())
}

/// The model's elements, and a vertex per node outside every element.
pub(super) fn cells(model: &Model) -> Vec<(CellType, Vec<usize>)> {
    let mut used = vec![false; model.nodes.len()];
    let mut cells: Vec<(CellType, Vec<usize>)> = model
        .elements
        .iter()
        .map(|e| {
            for &n in &e.nodes {
                used[n] = true;
            }
            (cell_type(e.kind), e.nodes.clone())
        })
        .collect();
    cells.extend(
        (0..model.nodes.len())
            .filter(|&n| !used[n])
            .map(|n| (CellType::Vertex, vec![n])),
    );
    cells
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seven_significant_digits() {
        assert_eq!(sig(31718.038906265498), "31718.04");
        assert_eq!(sig(0.20690142), "0.2069014");
        assert_eq!(sig(1234567.89), "1234568");
        assert_eq!(sig(1.2345678e-6), "1.234568e-6");
        assert_eq!(sig(-5.0), "-5.000000");
        assert_eq!(sig(0.0), "0");
        assert_eq!(sig(2.5e9), "2.500000e9");
    }

    #[test]
    fn shapes_scale_to_unit_peak_with_positive_largest_component() {
        let s = nodal_shape(&[0.0, 3.0, -4.0, 1.0, 0.0, 0.0]);
        for (a, b) in s.iter().zip([0.0, -0.6, 0.8, -0.2, 0.0, 0.0]) {
            approx::assert_abs_diff_eq!(*a, b, epsilon = 1e-15);
        }
        assert_eq!(nodal_shape(&[0.0; 3]), vec![0.0; 3]);
    }
}
