//! VTK XML UnstructuredGrid files (`.vtu`, ASCII) for ParaView: points, cells and
//! point data. Written here rather than with a crate: `vtkio` 0.6.3, its latest stable
//! release, does write XML `.vtu` with quadratic cells (tried), but only base64-binary
//! arrays, and it pulls in nom 3 and quick-xml 0.22, releases years behind their own
//! lines. The ASCII form is a few tags, and the reader tests (harness/tests/modes_cli.rs,
//! field_output.rs, knife.rs) parse it back.

use std::fmt::Write;

/// VTK cell types used here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellType {
    /// One node (VTK_VERTEX = 1): a lumped mass.
    Vertex,
    /// Four nodes around a face (VTK_QUAD = 9): a contact face's element face.
    Quad,
    /// A solid element of this VTK cell type, its nodes in the element's Abaqus order,
    /// which is VTK's (`SolidElement::vtk_cell`: VTK_TETRA = 10, VTK_HEXAHEDRON = 12,
    /// VTK_QUADRATIC_TETRA = 24, VTK_QUADRATIC_HEXAHEDRON = 25).
    Solid(u8),
}

impl CellType {
    fn code(self) -> u8 {
        match self {
            CellType::Vertex => 1,
            CellType::Quad => 9,
            CellType::Solid(code) => code,
        }
    }
}

/// A named point field: `components` values per point, point after point.
pub struct PointField<'a> {
    pub name: &'a str,
    pub components: usize,
    pub values: &'a [f64],
}

/// The `.vtu` text of a grid of `points` (length), `cells` (type, point indices) and
/// point data `fields` (each `components × points.len()` values; the first is
/// ParaView's active one). Non-finite values are written as 0 (VTK readers reject
/// "NaN" in ASCII data): the callers write only finite ones.
pub fn unstructured_grid(
    points: &[[f64; 3]],
    cells: &[(CellType, Vec<usize>)],
    fields: &[PointField],
) -> String {
    let mut s = String::new();
    s.push_str(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
    );
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        points.len(),
        cells.len()
    );
    s.push_str("      <Points>\n");
    floats(&mut s, "position", 3, points.iter().flatten().copied());
    s.push_str("      </Points>\n      <Cells>\n");
    ints(
        &mut s,
        "connectivity",
        "Int64",
        cells.iter().flat_map(|(_, n)| n.iter().copied()),
    );
    ints(
        &mut s,
        "offsets",
        "Int64",
        cells.iter().scan(0, |o, (_, n)| {
            *o += n.len();
            Some(*o)
        }),
    );
    ints(
        &mut s,
        "types",
        "UInt8",
        cells.iter().map(|(t, _)| t.code() as usize),
    );
    s.push_str("      </Cells>\n");
    match fields.first() {
        Some(f) if f.components == 3 => {
            let _ = writeln!(s, "      <PointData Vectors=\"{}\">", escape(f.name));
        }
        Some(f) => {
            let _ = writeln!(s, "      <PointData Scalars=\"{}\">", escape(f.name));
        }
        None => s.push_str("      <PointData>\n"),
    }
    for f in fields {
        floats(&mut s, f.name, f.components, f.values.iter().copied());
    }
    s.push_str("      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    s
}

/// XML attribute text: the five special characters escaped.
fn escape(name: &str) -> String {
    name.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}

fn floats(out: &mut String, name: &str, comps: usize, values: impl Iterator<Item = f64>) {
    let _ = write!(
        out,
        "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{comps}\" format=\"ascii\">\n         ",
        escape(name)
    );
    for v in values {
        let v = if v.is_finite() { v } else { 0.0 };
        let _ = write!(out, " {v:.9e}");
    }
    out.push_str("\n        </DataArray>\n");
}

fn ints(out: &mut String, name: &str, ty: &str, values: impl Iterator<Item = usize>) {
    let _ = write!(
        out,
        "        <DataArray type=\"{ty}\" Name=\"{name}\" format=\"ascii\">\n         "
    );
    for v in values {
        let _ = write!(out, " {v}");
    }
    out.push_str("\n        </DataArray>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_hexahedron_and_a_vertex() {
        let mut points: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64])
            .collect();
        points.push([2.0, 0.0, 0.0]);
        let disp: Vec<f64> = (0..27).map(|i| i as f64 * 0.5).collect();
        let text = unstructured_grid(
            &points,
            &[
                (CellType::Solid(12), vec![0, 1, 3, 2, 4, 5, 7, 6]),
                (CellType::Vertex, vec![8]),
            ],
            &[PointField {
                name: "mode_1_<a&b>",
                components: 3,
                values: &disp,
            }],
        );
        assert!(text.contains("NumberOfPoints=\"9\" NumberOfCells=\"2\""));
        assert!(text.contains("Vectors=\"mode_1_&lt;a&amp;b&gt;\""));
        assert!(text.contains("\n          8 9\n"), "offsets");
        assert!(text.contains("\n          12 1\n"), "types");
        assert!(text.contains(" 1.300000000e1\n"), "last value");
    }
}
