//! Finite-element foundation: meshes, the hex8 element, sparse assembly, loads,
//! node-pair blocks, contact pairs and ties.
//!
//! DOF numbering: node `n`, component `c` (0 = x, 1 = y, 2 = z) is full DOF `3n + c`.

pub mod assembly;
pub mod contact_pairs;
pub mod csc;
pub mod dofs;
pub mod elements;
pub mod error;
pub mod grading;
pub mod hex8;
pub mod material;
pub mod mesh;
pub mod pair_blocks;
pub mod pairing;
pub mod surface;
pub mod ties;

#[cfg(test)]
mod pair_blocks_tests;
