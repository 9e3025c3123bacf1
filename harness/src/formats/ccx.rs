//! CalculiX's matrix storage files as Matrix Market files and a DOF list.
//!
//! A step `*FREQUENCY, SOLVER=MATRIXSTORAGE` (or `*STATIC, SOLVER=MATRIXSTORAGE`) makes
//! ccx write, instead of solving, the stiffness and mass matrices of the free DOFs
//! (boundary conditions removed): `JOB.sti` and `JOB.mas`, one entry `row column value`
//! per line, 1-based, upper triangle (row ≤ column), and `JOB.dof`, one line `node.dof`
//! per row (`12.3`: node 12, z). [`import`] turns them into `K.mtx` and `M.mtx`
//! (coordinate real symmetric: the lower triangle) and `dofs.csv` (`12,z`: the node
//! number is the point's name).

use std::fmt::Write as _;
use std::path::Path;

use super::MatrixError;

/// The three files of a `[[matrices]]` model, as text.
#[derive(Debug, Clone, PartialEq)]
pub struct Imported {
    pub stiffness: String,
    pub mass: String,
    pub dofs: String,
    /// Rows (free DOFs).
    pub n: usize,
}

fn read(path: &Path) -> Result<String, MatrixError> {
    std::fs::read_to_string(path)
        .map_err(|e| MatrixError::at(&path.display().to_string(), 0, format!("cannot read: {e}")))
}

/// `JOB.dof` → `node,direction` rows.
fn dofs(file: &str, text: &str) -> Result<Vec<String>, MatrixError> {
    let mut out = Vec::new();
    for (i, l) in text.lines().enumerate() {
        let l = l.trim();
        if l.is_empty() {
            continue;
        }
        let parsed = l.split_once('.').and_then(|(node, d)| {
            let node: u64 = node.parse().ok()?;
            let dir = match d {
                "1" => "x",
                "2" => "y",
                "3" => "z",
                _ => return None,
            };
            Some(format!("{node},{dir}"))
        });
        out.push(parsed.ok_or_else(|| {
            MatrixError::at(
                file,
                i + 1,
                format!("`{l}`: expected `node.dof` with dof 1, 2 or 3 (translations; rotations and other DOFs are not read)"),
            )
        })?);
    }
    if out.is_empty() {
        return Err(MatrixError::at(file, 0, "no DOFs".into()));
    }
    Ok(out)
}

/// `JOB.sti` or `JOB.mas` (upper triangle, 1-based) → Matrix Market symmetric text.
fn matrix(file: &str, text: &str, n: usize, what: &str) -> Result<String, MatrixError> {
    let mut entries = Vec::new();
    for (i, l) in text.lines().enumerate() {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.is_empty() {
            continue;
        }
        let bad = |m: String| MatrixError::at(file, i + 1, m);
        if f.len() != 3 {
            return Err(bad(format!("`{l}`: expected `row column value`")));
        }
        let idx = |s: &str| match s.parse::<usize>() {
            Ok(k) if (1..=n).contains(&k) => Ok(k),
            _ => Err(bad(format!(
                "index `{s}` outside 1..={n} (the .dof file's rows)"
            ))),
        };
        let (r, c) = (idx(f[0])?, idx(f[1])?);
        let v: f64 = f[2]
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| bad(format!("`{}` is not a finite number", f[2])))?;
        if r > c {
            return Err(bad(format!(
                "entry ({r}, {c}) below the diagonal: ccx stores the upper triangle"
            )));
        }
        // Stored entries that are exactly zero carry nothing.
        if v != 0.0 || r == c {
            entries.push((c, r, v));
        }
    }
    let mut out = format!(
        "%%MatrixMarket matrix coordinate real symmetric\n% {what} from CalculiX {file} (jointlin matrices import-ccx)\n{n} {n} {}\n",
        entries.len()
    );
    for (r, c, v) in entries {
        writeln!(out, "{r} {c} {v:e}").expect("string");
    }
    Ok(out)
}

/// Reads `JOB.sti`, `JOB.mas` and `JOB.dof` (`job` without extension).
pub fn import(job: &Path) -> Result<Imported, MatrixError> {
    let with = |ext: &str| {
        let mut p = job.as_os_str().to_owned();
        p.push(ext);
        std::path::PathBuf::from(p)
    };
    let (dof_p, sti_p, mas_p) = (with(".dof"), with(".sti"), with(".mas"));
    let rows = dofs(&dof_p.display().to_string(), &read(&dof_p)?)?;
    let n = rows.len();
    let stiffness = matrix(
        &sti_p.display().to_string(),
        &read(&sti_p)?,
        n,
        "stiffness K",
    )?;
    let mass = matrix(&mas_p.display().to_string(), &read(&mas_p)?, n, "mass M")?;
    let mut dofs = String::from("point,direction\n");
    for r in rows {
        dofs.push_str(&r);
        dofs.push('\n');
    }
    Ok(Imported {
        stiffness,
        mass,
        dofs,
        n,
    })
}
