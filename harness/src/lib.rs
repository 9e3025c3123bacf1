//! jointlin-harness: an independent host FE code that exercises jointlin the way
//! Abaqus would (through the C API only, [`capi`]).
//!
//! Pipeline of `jointlin run SCENE --out DIR` ([`run`]):
//! 1. [`input`]: the input path; [`input::scene`]: TOML schema, validation with file:line:key errors;
//!    [`settings`]: what a run computes (`[sweep]`, `[iteration]`, `[effects]`, units).
//! 2. [`model`]: scene → mesh and lumped bodies, K, M, material damping, contact points
//!    (node pairs with frames and tributary areas), preload and excitation, outputs.
//! 3. [`solve::static_step`]: the preload step, Newton with UINTER (LINPER = 0).
//! 4. [`solve::sweep`]: the steady-state step, `fast` (one factorization per frequency,
//!    condensation or FGMRES for the contact iterations) or `thesis` (multi-pass
//!    UEXTERNALDB scheme through the library's store, UINTER LINPER = 1).
//! 5. [`report`]: results.csv, points.csv, stick_slip.csv, run.json, SVG plots.
//!
//! Foundation: [`fe`] (hex8 with incompatible modes, CSC assembly, pair blocks, contact
//! pairs), [`solve::umfpack`] (complex 64-bit UMFPACK), [`solve::modal`]. Also
//! [`mod@bench`] (`jointlin bench`, `jointlin modes`), and the time-domain reference,
//! validation and trade-off studies ([`time`], [`validate`], [`tradeoff`]).
//!
//! Units are the caller's and must be consistent. The tests use N, mm, s, t, so E is
//! in MPa (N/mm²), ρ in t/mm³, forces in N, frequencies in Hz or rad/s as named.
// Documented with its private items (`cargo doc --document-private-items`, as
// scripts/test.sh builds it): docs may link to private helpers and constants.
#![allow(rustdoc::private_intra_doc_links)]
// Index loops mirror the formulas (Σᵢ over nodes, components); iterator rewrites
// would hide the maths.
#![allow(clippy::needless_range_loop)]

// The commands (`cli`) name the rooms as `jointlin_harness::`, as a program outside the
// crate would: they sit above every room, and the `jointlin` program and the Python
// package's extension both run them.
extern crate self as jointlin_harness;

pub mod backbone;
pub mod bench;
pub mod capi;
pub mod cli;
pub mod effects;
pub mod export;
pub mod fe;
pub mod formats;
pub mod input;
pub mod linalg;
pub mod loss;
pub mod mhb;
pub mod model;
pub mod names;
pub mod reduce;
pub mod report;
pub mod run;
pub mod settings;
pub mod solve;
pub mod time;
pub mod tradeoff;
pub mod util;
pub mod validate;
