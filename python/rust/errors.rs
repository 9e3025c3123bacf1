//! Status codes and their messages, and the Python exception of a failed C-API call.

use std::ffi::{c_char, CStr};

use jointlin::ffi::error::{jointlin_last_error, jointlin_status_message};
use pyo3::prelude::*;

/// `jointlin_status_message(code)`: the library's English text of a status code.
#[pyfunction]
pub fn status_message(code: i32) -> String {
    // SAFETY: the library returns a static NUL-terminated string for every code.
    unsafe { CStr::from_ptr(jointlin_status_message(code)) }
        .to_string_lossy()
        .into_owned()
}

/// The library's C ABI version as (major, minor).
#[pyfunction]
pub fn abi_version() -> (u32, u32) {
    let v = jointlin::ffi::jointlin_abi_version();
    (v >> 16, v & 0xffff)
}

/// `jointlin_last_error` of this thread: the failing function and the offending input.
pub fn last_error() -> String {
    // SAFETY: NULL with length 0 asks for the length; then a buffer of that length + 1.
    let len = unsafe { jointlin_last_error(std::ptr::null_mut(), 0) };
    let mut buf = vec![0u8; len + 1];
    // SAFETY: `buf` holds len + 1 writable bytes.
    unsafe { jointlin_last_error(buf.as_mut_ptr().cast::<c_char>(), buf.len()) };
    buf.truncate(len);
    String::from_utf8_lossy(&buf).into_owned()
}

/// The Python exception of status `code` with `detail` (the class `jointlin._errors`
/// names for the code: NonFiniteError, OutOfRangeError, …).
pub fn status_error(py: Python<'_>, code: i32, detail: &str) -> PyErr {
    let message = format!("{} ({detail})", status_message(code));
    match py
        .import("jointlin._errors")
        .and_then(|m| m.getattr("error_for"))
        .and_then(|f| f.call1((code, message)))
    {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

/// The exception of the last failing call on this thread with status `code`.
pub fn call_error(py: Python<'_>, code: i32) -> PyErr {
    status_error(py, code, &last_error())
}
