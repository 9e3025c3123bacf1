//! Utilities every room may use: process timers and memory ([`rusage`]), the progress
//! bar of the commands ([`progress`]) and the seeded test generator (`rng`).

pub mod progress;
pub mod rusage;

pub(crate) mod rng;
