//! jointlin-harness: an independent host FE code that exercises jointlin the way
//! Abaqus would (through the C API only).
//!
//! This library part holds the FE foundation:
//! - [`fe`]: structured hex8 meshes of stacked boxes, the hex8 element (incompatible
//!   modes), sparse assembly with fixed DOFs eliminated, surface pressure loads,
//!   node-pair spring/damper blocks (where contact points enter) and contact pairs.
//! - [`solve`]: a safe wrapper over UMFPACK's complex 64-bit interface and a
//!   shift-invert subspace iteration for eigenfrequencies.
//!
//! Units are the caller's and must be consistent. The tests use N, mm, s, t, so E is
//! in MPa (N/mm²), ρ in t/mm³, forces in N, frequencies in Hz or rad/s as named.

// Index loops mirror the formulas (Σᵢ over nodes, components); iterator rewrites
// would hide the maths.
#![allow(clippy::needless_range_loop)]

pub mod bench;
pub mod capi;
pub mod fe;
pub mod model;
pub mod report;
pub mod run;
pub mod scene;
pub mod solve;
pub mod time;
pub mod tradeoff;
pub mod validate;

pub(crate) mod rng;
