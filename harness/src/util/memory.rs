//! How much memory a run may take: the machine's available memory (`MemAvailable` of
//! /proc/meminfo), or the environment variable [`MAX_MEMORY_VAR`] when set.

/// Environment variable that sets the memory limit of a run: bytes, or a number with
/// the suffix k, M, G or T (powers of 1000), e.g. `JOINTLIN_MAX_MEMORY=64G`.
pub const MAX_MEMORY_VAR: &str = "JOINTLIN_MAX_MEMORY";

// What a run keeps, for the estimates of scenes and decks made before anything is
// allocated.

/// Bytes per DOF of the sparse matrices: a hex8 mesh couples each DOF with 81 (27
/// nodes × 3), held in K, M, D (real), the dynamic stiffness (complex), the static
/// tangent, their index arrays, and the solvers' vectors of that length.
pub const MATRIX_BYTES_PER_DOF: f64 = 4000.0;
/// Bytes per estimated entry of the sparse LU factors: fitted to the peak memory of
/// `jointlin run` on two bodies in contact (4 320 and 29 376 DOFs: 0.10 and 1.56 GB)
/// and three beams (13 608 DOFs: 0.36 GB); with the DOF term the estimate is 1.1–1.7 ×
/// the measured peak (2.4 × on the knife's 824 DOFs). UMFPACK's real fill exceeds the
/// nested dissection count, and the static and complex factors, the FGMRES basis and
/// the contact blocks come with it.
pub const FACTOR_BYTES_PER_ENTRY: f64 = 2000.0;
/// Bytes kept per frequency and contact point (point results: amplitudes, k*, d*,
/// energy and ratio per direction).
pub const POINT_BYTES_PER_FREQUENCY: f64 = 160.0;
/// Bytes kept per frequency and output (complex amplitude, with and without contact
/// damping) and per frequency itself.
pub const OUTPUT_BYTES_PER_FREQUENCY: f64 = 48.0;
pub const BYTES_PER_FREQUENCY: f64 = 64.0;
/// The process itself (binary, libraries, allocator) before the model (13 MB measured).
pub const BASE_BYTES: f64 = 20e6;

/// Where a memory limit comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LimitSource {
    /// `MemAvailable` of /proc/meminfo.
    Available,
    /// The environment variable [`MAX_MEMORY_VAR`].
    Variable,
}

impl LimitSource {
    /// "available (…)" or "allowed by …", for messages.
    pub fn describe(self) -> &'static str {
        match self {
            LimitSource::Available => "available (MemAvailable of /proc/meminfo)",
            LimitSource::Variable => "allowed by JOINTLIN_MAX_MEMORY",
        }
    }
}

/// The memory a run may take (bytes) and where the number comes from; `Ok(None)` if
/// neither the variable nor /proc/meminfo gives one; an error if the variable is set
/// but is not a size.
pub fn limit() -> Result<Option<(f64, LimitSource)>, String> {
    match std::env::var(MAX_MEMORY_VAR) {
        Ok(v) => parse_size(&v)
            .map(|b| Some((b, LimitSource::Variable)))
            .ok_or_else(|| {
                format!("{MAX_MEMORY_VAR}=`{v}` is not a size (bytes, or e.g. 500M, 64G)")
            }),
        Err(_) => Ok(available_bytes().map(|b| (b, LimitSource::Available))),
    }
}

/// `MemAvailable` of /proc/meminfo (bytes), if readable.
pub fn available_bytes() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    meminfo_available(&text)
}

/// `MemAvailable: N kB` of a /proc/meminfo text, in bytes.
fn meminfo_available(text: &str) -> Option<f64> {
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// A size: a non-negative number of bytes with an optional suffix k, M, G, T (× 1e3,
/// 1e6, 1e9, 1e12; a trailing `B` allowed).
pub fn parse_size(s: &str) -> Option<f64> {
    let t = s.trim();
    let t = t.strip_suffix(['B', 'b']).unwrap_or(t);
    let (num, factor) = match t.chars().last()? {
        'k' | 'K' => (&t[..t.len() - 1], 1e3),
        'M' | 'm' => (&t[..t.len() - 1], 1e6),
        'G' | 'g' => (&t[..t.len() - 1], 1e9),
        'T' | 't' => (&t[..t.len() - 1], 1e12),
        _ => (t, 1.0),
    };
    let v: f64 = num.trim().parse().ok()?;
    (v.is_finite() && v >= 0.0).then_some(v * factor)
}

/// A byte count for messages: `8.00 GB (8000000000 bytes)`.
pub fn format_bytes(b: f64) -> String {
    format!("{:.2} GB ({:.0} bytes)", b / 1e9, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_and_without_suffixes() {
        assert_eq!(parse_size("123"), Some(123.0));
        assert_eq!(parse_size("64G"), Some(64e9));
        assert_eq!(parse_size("1.5 GB"), Some(1.5e9));
        assert_eq!(parse_size("500M"), Some(500e6));
        assert_eq!(parse_size("2t"), Some(2e12));
        for bad in ["", "G", "-1G", "lots", "1e400", "NaN"] {
            assert_eq!(parse_size(bad), None, "{bad}");
        }
    }

    #[test]
    fn meminfo_available_is_read_in_bytes() {
        let text = "MemTotal:  16000000 kB\nMemFree: 100 kB\nMemAvailable:   8000000 kB\n";
        assert_eq!(meminfo_available(text), Some(8_192_000_000.0));
        assert_eq!(meminfo_available("MemTotal: 1 kB\n"), None);
    }
}
