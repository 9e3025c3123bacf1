//! 3×3 spring/damper blocks between node pairs (or a slave node and the interpolated
//! master face, see [`Coupling`]): how contact points and ties enter the system.
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

use std::ops::{AddAssign, Mul, Neg};

use nalgebra::{Matrix3, Scalar};

use crate::fe::csc::CscPattern;
use crate::fe::dofs::DofMap;

/// The nodes of one block and their weights: the block's relative displacement is
/// δ = Σᵢ wᵢ u_{nodeᵢ} (global axes). A node pair `[a, b]` is `[(a, −1), (b, +1)]`; a
/// slave node paired with a master face is `(slave, +1)` and `(masterᵢ, −Nᵢ)` with the
/// face's shape functions at the projection (`fe::pairing`).
pub type Coupling = Vec<(usize, f64)>;

/// The coupling of node pair `[a, b]`: δ = u_b − u_a.
pub fn pair_coupling([a, b]: [usize; 2]) -> Coupling {
    vec![(a, -1.0), (b, 1.0)]
}

/// Value slots of the blocks of a list of couplings on one pattern.
#[derive(Debug, Clone, PartialEq)]
pub struct PairBlocks {
    couplings: Vec<Coupling>,
    /// slots[p][r·3n + c]: value index of entry (DOF r, DOF c) of coupling p's 3n × 3n
    /// block, DOF order (node₀.x, node₀.y, node₀.z, node₁.x, …); `None` where a DOF is
    /// fixed.
    slots: Vec<Vec<Option<usize>>>,
}

fn coupling_free(c: &[(usize, f64)], dofs: &DofMap) -> Vec<Option<usize>> {
    (0..3 * c.len())
        .map(|i| dofs.free(3 * c[i / 3].0 + i % 3))
        .collect()
}

impl PairBlocks {
    /// The (row, col) free-DOF entries the pattern needs for these couplings.
    pub fn pattern_entries<'a>(
        couplings: &'a [Coupling],
        dofs: &'a DofMap,
    ) -> impl Iterator<Item = (usize, usize)> + 'a {
        couplings.iter().flat_map(move |c| {
            let f = coupling_free(c, dofs);
            let n = f.len();
            (0..n * n).filter_map(move |k| Some((f[k / n]?, f[k % n]?)))
        })
    }

    /// Finds the value slots. `pattern` must contain [`Self::pattern_entries`] (as the
    /// pattern built by `assembly::assemble` does); panics otherwise (programming error).
    pub fn new(couplings: &[Coupling], dofs: &DofMap, pattern: &CscPattern) -> Self {
        let slots = couplings
            .iter()
            .map(|c| {
                let f = coupling_free(c, dofs);
                let n = f.len();
                (0..n * n)
                    .map(|k| {
                        let (fr, fc) = (f[k / n]?, f[k % n]?);
                        Some(
                            pattern
                                .find(fr, fc)
                                .expect("pair block entry missing from pattern"),
                        )
                    })
                    .collect()
            })
            .collect();
        PairBlocks {
            couplings: couplings.to_vec(),
            slots,
        }
    }

    /// Number of couplings.
    pub fn len(&self) -> usize {
        self.couplings.len()
    }

    pub fn is_empty(&self) -> bool {
        self.couplings.is_empty()
    }

    /// The nodes and weights of coupling `p`.
    pub fn coupling(&self, p: usize) -> &[(usize, f64)] {
        &self.couplings[p]
    }

    /// Adds coupling `p`'s block (wᵢwⱼK between nodes i and j; [[K, −K], [−K, K]] for a
    /// node pair; K in global axes) to `values` (the values of a matrix on the pattern
    /// given to [`Self::new`]).
    pub fn add<T>(&self, values: &mut [T], p: usize, k: &Matrix3<T>)
    where
        T: Scalar + Copy + AddAssign + Neg<Output = T> + Mul<f64, Output = T>,
    {
        let s = &self.slots[p];
        let w = &self.couplings[p];
        let n = 3 * w.len();
        for r in 0..n {
            for c in 0..n {
                if let Some(slot) = s[r * n + c] {
                    values[slot] += k[(r % 3, c % 3)] * (w[r / 3].1 * w[c / 3].1);
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
