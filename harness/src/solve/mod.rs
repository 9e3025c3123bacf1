//! Linear solvers (UMFPACK, modal), the static preload step and the steady-state sweep.

pub mod contact;
pub mod modal;
pub mod static_step;
pub mod umfpack;
