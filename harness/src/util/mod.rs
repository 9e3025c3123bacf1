//! Utilities every room may use: process timers and memory ([`rusage`]), the progress
//! bar of the commands ([`progress`]), atomic output files ([`atomic`]), the memory a run
//! may take ([`memory`]), numbers with significant digits ([`number`]), CSV tables
//! ([`csv_table`]), plot axis ticks ([`ticks`]), the provenance head of run.json ([`provenance`]) and the seeded test generator (`rng`).

pub mod atomic;
pub mod csv_table;
pub mod memory;
pub mod number;
pub mod parallel;
pub mod progress;
pub mod provenance;
pub mod rusage;
pub mod ticks;

pub(crate) mod rng;
