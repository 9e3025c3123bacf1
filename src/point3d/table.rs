//! The unit cell's describing function tabulated (docs/contact3d.md §4): the first
//! harmonics of a Jenkins cell (stiffness 1, stretch at the limit x = 1) on the ellipse
//! (a cos θ, b sin θ), interpolated from `unit_cell_table.csv` instead of integrated, for
//! sweeps over many points. [`super::unit_cell::unit_cell`] made the table (the ignored
//! test `tabulated_unit_cell::regenerate` writes it) and stays the reference.
//!
//! Layout, for a ≥ b (b > a by the roles swapped):
//! * max(a, b) ≤ 1: the cell sticks (exact, no table);
//! * 1 < a < A_MAX, b ≥ B_MIN: bicubic (4 × 4 Lagrange) interpolation on uniform grids in
//!   z = √(ln a / ln A_MAX) (the onset at a = 1 is smooth in z: k* − 1 ∝ (a − 1)^{3/2} ∝ z³)
//!   and, in two blocks that meet where the minor axis reaches the cell's stretch (b = 1:
//!   below it the cell sticks around the minor axis's ends, above it that stick is gone, a
//!   kink across which no stencil reaches), v = 1 − √(ln b / ln B_MIN) for b ≤ 1 (dense
//!   toward b = 1, where near-circles of a ≈ 1 switch between sliding all round and
//!   sticking at the minor axis's ends) and
//!   v = ln b / ln a for 1 ≤ b ≤ a (up to the circle);
//! * b < B_MIN: the row b = B_MIN, its minor-direction harmonics scaled by b/B_MIN (a path
//!   that thin moves the cell sideways linearly; the major direction changes by O(b²));
//! * a ≥ A_MAX: the rigid–plastic cell ([`super::unit_cell::RIGID_RATIO`]) tabulated in
//!   ln(b/a) down to E_MIN (thinner: the row E_MIN).
//!
//! Accuracy (test `tabulated_unit_cell_matches_the_integrated_one`): the force harmonics
//! within [`TABLE_TOLERANCE`] of the cell's limit force f over the whole plane.

use std::f64::consts::PI;
use std::sync::OnceLock;

use super::ellipse::CellHarmonics;
use super::unit_cell::{rigid_plastic, unit_cell};

/// Largest a of the finite-x table; above it the cell is rigid–plastic (error O(1/a) in
/// the major direction's harmonics).
pub const A_MAX: f64 = 1e6;
/// Smallest b of the table (units of x).
pub const B_MIN: f64 = 1e-3;
/// Smallest b/a of the rigid–plastic row.
pub const E_MIN: f64 = 1e-8;
/// Grid sizes: z (rows), v (columns of each block), ln(b/a) of the rigid–plastic row.
pub const NZ: usize = 64;
pub const NV: usize = 48;
pub const NE: usize = 48;
/// Interpolation error bound of the force harmonics, in units of the cell's limit force.
pub const TABLE_TOLERANCE: f64 = 2e-3;

/// Harmonics (c₁, s₁, c₂, s₂) at the grid nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Row-major, NZ × NV, per block ([`Block`]).
    pub grid: [Vec<[f64; 4]>; 2],
    /// NE rigid–plastic values, b/a from 1 down to E_MIN.
    pub rigid: Vec<[f64; 4]>,
}

/// The two blocks of the finite-x grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Block {
    /// B_MIN ≤ b ≤ 1.
    Lower = 0,
    /// 1 ≤ b ≤ a.
    Upper = 1,
}

const BLOCKS: [Block; 2] = [Block::Lower, Block::Upper];

fn block_name(b: Block) -> &'static str {
    match b {
        Block::Lower => "lower",
        Block::Upper => "upper",
    }
}

/// a of grid row i.
fn row_a(i: usize) -> f64 {
    let z = i as f64 / (NZ - 1) as f64;
    (z * z * A_MAX.ln()).exp()
}

/// The (a, b) of grid node (i, j) of `block`.
pub fn grid_node(block: Block, i: usize, j: usize) -> (f64, f64) {
    let a = row_a(i);
    let v = j as f64 / (NV - 1) as f64;
    let b = match block {
        Block::Lower => B_MIN.powf((1.0 - v) * (1.0 - v)),
        Block::Upper => a.powf(v),
    };
    (a, b.min(a))
}

/// b/a of rigid–plastic node k.
pub fn rigid_node(k: usize) -> f64 {
    E_MIN.powf(k as f64 / (NE - 1) as f64)
}

fn harmonics_of(h: CellHarmonics) -> [f64; 4] {
    [h.c1, h.s1, h.c2, h.s2]
}

/// Computes the whole table with `threads` threads (about two minutes: the rows near
/// A_MAX integrate ~10⁶ steps per cycle).
pub fn compute(threads: usize) -> Table {
    let threads = threads.max(1);
    let jobs: Vec<(Block, usize)> = BLOCKS
        .iter()
        .flat_map(|&b| (0..NZ).map(move |i| (b, i)))
        .collect();
    let mut grid = [vec![[0.0; 4]; NZ * NV], vec![[0.0; 4]; NZ * NV]];
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let mine: Vec<(Block, usize)> =
                    jobs.iter().copied().skip(t).step_by(threads).collect();
                s.spawn(move || {
                    mine.into_iter()
                        .map(|(block, i)| {
                            let row: Vec<[f64; 4]> = (0..NV)
                                .map(|j| {
                                    let (a, b) = grid_node(block, i, j);
                                    harmonics_of(unit_cell(a, b))
                                })
                                .collect();
                            (block, i, row)
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        for h in handles {
            for (block, i, row) in h.join().expect("table thread") {
                grid[block as usize][i * NV..(i + 1) * NV].copy_from_slice(&row);
            }
        }
    });
    let rigid = (0..NE)
        .map(|k| harmonics_of(rigid_plastic(1.0, rigid_node(k))))
        .collect();
    Table { grid, rigid }
}

/// The table as CSV: a comment header, then `kind,i,j,c1,s1,c2,s2` per node.
pub fn to_csv(t: &Table) -> String {
    let mut s = format!(
        "# Unit Jenkins cell on the ellipse (a cos θ, b sin θ): first harmonics c1 s1 c2 s2 (units of f)\n\
         # rows: a = exp(z² ln {A_MAX:e}), z = i/{}; lower: b = {B_MIN:e}^((1 - j/{})²); upper: b = a^(j/{})\n\
         # rigid: b/a = {E_MIN:e}^(i/{})\n\
         # written by: cargo test --release --lib regenerate_unit_cell_table -- --ignored\n",
        NZ - 1,
        NV - 1,
        NV - 1,
        NE - 1
    );
    for block in BLOCKS {
        for i in 0..NZ {
            for j in 0..NV {
                let h = t.grid[block as usize][i * NV + j];
                let name = block_name(block);
                s += &format!(
                    "{name},{i},{j},{:e},{:e},{:e},{:e}\n",
                    h[0], h[1], h[2], h[3]
                );
            }
        }
    }
    for (k, h) in t.rigid.iter().enumerate() {
        s += &format!("rigid,{k},0,{:e},{:e},{:e},{:e}\n", h[0], h[1], h[2], h[3]);
    }
    s
}

/// Reads [`to_csv`]'s output; `None` if it does not hold every node of this layout.
pub fn parse(text: &str) -> Option<Table> {
    let mut grid = [vec![[f64::NAN; 4]; NZ * NV], vec![[f64::NAN; 4]; NZ * NV]];
    let mut rigid = vec![[f64::NAN; 4]; NE];
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != 7 {
            return None;
        }
        let (i, j): (usize, usize) = (f[1].parse().ok()?, f[2].parse().ok()?);
        let mut h = [0.0; 4];
        for (q, v) in h.iter_mut().enumerate() {
            *v = f[3 + q].parse().ok()?;
        }
        match f[0] {
            "lower" if i < NZ && j < NV => grid[0][i * NV + j] = h,
            "upper" if i < NZ && j < NV => grid[1][i * NV + j] = h,
            "rigid" if i < NE => rigid[i] = h,
            _ => return None,
        }
    }
    let all_finite = grid
        .iter()
        .flatten()
        .chain(&rigid)
        .flatten()
        .all(|v| v.is_finite());
    all_finite.then_some(Table { grid, rigid })
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        parse(include_str!("unit_cell_table.csv"))
            .expect("unit_cell_table.csv matches the table layout")
    })
}

/// Lagrange weights of the 4 nodes around t (in node units, 0 ≤ t ≤ n − 1) and the first.
fn stencil(t: f64, n: usize) -> (usize, [f64; 4]) {
    let i0 = (t.floor() as isize - 1).clamp(0, n as isize - 4) as usize;
    let x = t - i0 as f64;
    let mut w = [0.0; 4];
    for (k, wk) in w.iter_mut().enumerate() {
        *wk = (0..4)
            .filter(|&m| m != k)
            .map(|m| (x - m as f64) / (k as f64 - m as f64))
            .product();
    }
    (i0, w)
}

fn interpolate(a: f64, b: f64) -> [f64; 4] {
    let z = (a.ln() / A_MAX.ln()).sqrt().clamp(0.0, 1.0);
    let (block, v) = if b <= 1.0 {
        (Block::Lower, 1.0 - (b.ln() / B_MIN.ln()).sqrt())
    } else {
        (Block::Upper, b.ln() / a.ln())
    };
    let grid = &table().grid[block as usize];
    let (i0, wi) = stencil(z * (NZ - 1) as f64, NZ);
    let (j0, wj) = stencil(v.clamp(0.0, 1.0) * (NV - 1) as f64, NV);
    let mut h = [0.0; 4];
    for (di, w1) in wi.iter().enumerate() {
        for (dj, w2) in wj.iter().enumerate() {
            let node = grid[(i0 + di) * NV + j0 + dj];
            for (hq, nq) in h.iter_mut().zip(node) {
                *hq += w1 * w2 * nq;
            }
        }
    }
    h
}

fn rigid(e: f64) -> [f64; 4] {
    let t = table();
    let k = (e.max(E_MIN).ln() / E_MIN.ln()).clamp(0.0, 1.0) * (NE - 1) as f64;
    let (k0, w) = stencil(k, NE);
    let mut h = [0.0; 4];
    for (d, wk) in w.iter().enumerate() {
        for (hq, nq) in h.iter_mut().zip(t.rigid[k0 + d]) {
            *hq += wk * nq;
        }
    }
    h
}

/// Harmonics of a unit cell on the ellipse (a, b ≥ 0, finite), from the table; the
/// energy per cycle is π(b c₂ − a s₁), the work of the force on the path.
pub fn unit_cell_tabulated(a: f64, b: f64) -> CellHarmonics {
    if b > a {
        // Roles swapped: the cell on (b cos θ', a sin θ') with θ = θ' + π/2 and direction 1
        // reflected.
        let h = unit_cell_tabulated(b, a);
        return CellHarmonics {
            c1: h.s2,
            s1: -h.c2,
            c2: -h.s1,
            s2: h.c1,
            energy: h.energy,
        };
    }
    if a <= 1.0 || b == 0.0 {
        // Stick, and the straight path: closed forms.
        return unit_cell(a, b);
    }
    let [c1, s1, c2, s2] = if a >= A_MAX {
        rigid(b / a)
    } else if b < B_MIN {
        let [c1, s1, c2, s2] = interpolate(a, B_MIN);
        let f = b / B_MIN;
        [c1, s1, c2 * f, s2 * f]
    } else {
        interpolate(a, b)
    };
    CellHarmonics {
        c1,
        s1,
        c2,
        s2,
        energy: (PI * (b * c2 - a * s1)).max(0.0),
    }
}
