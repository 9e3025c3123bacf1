//! `jointlin._native`: the compiled half of the Python package. The library is reached
//! only through its C API (`jointlin::ffi`), called per element exactly as a C host
//! would, so a number from Python is the C API's number bit for bit; the Python half
//! (`jointlin/`) broadcasts arrays, names statuses and raises.
//!
//! - [`linearize`]: vectorized `jointlin_linearize`, `jointlin_linearize3d`,
//!   `jointlin_screw_preload`, one status per element;
//! - [`point`]: the time-domain points (`jointlin_point_step`, `jointlin_point3d_step`)
//!   as stateful objects;
//! - [`scene`]: the harness's input check and its commands (run in a child process).
// Documented with its private items (`cargo doc --document-private-items`).
#![allow(rustdoc::private_intra_doc_links)]

mod errors;
mod linearize;
mod point;
mod scene;

use pyo3::prelude::*;

/// The extension module `jointlin._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(errors::status_message, m)?)?;
    m.add_function(wrap_pyfunction!(errors::abi_version, m)?)?;
    m.add_function(wrap_pyfunction!(linearize::linearize, m)?)?;
    m.add_function(wrap_pyfunction!(linearize::linearize3d, m)?)?;
    m.add_function(wrap_pyfunction!(linearize::screw_preload, m)?)?;
    m.add_class::<point::Point>()?;
    m.add_class::<point::Point3d>()?;
    m.add_function(wrap_pyfunction!(scene::check_input, m)?)?;
    m.add_function(wrap_pyfunction!(scene::cli, m)?)?;
    Ok(())
}
