//! The settings of a run, below every room that reads them: what a run computes
//! (`[sweep]`, `[iteration]` with the mode, `[[outputs]]`, `[effects]`), the studies'
//! tables (`[loss_study]`, `[time_domain]`, `[field_output]`) and the units with their
//! names in columns and labels (`units`) and the names a system may state (`unit_names`). The scene schema deserializes into these types and the
//! deck reader fills them; solvers, the time domain and reports read them here, never
//! from an input reader.

pub mod frequencies;
pub mod run;
pub mod studies;
pub mod study;
pub mod unit_names;
pub mod units;

pub use run::RunSettings;
pub use studies::*;
pub use study::*;
pub use units::Units;
