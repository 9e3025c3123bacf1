//! Linear solvers: UMFPACK (complex, 64-bit indices) and the modal eigensolver on top.

pub mod modal;
pub mod umfpack;
