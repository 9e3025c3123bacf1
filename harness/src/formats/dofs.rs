//! The DOF list of a matrices model (a scene's `[[matrices]]`): which named point and direction each row of
//! M, K (and D) is. One row per line, `point,direction`: `tip,x` is the translation of
//! point `tip` along x (`x`, `y`, `z`); any other direction label (`modal,1`, `q,3`) makes
//! the row a generalized coordinate (a modal amplitude of a Craig–Bampton or modal
//! reduction), which no joint, spring, clamp or output can name by an axis. An optional
//! first line `point,direction` is a header; `#` starts a comment; blank lines are
//! skipped.

use super::MatrixError;

/// One row of the matrices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Dof {
    pub point: String,
    /// The translation axis (0 x, 1 y, 2 z), or `None` for a generalized coordinate.
    pub axis: Option<usize>,
    /// The direction as written (`x`, `1`, …).
    pub label: String,
}

impl Dof {
    /// `point.direction`, as the row is named in messages and run.json.
    pub fn name(&self) -> String {
        format!("{}.{}", self.point, self.label)
    }
}

/// Parses the list `text` of file `file`.
pub fn parse(file: &str, text: &str) -> Result<Vec<Dof>, MatrixError> {
    parse_lines(file, text.lines().enumerate().map(|(i, l)| (i + 1, l)))
}

/// Parses numbered lines (an inline list: line = index + 1).
pub fn parse_lines<'a>(
    file: &str,
    lines: impl Iterator<Item = (usize, &'a str)>,
) -> Result<Vec<Dof>, MatrixError> {
    let mut out: Vec<Dof> = Vec::new();
    let mut seen = std::collections::BTreeMap::new();
    for (line, raw) in lines {
        let l = raw.split('#').next().unwrap_or("").trim();
        if l.is_empty() {
            continue;
        }
        let f: Vec<&str> = l.split(',').map(str::trim).collect();
        if out.is_empty()
            && seen.is_empty()
            && f.len() == 2
            && f[0] == "point"
            && f[1] == "direction"
        {
            seen.insert(("".to_string(), "".to_string()), line);
            continue;
        }
        if f.len() != 2 || f[0].is_empty() || f[1].is_empty() {
            return Err(MatrixError::at(
                file,
                line,
                format!("`{l}`: expected `point,direction` (e.g. `tip,x`, or `modal,1` for a modal coordinate)"),
            ));
        }
        let ok = |s: &str| {
            s.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        };
        if !ok(f[0]) || !ok(f[1]) {
            return Err(MatrixError::at(
                file,
                line,
                format!("`{l}`: point and direction use only A-Z a-z 0-9 _ -"),
            ));
        }
        if let Some(first) = seen.insert((f[0].to_string(), f[1].to_string()), line) {
            return Err(MatrixError::at(
                file,
                line,
                format!("`{l}` listed twice (first at line {first})"),
            ));
        }
        let axis = match f[1] {
            "x" => Some(0),
            "y" => Some(1),
            "z" => Some(2),
            _ => None,
        };
        out.push(Dof {
            point: f[0].to_string(),
            axis,
            label: f[1].to_string(),
        });
    }
    if out.is_empty() {
        return Err(MatrixError::at(
            file,
            0,
            "the DOF list is empty".to_string(),
        ));
    }
    Ok(out)
}
