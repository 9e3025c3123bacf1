//! Errors of the safe core. Each maps to one C status code in `ffi/error.rs`.

/// What went wrong with a contact-point question. Messages name the offending input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// An input was NaN or ±∞.
    #[error("non-finite input: {0}")]
    NonFinite(&'static str),
    /// An input was finite but outside its valid range.
    #[error("input out of range: {0}")]
    OutOfRange(&'static str),
    /// A result would not be representable (e.g. d* at ω so small that it overflows).
    #[error("result not representable: {0}")]
    Overflow(&'static str),
}

/// Rejects NaN and ±∞ with a message naming the input.
pub(crate) fn finite(value: f64, what: &'static str) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite(what))
    }
}
