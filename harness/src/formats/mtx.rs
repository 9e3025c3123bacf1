//! A strict Matrix Market reader (NIST format, `%%MatrixMarket matrix …`): `coordinate`
//! or `array`, `real` or `integer`, `general` or `symmetric`; the result is a dense
//! matrix (reduced models are small). What the format does not allow, or what a model
//! matrix must not be, is an error naming `file:line`: a second value at the same entry,
//! an upper-triangle entry in a symmetric file, an index out of range, a count that
//! does not match, a value that is not a finite number.
//!
//! Written here rather than taken from a crate: the crates that read the format
//! (nalgebra-sparse's `io`, matrixmarket-rs) report no line numbers, and a symmetric
//! array file, which `scipy.io.mmwrite` writes for a dense NumPy matrix, is not read by
//! all of them.

use nalgebra::DMatrix;

use super::MatrixError;

/// Largest dimension read (the lumped solvers are dense: n² values).
pub const MAX_DIM: usize = 4000;

/// A matrix as read, with where each stored entry came from.
#[derive(Debug, Clone)]
pub struct Read {
    pub matrix: DMatrix<f64>,
    /// Declared `symmetric` (only the lower triangle was stored).
    pub symmetric: bool,
    /// 1-based line of each stored entry (0: not stored), for later messages.
    pub lines: DMatrix<u32>,
    /// 1-based line of the size line.
    pub size_line: usize,
}

/// Reads the Matrix Market text `text` of file `file`.
pub fn parse(file: &str, text: &str) -> Result<Read, MatrixError> {
    let err = |line: usize, msg: String| MatrixError::at(file, line, msg);
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let (_, header) = lines.next().ok_or_else(|| {
        err(
            1,
            "empty file: a Matrix Market file starts with `%%MatrixMarket matrix …`".into(),
        )
    })?;
    let (coordinate, symmetric, symmetry) = header_kind(file, header)?;
    let mut data = lines.filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('%'));
    let (size_line, size) = data
        .next()
        .ok_or_else(|| err(1, "no size line after the header".into()))?;
    let dims = dimensions(file, size_line, size, coordinate)?;
    let n = dims[0];
    let mut matrix = DMatrix::<f64>::zeros(n, n);
    let mut at = DMatrix::<u32>::zeros(n, n);
    let value = |line: usize, s: &str| value(file, line, s);
    let mut store = |line: usize, i: usize, j: usize, v: f64| -> Result<(), MatrixError> {
        if at[(i, j)] != 0 {
            return Err(err(
                line,
                format!(
                    "entry ({}, {}) given twice (first at line {})",
                    i + 1,
                    j + 1,
                    at[(i, j)]
                ),
            ));
        }
        matrix[(i, j)] = v;
        at[(i, j)] = line as u32;
        if symmetric && i != j {
            matrix[(j, i)] = v;
            at[(j, i)] = line as u32;
        }
        Ok(())
    };
    let mut count = 0usize;
    if coordinate {
        let nnz = dims[2];
        for (line, l) in data {
            let f: Vec<&str> = l.split_whitespace().collect();
            if f.len() != 3 {
                return Err(err(line, format!("`{l}`: expected `row column value`")));
            }
            let idx = |s: &str| match s.parse::<usize>().ok() {
                Some(k) if (1..=n).contains(&k) => Ok(k - 1),
                _ => Err(err(line, format!("index `{s}` outside 1..={n}"))),
            };
            let (i, j) = (idx(f[0])?, idx(f[1])?);
            if symmetric && i < j {
                return Err(err(
                    line,
                    format!(
                        "entry ({}, {}) above the diagonal: a symmetric file stores the lower triangle (row ≥ column)",
                        i + 1,
                        j + 1
                    ),
                ));
            }
            count += 1;
            if count > nnz {
                return Err(err(
                    line,
                    format!("more entries than the {nnz} of the size line"),
                ));
            }
            store(line, i, j, value(line, f[2])?)?;
        }
        if count != nnz {
            return Err(err(
                size_line,
                format!("the size line announces {nnz} entries, the file has {count}"),
            ));
        }
    } else {
        // Column-major; a symmetric array holds the lower triangle column by column.
        let cells: Vec<(usize, usize)> = (0..n)
            .flat_map(|j| (if symmetric { j } else { 0 }..n).map(move |i| (i, j)))
            .collect();
        let mut next = cells.iter();
        for (line, l) in data {
            for s in l.split_whitespace() {
                let Some(&(i, j)) = next.next() else {
                    return Err(err(
                        line,
                        format!(
                            "more values than the {} of a {n} × {n} {} array",
                            cells.len(),
                            symmetry
                        ),
                    ));
                };
                store(line, i, j, value(line, s)?)?;
                count += 1;
            }
        }
        if count != cells.len() {
            return Err(err(
                size_line,
                format!(
                    "a {n} × {n} {} array has {} values, the file has {count}",
                    symmetry,
                    cells.len()
                ),
            ));
        }
    }
    Ok(Read {
        matrix,
        symmetric,
        lines: at,
        size_line,
    })
}

/// A finite number, or the error at `line` naming `s`.
fn value(file: &str, line: usize, s: &str) -> Result<f64, MatrixError> {
    let v: f64 = s
        .parse()
        .map_err(|_| MatrixError::at(file, line, format!("`{s}` is not a number")))?;
    if !v.is_finite() {
        return Err(MatrixError::at(
            file,
            line,
            format!("value `{s}` is not finite"),
        ));
    }
    Ok(v)
}

/// The header line's kind: coordinate (else array), symmetric (else general), and the
/// symmetry's word; anything else is refused at line 1.
fn header_kind(file: &str, header: &str) -> Result<(bool, bool, String), MatrixError> {
    let err = |line: usize, msg: String| MatrixError::at(file, line, msg);
    let words: Vec<String> = header.split_whitespace().map(str::to_lowercase).collect();
    if words.len() != 5 || words[0] != "%%matrixmarket" || words[1] != "matrix" {
        return Err(err(
            1,
            format!("not a Matrix Market header: `{header}` (expected `%%MatrixMarket matrix coordinate real symmetric` or the like)"),
        ));
    }
    let coordinate = match words[2].as_str() {
        "coordinate" => true,
        "array" => false,
        f => {
            return Err(err(
                1,
                format!("format `{f}`: only `coordinate` and `array` are read"),
            ))
        }
    };
    if !matches!(words[3].as_str(), "real" | "integer") {
        return Err(err(
            1,
            format!(
                "field `{}`: only `real` and `integer` matrices are model matrices",
                words[3]
            ),
        ));
    }
    let symmetric = match words[4].as_str() {
        "general" => false,
        "symmetric" => true,
        s => {
            return Err(err(
                1,
                format!("symmetry `{s}`: only `general` and `symmetric` are read"),
            ))
        }
    };
    Ok((coordinate, symmetric, words[4].clone()))
}

/// The size line's numbers (rows, columns and, for `coordinate`, entries) of a square
/// matrix of 1 to [`MAX_DIM`] rows; anything else is refused at `size_line`.
fn dimensions(
    file: &str,
    size_line: usize,
    size: &str,
    coordinate: bool,
) -> Result<Vec<usize>, MatrixError> {
    let err = |line: usize, msg: String| MatrixError::at(file, line, msg);
    let numbers: Vec<&str> = size.split_whitespace().collect();
    let want = if coordinate { 3 } else { 2 };
    let int = |s: &str| s.parse::<usize>().ok();
    let dims: Vec<usize> = numbers.iter().filter_map(|s| int(s)).collect();
    if numbers.len() != want || dims.len() != want {
        return Err(err(
            size_line,
            format!(
                "size line `{size}`: expected {} non-negative integers",
                if coordinate {
                    "rows, columns, entries:"
                } else {
                    "rows, columns:"
                }
            ),
        ));
    }
    let (nr, nc) = (dims[0], dims[1]);
    if nr != nc {
        return Err(err(
            size_line,
            format!("the matrix is {nr} × {nc}: model matrices are square"),
        ));
    }
    if nr == 0 || nr > MAX_DIM {
        return Err(err(
            size_line,
            format!("dimension {nr}: 1 to {MAX_DIM} rows are read"),
        ));
    }
    Ok(dims)
}

/// `matrix` (symmetric) as Matrix Market `coordinate real symmetric` text: its nonzero
/// lower triangle, each value in the shortest form that reads back exactly; `comment`
/// lines follow the header.
pub fn write_symmetric(matrix: &DMatrix<f64>, comment: &str) -> String {
    use std::fmt::Write as _;
    let n = matrix.nrows();
    let entries: Vec<(usize, usize, f64)> = (0..n)
        .flat_map(|j| (j..n).map(move |i| (i, j)))
        .map(|(i, j)| (i, j, matrix[(i, j)]))
        .filter(|&(i, j, v)| v != 0.0 || i == j)
        .collect();
    let mut out = String::from("%%MatrixMarket matrix coordinate real symmetric\n");
    for l in comment.lines() {
        writeln!(out, "% {l}").expect("string");
    }
    writeln!(out, "{n} {n} {}", entries.len()).expect("string");
    for (i, j, v) in entries {
        writeln!(out, "{} {} {v:e}", i + 1, j + 1).expect("string");
    }
    out
}
