//! The identity of a contact point in the store.

use super::StoreError;

/// Identity of a contact point: interaction name, NODE and coordinate bits. NODE alone is
/// not enough (it is 0 for surface-to-surface contact).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct PointKey {
    pub(super) name: Vec<u8>,
    pub(super) node: i32,
    pub(super) coords: Vec<u64>,
}

/// Longest interaction name accepted (Abaqus: CHARACTER*80).
pub const MAX_NAME_LEN: usize = 256;

impl PointKey {
    /// Trailing blanks and NULs of `name` are ignored (Fortran pads CHARACTER*80 with
    /// blanks); −0.0 and 0.0 are the same coordinate. At most 3 coordinates.
    pub fn new(name: &[u8], node: i32, coords: &[f64]) -> Result<Self, StoreError> {
        if name.len() > MAX_NAME_LEN {
            return Err(StoreError::OutOfRange("interaction name longer than 256"));
        }
        if coords.len() > 3 {
            return Err(StoreError::OutOfRange("more than 3 coordinates"));
        }
        if coords.iter().any(|c| !c.is_finite()) {
            return Err(StoreError::NonFinite("coordinates"));
        }
        let end = name
            .iter()
            .rposition(|&c| c != b' ' && c != 0)
            .map_or(0, |i| i + 1);
        Ok(Self {
            name: name[..end].to_vec(),
            node,
            coords: coords.iter().map(|c| (c + 0.0).to_bits()).collect(),
        })
    }
}

/// CRC-32 of a point's PROPS (their bits, −0.0 as 0.0): what a restart file keeps of
/// them, to recognise the model it was written for.
pub fn props_checksum(props: &[f64]) -> u32 {
    let mut crc = crc32fast::Hasher::new();
    for p in props {
        crc.update(&(p + 0.0).to_bits().to_le_bytes());
    }
    crc.finalize()
}

impl std::fmt::Display for PointKey {
    /// `NAME node N at (x, y, z)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let xyz: Vec<String> = self
            .coords
            .iter()
            .map(|c| format!("{:e}", f64::from_bits(*c)))
            .collect();
        write!(
            f,
            "{} node {} at ({})",
            String::from_utf8_lossy(&self.name),
            self.node,
            xyz.join(", ")
        )
    }
}
