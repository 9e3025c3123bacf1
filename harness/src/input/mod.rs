//! Model input formats.

pub mod deck;
