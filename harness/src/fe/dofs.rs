//! Free and full degrees of freedom: node `n`, component `c` is full DOF `3n + c`; fixed
//! DOFs are dropped and tied nodes share theirs.

/// Map between full DOFs (`3·node + c`) and free (unconstrained) DOFs. Tied nodes
/// (see [`crate::fe::mesh::Model::ties`]) share their free DOFs: a tie is exact (node merging), not a
/// penalty.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DofMap {
    full_to_free: Vec<Option<usize>>,
    free_to_full: Vec<usize>,
}

impl DofMap {
    /// Free DOFs are those with `fixed[d] == false`, numbered in full-DOF order.
    pub fn from_fixed(fixed: &[bool]) -> Self {
        Self::new(fixed, &[])
    }

    /// As [`DofMap::from_fixed`], with the nodes of each tie `[a, b]` sharing their DOFs
    /// (chains of ties join into one group). A component fixed on any node of a group is
    /// fixed on all of them. Each group's DOF is numbered at its lowest node.
    pub fn new(fixed: &[bool], ties: &[[usize; 2]]) -> Self {
        let n_nodes = fixed.len() / 3;
        // Union-find over nodes; the root is the group's lowest node.
        let mut parent: Vec<usize> = (0..n_nodes).collect();
        fn root(parent: &mut [usize], mut n: usize) -> usize {
            while parent[n] != n {
                parent[n] = parent[parent[n]];
                n = parent[n];
            }
            n
        }
        for &[a, b] in ties {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent[ra.max(rb)] = ra.min(rb);
        }
        let roots: Vec<usize> = (0..n_nodes).map(|n| root(&mut parent, n)).collect();
        let mut group_fixed = vec![false; fixed.len()];
        for (d, &f) in fixed.iter().enumerate() {
            if f {
                group_fixed[3 * roots[d / 3] + d % 3] = true;
            }
        }
        let mut full_to_free = vec![None; fixed.len()];
        let mut free_to_full = Vec::new();
        for d in 0..fixed.len() {
            let r = 3 * roots[d / 3] + d % 3;
            if group_fixed[r] {
                continue;
            }
            if r == d {
                full_to_free[d] = Some(free_to_full.len());
                free_to_full.push(d);
            } else {
                full_to_free[d] = full_to_free[r];
            }
        }
        DofMap {
            full_to_free,
            free_to_full,
        }
    }

    pub fn n_full(&self) -> usize {
        self.full_to_free.len()
    }

    pub fn n_free(&self) -> usize {
        self.free_to_full.len()
    }

    /// Free index of full DOF `d`, `None` if fixed.
    pub fn free(&self, d: usize) -> Option<usize> {
        self.full_to_free[d]
    }

    /// Full DOF of free index `f` (a tied group's lowest node).
    pub fn full(&self, f: usize) -> usize {
        self.free_to_full[f]
    }

    /// Free part of a full vector of nodal forces: entries of tied DOFs are summed,
    /// fixed ones dropped.
    pub fn restrict<T: Copy + Default + std::ops::AddAssign>(&self, full: &[T]) -> Vec<T> {
        let mut out = vec![T::default(); self.n_free()];
        for (d, f) in self.full_to_free.iter().enumerate() {
            if let Some(f) = f {
                out[*f] += full[d];
            }
        }
        out
    }

    /// Full vector from a free one: tied DOFs share the value, fixed DOFs are
    /// `T::default()` (zero).
    pub fn expand<T: Copy + Default>(&self, free: &[T]) -> Vec<T> {
        self.full_to_free
            .iter()
            .map(|f| f.map_or_else(T::default, |f| free[f]))
            .collect()
    }
}
