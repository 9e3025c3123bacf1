//! 3×3 spring/damper blocks between node pairs: how contact points enter the system.
//!
//! For a pair `[a, b]` with relative displacement δ = u_b − u_a (global axes) and a
//! 3×3 block K (global axes, e.g. complex k + iωd), the spring pulls b back with −Kδ
//! and a along with +Kδ. Its internal-force contribution (the rows of S u = f_ext) is
//! (−Kδ at a, +Kδ at b), i.e. the 6×6 block [[K, −K], [−K, K]] on (u_a, u_b). Blocks given in a local frame Q = [n t₁ t₂] (columns, unit vectors)
//! become K = Q K_loc Qᵀ ([`to_global`]).
//!
//! The value slots of every block are found once ([`PairBlocks::new`]); adding blocks
//! per frequency is index arithmetic on `values` with no allocation. Entries whose
//! DOF is fixed are dropped (the fixed node does not move).

use std::ops::{AddAssign, Neg};

use nalgebra::{Matrix3, Scalar};

use crate::fe::csc::CscPattern;
use crate::fe::dofs::DofMap;

/// Value slots of the 6×6 blocks of a list of node pairs on one pattern.
#[derive(Debug, Clone, PartialEq)]
pub struct PairBlocks {
    pairs: Vec<[usize; 2]>,
    /// slots[p][r][c]: value index of entry (DOF r, DOF c) of pair p's 6×6 block, DOF
    /// order (a.x, a.y, a.z, b.x, b.y, b.z); `None` where a DOF is fixed.
    slots: Vec<[[Option<usize>; 6]; 6]>,
}

fn pair_free(pair: [usize; 2], dofs: &DofMap) -> [Option<usize>; 6] {
    std::array::from_fn(|i| dofs.free(3 * pair[i / 3] + i % 3))
}

impl PairBlocks {
    /// The (row, col) free-DOF entries the pattern needs for these pairs.
    pub fn pattern_entries<'a>(
        pairs: &'a [[usize; 2]],
        dofs: &'a DofMap,
    ) -> impl Iterator<Item = (usize, usize)> + 'a {
        pairs.iter().flat_map(move |&p| {
            let f = pair_free(p, dofs);
            (0..36).filter_map(move |k| Some((f[k / 6]?, f[k % 6]?)))
        })
    }

    /// Finds the value slots. `pattern` must contain [`Self::pattern_entries`] (as the
    /// pattern built by `assembly::assemble` does); panics otherwise (programming error).
    pub fn new(pairs: &[[usize; 2]], dofs: &DofMap, pattern: &CscPattern) -> Self {
        let slots = pairs
            .iter()
            .map(|&p| {
                let f = pair_free(p, dofs);
                std::array::from_fn(|r| {
                    std::array::from_fn(|c| {
                        let (fr, fc) = (f[r]?, f[c]?);
                        Some(
                            pattern
                                .find(fr, fc)
                                .expect("pair block entry missing from pattern"),
                        )
                    })
                })
            })
            .collect();
        PairBlocks {
            pairs: pairs.to_vec(),
            slots,
        }
    }

    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// The node pair `[a, b]` of pair `p`.
    pub fn pair(&self, p: usize) -> [usize; 2] {
        self.pairs[p]
    }

    /// Adds pair `p`'s block [[K, −K], [−K, K]] (K in global axes) to `values`
    /// (the values of a matrix on the pattern given to [`Self::new`]).
    pub fn add<T>(&self, values: &mut [T], p: usize, k: &Matrix3<T>)
    where
        T: Scalar + Copy + AddAssign + Neg<Output = T>,
    {
        let s = &self.slots[p];
        for r in 0..6 {
            for c in 0..6 {
                if let Some(slot) = s[r][c] {
                    let v = k[(r % 3, c % 3)];
                    values[slot] += if (r < 3) == (c < 3) { v } else { -v };
                }
            }
        }
    }
}

/// K = Q K_loc Qᵀ: a block given in the local frame Q (columns = local axes in global
/// coordinates) expressed in global axes. Works for real or complex K_loc.
pub fn to_global<T>(q: &Matrix3<f64>, k_local: &Matrix3<T>) -> Matrix3<T>
where
    T: Scalar + Copy + AddAssign + Default + std::ops::Mul<f64, Output = T>,
{
    let mut out = Matrix3::from_element(T::default());
    for i in 0..3 {
        for j in 0..3 {
            let mut acc = T::default();
            for a in 0..3 {
                for b in 0..3 {
                    acc += k_local[(a, b)] * (q[(i, a)] * q[(j, b)]);
                }
            }
            out[(i, j)] = acc;
        }
    }
    out
}

/// K = Q diag(k) Qᵀ: independent springs along the local axes (e.g. k_N, k_T1, k_T2).
pub fn diagonal_to_global<T>(q: &Matrix3<f64>, k: [T; 3]) -> Matrix3<T>
where
    T: Scalar + Copy + AddAssign + Default + std::ops::Mul<f64, Output = T>,
{
    let mut local = Matrix3::from_element(T::default());
    for a in 0..3 {
        local[(a, a)] = k[a];
    }
    to_global(q, &local)
}
