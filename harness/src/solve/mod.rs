//! Linear solvers (UMFPACK, modal), the static preload step and the steady-state sweep.

pub mod arpack;
pub mod cholmod;
pub mod contact;
pub mod cost;
pub mod dense;
pub mod line_search;
pub mod modal;
pub mod modal_band;
pub mod modal_stuck;
pub mod mode_labels;
pub mod prepared;
pub mod reduction;
pub mod static_step;
pub mod sweep;
pub mod umfpack;
