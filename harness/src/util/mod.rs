//! Utilities every room may use: process timers and memory ([`rusage`]), the progress
//! bar of the commands ([`progress`]), atomic output files ([`atomic`]), plot axis ticks
//! ([`ticks`]) and the seeded test generator (`rng`).

pub mod atomic;
pub mod progress;
pub mod rusage;
pub mod ticks;

pub(crate) mod rng;
