//! `jointlin_store_set_model`: the host's model fingerprint, so that a restart file
//! written for another model is rejected at LOP 4 instead of scheduling increments that
//! do not exist.

use std::ffi::c_char;

use super::check_ptr;
use super::error::boundary;
use super::store::{jointlin_store, store_ref};

/// Sets the store's model fingerprint: `len` bytes (at most 4096, not NUL-terminated;
/// NULL with `len` 0 clears it) that identify the model the sweep runs, e.g. a hash of
/// the input deck, the job's contact definitions and frequencies. Call it right after
/// creating the store, before LOP 0 or LOP 4.
///
/// The restart file (format 4) carries the fingerprint and the store's settings
/// (initial_amplitude, rtol, atol, scheme, max_passes, sweep_step, kinc_numbering), each
/// point's key with the CRC-32 of its PROPS (points met through jointlin_uinter), and
/// ends with a CRC-32 of its content; LOP 4 and jointlin_store_restore reject a file
/// whose fingerprint or settings differ, or whose checksum does not match (changed or
/// cut), with JOINTLIN_ERR_IO, leaving the store unchanged. After such a restore a point
/// the file does not list, or lists with other PROPS (a file another job left), is
/// JOINTLIN_ERR_IO at its first call. A file of the older format 1 (no fingerprints)
/// is read only by a store without a fingerprint; formats 2 (no checksum) and 3 (no
/// PROPS) are refused.
///
/// Errors: JOINTLIN_ERR_NULL (`store`, or `bytes` with `len` > 0), JOINTLIN_ERR_OUT_OF_RANGE
/// (`len` > 4096).
///
/// # Safety
/// `store` a live handle; `bytes` points to `len` readable bytes (or is NULL when `len` is 0).
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_set_model(
    store: *const jointlin_store,
    bytes: *const c_char,
    len: usize,
) -> i32 {
    boundary("jointlin_store_set_model", || {
        // SAFETY: checked by the helper.
        let s = unsafe { store_ref(store) }?;
        let fingerprint: &[u8] = if len == 0 {
            &[]
        } else {
            check_ptr(bytes, "bytes")?;
            if len > crate::store::MAX_MODEL_LEN {
                return Err(crate::store::StoreError::OutOfRange(
                    "model fingerprint longer than 4096 bytes",
                )
                .into());
            }
            // SAFETY: non-NULL, `len` readable bytes by contract.
            unsafe { std::slice::from_raw_parts(bytes.cast::<u8>(), len) }
        };
        s.set_model(fingerprint)?;
        Ok(())
    })
}
