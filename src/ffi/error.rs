//! Status codes, the one mapping from core errors to them, the panic boundary and the
//! thread-local error detail.

use std::cell::RefCell;
use std::ffi::{c_char, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::store::StoreError;

/// Success.
pub const JOINTLIN_OK: i32 = 0;
/// A required pointer argument was NULL.
pub const JOINTLIN_ERR_NULL: i32 = 1;
/// A floating-point input was NaN or infinite.
pub const JOINTLIN_ERR_NON_FINITE: i32 = 2;
/// A finite input (or an integer code, or a pointer's alignment) was outside its valid range.
pub const JOINTLIN_ERR_OUT_OF_RANGE: i32 = 3;
/// A result would not be representable (e.g. d* for a vanishing amplitude or frequency).
pub const JOINTLIN_ERR_OVERFLOW: i32 = 4;
/// A UINTER property (PROPS) is invalid: unknown code, negative friction coefficient, a
/// stiffness that must be > 0, or an inconsistent combination.
pub const JOINTLIN_ERR_PROPS: i32 = 5;
/// An array is too small (NSTATV, NPROPS, a caller-supplied capacity).
pub const JOINTLIN_ERR_SIZE: i32 = 6;
/// A nonlinear problem has no solution for the given data.
pub const JOINTLIN_ERR_NO_SOLUTION: i32 = 7;
/// An iteration did not converge within its limits.
pub const JOINTLIN_ERR_NOT_CONVERGED: i32 = 8;
/// A contact point id that the store never registered.
pub const JOINTLIN_ERR_UNKNOWN_POINT: i32 = 9;
/// A call that does not fit the UEXTERNALDB sequence (LOP 0 … 3), e.g. an estimate
/// outside an open increment.
pub const JOINTLIN_ERR_SEQUENCE: i32 = 10;
/// Reading or writing the restart file failed.
pub const JOINTLIN_ERR_IO: i32 = 11;
/// A Rust panic was caught at the API boundary (a bug in jointlin; please report it).
pub const JOINTLIN_ERR_PANIC: i32 = 12;

/// An error on its way to the C caller: a status code and a detail message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FfiError {
    pub code: i32,
    pub detail: String,
}

impl FfiError {
    pub fn new(code: i32, detail: impl Into<String>) -> Self {
        Self {
            code,
            detail: detail.into(),
        }
    }
}

pub(crate) type FfiResult<T> = Result<T, FfiError>;

impl From<crate::Error> for FfiError {
    fn from(e: crate::Error) -> Self {
        let code = match e {
            crate::Error::NonFinite(_) => JOINTLIN_ERR_NON_FINITE,
            crate::Error::OutOfRange(_) => JOINTLIN_ERR_OUT_OF_RANGE,
            crate::Error::Overflow(_) => JOINTLIN_ERR_OVERFLOW,
        };
        Self::new(code, e.to_string())
    }
}

impl From<StoreError> for FfiError {
    fn from(e: StoreError) -> Self {
        let code = match e {
            StoreError::NonFinite(_) => JOINTLIN_ERR_NON_FINITE,
            StoreError::OutOfRange(_) => JOINTLIN_ERR_OUT_OF_RANGE,
            StoreError::UnknownPoint(_) | StoreError::Node { .. } => JOINTLIN_ERR_UNKNOWN_POINT,
            StoreError::Sequence(_) => JOINTLIN_ERR_SEQUENCE,
            StoreError::Io(_) => JOINTLIN_ERR_IO,
            StoreError::Poisoned => JOINTLIN_ERR_PANIC,
        };
        Self::new(code, e.to_string())
    }
}

thread_local! {
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

fn set_last_error(msg: String) {
    LAST_ERROR.with(|l| *l.borrow_mut() = msg);
}

/// The panic boundary every export goes through: runs `body`, turns its error into a status
/// code and records the detail (prefixed by the function name) for `jointlin_last_error`.
pub(crate) fn boundary(function: &'static str, body: impl FnOnce() -> FfiResult<()>) -> i32 {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => JOINTLIN_OK,
        Ok(Err(e)) => {
            set_last_error(format!("{function}: {}", e.detail));
            e.code
        }
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            set_last_error(format!("{function}: panic: {what}"));
            JOINTLIN_ERR_PANIC
        }
    }
}

fn message(code: i32) -> &'static CStr {
    match code {
        JOINTLIN_OK => c"success",
        JOINTLIN_ERR_NULL => c"a required pointer argument was NULL",
        JOINTLIN_ERR_NON_FINITE => c"an input was NaN or infinite",
        JOINTLIN_ERR_OUT_OF_RANGE => c"an input was outside its valid range",
        JOINTLIN_ERR_OVERFLOW => c"a result would not be representable",
        JOINTLIN_ERR_PROPS => c"invalid UINTER properties (PROPS)",
        JOINTLIN_ERR_SIZE => c"an array is too small",
        JOINTLIN_ERR_NO_SOLUTION => c"the problem has no solution for these data",
        JOINTLIN_ERR_NOT_CONVERGED => c"the iteration did not converge",
        JOINTLIN_ERR_UNKNOWN_POINT => c"unknown contact point id",
        JOINTLIN_ERR_SEQUENCE => c"call out of the UEXTERNALDB sequence",
        JOINTLIN_ERR_IO => c"restart file I/O failed",
        JOINTLIN_ERR_PANIC => c"internal error (panic caught at the API boundary)",
        _ => c"unknown status code",
    }
}

/// A static, NUL-terminated English description of a status code. Never NULL; unknown codes
/// give "unknown status code". The caller must not free it.
#[no_mangle]
pub extern "C" fn jointlin_status_message(code: i32) -> *const c_char {
    message(code).as_ptr()
}

/// Copies the detail of the most recent failing jointlin call *on this thread* (function
/// name and the offending input) into `buf` as a NUL-terminated string, truncated to
/// `len - 1` bytes. Returns the full length of the detail in bytes, without the NUL (0 when
/// no call has failed on this thread), like snprintf: a return value >= `len` means the
/// copy was truncated. `buf` may be NULL when `len` is 0 (to ask for the length). Successful
/// calls do not clear the detail.
///
/// # Safety
/// `buf` must be NULL or point to `len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn jointlin_last_error(buf: *mut c_char, len: usize) -> usize {
    catch_unwind(|| {
        LAST_ERROR.with(|l| {
            let msg = l.borrow();
            let bytes = msg.as_bytes();
            if !buf.is_null() && len > 0 {
                let n = bytes.len().min(len - 1);
                // SAFETY: the caller guarantees `len` writable bytes at `buf`; n + 1 <= len.
                unsafe {
                    std::ptr::copy_nonoverlapping(bytes.as_ptr(), buf.cast::<u8>(), n);
                    *buf.add(n) = 0;
                }
            }
            bytes.len()
        })
    })
    .unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_has_its_own_message() {
        let codes = JOINTLIN_OK..=JOINTLIN_ERR_PANIC;
        let msgs: std::collections::HashSet<_> = codes.clone().map(message).collect();
        assert_eq!(msgs.len(), codes.count());
        assert!(!msgs.contains(message(-1)));
    }

    #[test]
    fn boundary_turns_panics_into_a_code() {
        let code = boundary("t", || panic!("boom"));
        assert_eq!(code, JOINTLIN_ERR_PANIC);
        let mut buf = [0 as c_char; 64];
        let n = unsafe { jointlin_last_error(buf.as_mut_ptr(), buf.len()) };
        let s = unsafe { CStr::from_ptr(buf.as_ptr()) }.to_str().unwrap();
        assert_eq!((n, s), ("t: panic: boom".len(), "t: panic: boom"));
        // Truncation keeps the NUL and reports the full length.
        let mut small = [1 as c_char; 4];
        assert_eq!(unsafe { jointlin_last_error(small.as_mut_ptr(), 4) }, n);
        assert_eq!(small[3], 0);
    }
}
