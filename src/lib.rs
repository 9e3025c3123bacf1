//! # jointlin
//!
//! Frequency-domain linearization of bolted and clamped joint contact, after Tianyi Yu (KIT 2012;
//! the method and its equations: `docs/model.md`):
//! per contact point and vibration amplitude, the Hertz–Mindlin–Coulomb hysteresis is
//! replaced by an equivalent spring k* (first-order harmonic balance, (3.8), (4.3)) and an
//! equivalent damper d* (energy balance, (3.14)).
//!
//! Pipeline, one contact point at a time:
//! 1. [`law`]: pure contact laws (Hertz normal, Mindlin or Jenkins tangential).
//! 2. [`hysteresis`]: the stateful time-domain point (slip → force, tangent, dissipation).
//! 3. [`linearize`]: amplitude A, frequency ω → k*, d*, η, energy per cycle, peak force.
//! 4. [`iterate`]: amplitude consistency for one point or a small dense system (4.2.3).
//! 5. [`store`]: the UEXTERNALDB-side iteration store over frequency increments (4.3.2).
//! 6. [`point3d`]: a contact point in three directions (unilateral normal law, coupled
//!    circular slip limit in the tangent plane) and its describing function.
//! 7. `ffi`: the C ABI (`jointlin_*`), the only unsafe code.

pub mod error;
pub mod ffi;
pub mod hysteresis;
pub mod iterate;
pub mod law;
pub mod linearize;
pub mod point3d;
pub mod store;
mod wide;

pub use error::Error;
