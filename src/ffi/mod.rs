//! The C ABI: `jointlin_*` functions, `#[repr(C)]` structs and status codes; the only unsafe
//! code of the crate. One module per object family (after rustls-ffi):
//!
//! * [`error`]: status codes, `jointlin_status_message`, `jointlin_last_error`, panic boundary;
//! * [`linearize`]: `jointlin_linearize` (one point, one amplitude, one frequency);
//! * [`cubic`]: `jointlin_linearize_cubic` (the Duffing cubic spring, one amplitude) and
//!   `jointlin_cubic_force` (its force and tangent at one elongation);
//! * [`point`]: `jointlin_point_step`, the time-domain hysteresis point for non-Abaqus hosts;
//! * [`point3d`]: `jointlin_point3d_step` and `jointlin_linearize3d`, the contact point in
//!   three directions (unilateral normal law, coupled slip limit) and its describing function;
//! * [`screw`]: `jointlin_screw_preload`, screw preload from torque (VDI 2230);
//! * [`store`]: the iteration store object `jointlin_store` (thesis §4.3.2);
//! * [`store_model`]: the host's model fingerprint, checked in restart files;
//! * [`store_ranks`]: stores of a job with several processes (MPI ranks): per-rank restart
//!   files and the end-of-pass agreement on the increments to re-run;
//! * [`uexternaldb`] and [`uinter`]: Abaqus-convention entry points (model.md §7);
//! * [`props`]: the UINTER PROPS and STATEV layouts, `jointlin_uinter_props_check`.
//!
//! Conventions for every function: the return value is a `JOINTLIN_*` status code; NULL,
//! NaN/±∞, out-of-range and size errors give named codes; outputs are written only when the
//! call returns `JOINTLIN_OK` (exceptions are documented); no output is ever NaN; a Rust
//! panic is caught and returned as `JOINTLIN_ERR_PANIC`; `jointlin_last_error` gives the
//! detail of a failure. All functions may be called from several threads at once; a
//! `jointlin_store` may be shared between threads, with the ordering rules of the
//! `jointlin_store` documentation (per-point calls from many threads, sequence calls such
//! as UEXTERNALDB from one thread, not overlapping the increment they open or close).

#![allow(non_camel_case_types)]

pub mod cubic;
pub mod error;
pub mod linearize;
pub mod point;
pub mod point3d;
pub mod point_tangents;
pub mod props;
pub mod screw;
pub mod store;
pub mod store_model;
pub mod store_ranks;
pub mod uexternaldb;
pub mod uinter;

use error::{
    FfiError, FfiResult, JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_NULL, JOINTLIN_ERR_OUT_OF_RANGE,
};

/// Major version of the C ABI: changes break existing callers.
pub const JOINTLIN_ABI_VERSION_MAJOR: u32 = 0;
/// Minor version of the C ABI: additions that keep existing callers working.
pub const JOINTLIN_ABI_VERSION_MINOR: u32 = 7;

/// The ABI version of the loaded library, (major << 16) | minor. A caller compiled against
/// this header should check that the major part equals JOINTLIN_ABI_VERSION_MAJOR.
#[no_mangle]
pub extern "C" fn jointlin_abi_version() -> u32 {
    (JOINTLIN_ABI_VERSION_MAJOR << 16) | JOINTLIN_ABI_VERSION_MINOR
}

/// Checks a pointer argument: not NULL, aligned for `T`.
pub(crate) fn check_ptr<T>(p: *const T, what: &str) -> FfiResult<()> {
    if p.is_null() {
        return Err(FfiError::new(JOINTLIN_ERR_NULL, format!("{what} is NULL")));
    }
    if !p.is_aligned() {
        return Err(FfiError::new(
            JOINTLIN_ERR_OUT_OF_RANGE,
            format!("{what} is misaligned"),
        ));
    }
    Ok(())
}

/// Copies `*p` after [`check_ptr`].
///
/// # Safety
/// `p` must be NULL or point to a readable `T`.
pub(crate) unsafe fn load<T: Copy>(p: *const T, what: &str) -> FfiResult<T> {
    check_ptr(p, what)?;
    // SAFETY: non-NULL and aligned (checked), readable by the caller's contract.
    Ok(unsafe { p.read() })
}

/// Copies the first `n` ≤ N doubles at `p` into an array (the rest 0) and rejects NaN/±∞.
///
/// # Safety
/// `p` must be NULL or point to `n` readable doubles.
pub(crate) unsafe fn load_finite<const N: usize>(
    p: *const f64,
    n: usize,
    what: &str,
) -> FfiResult<[f64; N]> {
    check_ptr(p, what)?;
    debug_assert!(n <= N);
    let mut out = [0.0; N];
    // SAFETY: non-NULL, aligned; n readable doubles by contract; `out` is a local.
    unsafe { std::ptr::copy_nonoverlapping(p, out.as_mut_ptr(), n.min(N)) };
    finite_all(&out, what)?;
    Ok(out)
}

/// Rejects NaN/±∞ in `values`, naming the input.
pub(crate) fn finite_all(values: &[f64], what: &str) -> FfiResult<()> {
    if all_finite(values) {
        return Ok(());
    }
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(FfiError::new(
            JOINTLIN_ERR_NON_FINITE,
            format!("{what}[{i}] is not finite"),
        )),
    }
}

/// Whether every value is finite: an exponent of all ones is NaN or ±∞. Branch-free over
/// the slice (the compiler vectorizes it), for the derivative arrays checked every step.
pub(crate) fn all_finite(values: &[f64]) -> bool {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    !values
        .iter()
        .fold(false, |bad, v| bad | (v.to_bits() & EXPONENT == EXPONENT))
}

/// Rejects a NaN/±∞ scalar, naming it.
pub(crate) fn finite(value: f64, what: &str) -> FfiResult<f64> {
    finite_all(&[value], what).map(|()| value)
}

/// Writes `value` to a pointer already checked by [`check_ptr`].
///
/// # Safety
/// `p` must be non-NULL, aligned and writable.
pub(crate) unsafe fn put<T>(p: *mut T, value: T) {
    // SAFETY: by the caller's contract.
    unsafe { p.write(value) }
}

/// Copies `src` to a pointer already checked by [`check_ptr`]. No reference to the
/// destination is created, so aliasing output arguments cannot cause undefined behaviour.
///
/// # Safety
/// `p` must be non-NULL, aligned and point to `src.len()` writable doubles.
pub(crate) unsafe fn put_all(p: *mut f64, src: &[f64]) {
    // SAFETY: by the caller's contract; `src` is a Rust-owned local that cannot overlap.
    unsafe { std::ptr::copy_nonoverlapping(src.as_ptr(), p, src.len()) }
}
