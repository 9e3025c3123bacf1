//! The harness's only door to jointlin: safe wrappers over the `extern "C"` functions of
//! `jointlin::ffi`, called exactly as a C or Fortran host would (raw pointers, status
//! codes). A non-OK status becomes a [`CapiError`] with the library's status message and
//! the thread's last-error detail.
//!
//! Every call is counted per thread ([`counts`]), so tests can show that switched-off
//! effects make no calls.

use std::cell::Cell;
use std::ffi::{c_char, CStr};

use jointlin::ffi::error::{jointlin_last_error, jointlin_status_message, JOINTLIN_OK};
use jointlin::ffi::linearize::{
    JOINTLIN_METHOD_GAUSS, JOINTLIN_METHOD_GRADED, JOINTLIN_METHOD_SIMPSON,
};
use thiserror::Error;

pub use jointlin::ffi::linearize::{
    JOINTLIN_REGIME_MICROSLIP, JOINTLIN_REGIME_OPEN, JOINTLIN_REGIME_SLIDING, JOINTLIN_REGIME_STICK,
};

/// STATEV length the harness keeps per contact point (the library's minimum).
pub const NSTATV: usize = 57;
/// PROPS length passed (all entries the library reads).
pub const NPROPS: usize = 12;

/// A failed C-API call.
#[derive(Debug, Clone, Error, PartialEq)]
#[error("{function} returned {code} ({message}): {detail}")]
pub struct CapiError {
    pub function: &'static str,
    pub code: i32,
    /// `jointlin_status_message(code)`.
    pub message: String,
    /// `jointlin_last_error` of this thread.
    pub detail: String,
}

/// The loaded library's C ABI version, "major.minor" (`jointlin_abi_version`).
pub fn abi_version() -> String {
    let v = jointlin::ffi::jointlin_abi_version();
    format!("{}.{}", v >> 16, v & 0xffff)
}

/// C-API calls made on this thread, by function.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct CallCounts {
    pub linearize: u64,
    /// jointlin_linearize_cubic (cubic springs).
    pub linearize_cubic: u64,
    /// jointlin_uinter with LINPER = 0 (general step).
    pub uinter_general: u64,
    /// jointlin_uinter with LINPER = 1 (steady-state step).
    pub uinter_linear: u64,
    pub uexternaldb: u64,
    /// Store object calls (new, register, estimate, report, next action, stats).
    pub store: u64,
}

thread_local! {
    static COUNTS: Cell<CallCounts> = Cell::new(CallCounts::default());
    static QUADRATURE: Cell<Option<Quadrature>> = const { Cell::new(None) };
}

/// Quadrature of the loop integrals (`jointlin_method`; PROPS 11/12 for UINTER).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Quadrature {
    /// Graded Gauss–Legendre, points per panel (the library's default with 8).
    Graded(i32),
    /// The thesis's composite Simpson rule, intervals.
    Simpson(i32),
    /// Plain Gauss–Legendre, points.
    Gauss(i32),
}

impl Quadrature {
    fn code(self) -> (i32, i32) {
        match self {
            Quadrature::Graded(n) => (JOINTLIN_METHOD_GRADED, n),
            Quadrature::Simpson(n) => (JOINTLIN_METHOD_SIMPSON, n),
            Quadrature::Gauss(n) => (JOINTLIN_METHOD_GAUSS, n),
        }
    }
}

/// Sets the quadrature of this thread's [`linearize()`] calls and of the PROPS built by
/// [`props::encode`] afterwards (`None`: the library's default). For fidelity studies
/// (`jointlin tradeoff`); returns the previous setting.
pub fn set_quadrature(q: Option<Quadrature>) -> Option<Quadrature> {
    QUADRATURE.with(|c| c.replace(q))
}

/// Calls made on this thread so far.
pub fn counts() -> CallCounts {
    COUNTS.with(|c| c.get())
}

fn count(f: impl FnOnce(&mut CallCounts)) {
    COUNTS.with(|c| {
        let mut v = c.get();
        f(&mut v);
        c.set(v);
    });
}

fn check(function: &'static str, code: i32) -> Result<(), CapiError> {
    if code == JOINTLIN_OK {
        return Ok(());
    }
    // SAFETY: jointlin_status_message never returns NULL; the string is static.
    let message = unsafe { CStr::from_ptr(jointlin_status_message(code)) }
        .to_string_lossy()
        .into_owned();
    let mut buf = vec![0u8; 512];
    // SAFETY: buf has 512 writable bytes.
    let n = unsafe { jointlin_last_error(buf.as_mut_ptr().cast::<c_char>(), buf.len()) };
    buf.truncate(n.min(511));
    Err(CapiError {
        function,
        code,
        message,
        detail: String::from_utf8_lossy(&buf).into_owned(),
    })
}

mod linearize;
mod point;
mod point3d;
pub mod props;
mod store;
mod uinter;

pub use linearize::*;
pub use point::*;
pub use point3d::*;
pub use store::*;
pub use uinter::*;

#[cfg(test)]
mod tests;
