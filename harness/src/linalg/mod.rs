//! Dense linear algebra at LAPACK speed: the LU factorization the harmonic-balance and
//! backbone Newton iterations solve with (their Jacobians have thousands of rows).

mod lu;

pub use lu::{solve, Lu};
