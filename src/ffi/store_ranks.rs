//! Stores of a job with several processes (MPI ranks): one store per rank, its own restart
//! file, and the end-of-pass agreement on which increments to re-run (model.md §7). The
//! library needs no MPI: the host reduces the summaries through its own communicator, or
//! the ranks use the file protocol.
//!
//! Per pass, on every rank, after the LOP 2 of the pass's last increment and before LOP 3:
//!
//! ```text
//! jointlin_store_pass_summary(store, NULL, 0, &len)      -> JOINTLIN_ERR_SIZE, len
//! (all ranks check they have the same len: MPI_Allreduce of {len, -len} with MPI_MAX)
//! jointlin_store_pass_summary(store, buf, len, &len)     -> this rank's summary
//! MPI_Allreduce(MPI_IN_PLACE, buf, len, MPI_INT32_T, MPI_MAX, comm)
//! jointlin_store_pass_agree(store, buf, len)             -> the agreed decision
//! jointlin_uexternaldb(store, 3, ...)                    -> the same next action everywhere
//! ```
//!
//! or, without a communicator, `jointlin_store_agree_files` in place of the middle three.

use std::ffi::c_char;
use std::time::Duration;

use super::error::{boundary, FfiError, JOINTLIN_ERR_OUT_OF_RANGE, JOINTLIN_ERR_SIZE};
use super::store::{jointlin_store, jointlin_store_config, jointlin_store_new, store_ref};
use super::{check_ptr, finite, put};
use crate::store::{PassSummary, Store};

fn rank_pair(rank: i32, ranks: i32) -> Result<(u32, u32), FfiError> {
    match (u32::try_from(rank), u32::try_from(ranks)) {
        (Ok(r), Ok(n)) if r < n => Ok((r, n)),
        _ => Err(FfiError::new(
            JOINTLIN_ERR_OUT_OF_RANGE,
            format!("rank {rank} of {ranks}: need 0 <= rank < ranks"),
        )),
    }
}

/// Creates the store of rank `rank` (0-based) of `ranks` processes: as jointlin_store_new,
/// but with `ranks` > 1 its restart file is `<restart_path>.r<rank>` (e.g.
/// `jointlin.restart.r3`), so that every rank saves and restores its own points. When
/// that file does not exist (a new iteration), the rank's pass files of an earlier
/// iteration (`<restart_path>.r<rank>.pass<P>`, jointlin_store_agree_files) are deleted.
/// `ranks` = 1 is jointlin_store_new.
///
/// Errors: those of jointlin_store_new; JOINTLIN_ERR_OUT_OF_RANGE (not 0 <= rank < ranks);
/// JOINTLIN_ERR_IO (stale pass files that cannot be deleted).
///
/// # Safety
/// As jointlin_store_new.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_new_ranked(
    config: *const jointlin_store_config,
    rank: i32,
    ranks: i32,
    out: *mut *mut jointlin_store,
) -> i32 {
    let mut plain: *mut jointlin_store = std::ptr::null_mut();
    // SAFETY: the caller's contract is jointlin_store_new's; `plain` is a local.
    let status = unsafe { jointlin_store_new(config, &mut plain) };
    if status != super::error::JOINTLIN_OK {
        return status; // jointlin_store_new recorded the detail
    }
    boundary("jointlin_store_new_ranked", || {
        // SAFETY: `plain` is the live handle just created, owned here (dropped on error).
        let fresh = unsafe { Box::from_raw(plain.cast::<Store>()) };
        check_ptr(out, "out")?;
        let (r, n) = rank_pair(rank, ranks)?;
        let store = Store::new_ranked(fresh.config().clone(), r, n)?;
        let handle = Box::into_raw(Box::new(store)).cast::<jointlin_store>();
        // SAFETY: checked.
        unsafe { put(out, handle) };
        Ok(())
    })
}

/// Writes the store's restart file path (bytes, not NUL-terminated) to `buf` and its
/// length to `*len`; 0 when the store has none. When the length exceeds `cap`, returns
/// JOINTLIN_ERR_SIZE and writes `*len` only. With `cap` = 0, `buf` may be NULL.
///
/// # Safety
/// `store` a live handle; `buf` points to `cap` writable bytes (or is NULL when `cap` is
/// 0); `len` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_restart_path(
    store: *const jointlin_store,
    buf: *mut c_char,
    cap: usize,
    len: *mut usize,
) -> i32 {
    boundary("jointlin_store_restart_path", || {
        // SAFETY: checked by the helper.
        let s = unsafe { store_ref(store) }?;
        if cap > 0 {
            check_ptr(buf, "buf")?;
        }
        check_ptr(len, "len")?;
        let bytes: Vec<u8> = s
            .config()
            .restart_path
            .as_ref()
            .map(|p| p.as_os_str().as_encoded_bytes().to_vec())
            .unwrap_or_default();
        // SAFETY: checked.
        unsafe { put(len, bytes.len()) };
        if bytes.len() > cap {
            return Err(FfiError::new(
                JOINTLIN_ERR_SIZE,
                format!("a path of {} bytes does not fit in {cap}", bytes.len()),
            ));
        }
        if !bytes.is_empty() {
            // SAFETY: cap >= bytes.len() > 0, so `buf` was checked; cap writable bytes.
            unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), buf.cast::<u8>(), bytes.len()) };
        }
        Ok(())
    })
}

/// Writes this rank's summary of the running pass to `summary` and its length (4 + 3n for
/// n sweep increments) to `*len`: between the LOP 2 of the pass's last increment and LOP 3.
/// The layout is made for an element-wise maximum over the ranks (`MPI_MAX`):
/// `{pass, -pass, n, -n, k_1..k_n, -k_1..-k_n, r_1..r_n}`, k ascending sweep increments,
/// r = 1 when the increment must be re-run on this rank (not converged here), else 0. After
/// the maximum, r = 1 when any rank needs the re-run, and the negated copies carry the
/// minimum, from which jointlin_store_pass_agree sees whether all ranks were at the same
/// pass with the same increments.
///
/// When `*len` exceeds `cap`, returns JOINTLIN_ERR_SIZE and writes `*len` only (with `cap`
/// = 0, `summary` may be NULL: a size query). All ranks must reduce arrays of the same
/// length: check that first (reduce {len, -len} by maximum).
///
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_SIZE, JOINTLIN_ERR_SEQUENCE (no pass running or
/// an increment open).
///
/// # Safety
/// `store` a live handle; `summary` points to `cap` writable int32_t (or is NULL when
/// `cap` is 0); `len` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_pass_summary(
    store: *const jointlin_store,
    summary: *mut i32,
    cap: usize,
    len: *mut usize,
) -> i32 {
    boundary("jointlin_store_pass_summary", || {
        // SAFETY: checked by the helper.
        let s = unsafe { store_ref(store) }?;
        if cap > 0 {
            check_ptr(summary, "summary")?;
        }
        check_ptr(len, "len")?;
        let encoded = s.pass_summary()?.encode()?;
        // SAFETY: checked.
        unsafe { put(len, encoded.len()) };
        if encoded.len() > cap {
            return Err(FfiError::new(
                JOINTLIN_ERR_SIZE,
                format!(
                    "a summary of {} integers does not fit in {cap}",
                    encoded.len()
                ),
            ));
        }
        // SAFETY: cap >= encoded.len() > 0, so `summary` was checked; cap writable ints.
        unsafe { std::ptr::copy_nonoverlapping(encoded.as_ptr(), summary, encoded.len()) };
        Ok(())
    })
}

/// Replaces this rank's decision for the running pass by the agreed one: `reduced` (`len`
/// integers) is the element-wise maximum over all ranks of their
/// jointlin_store_pass_summary arrays. The next LOP 3 decides from it, so every rank
/// decides the same next action and re-run list. Call between the last LOP 2 and LOP 3.
///
/// Errors: JOINTLIN_ERR_NULL; JOINTLIN_ERR_OUT_OF_RANGE (not a summary); JOINTLIN_ERR_SEQUENCE
/// (ranks at different passes or with different increments, a summary of another pass or
/// increments than this store's, one that does not re-run an increment this rank must
/// re-run, or no pass running). The store is unchanged on error.
///
/// # Safety
/// `store` a live handle; `reduced` points to `len` readable int32_t.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_pass_agree(
    store: *const jointlin_store,
    reduced: *const i32,
    len: usize,
) -> i32 {
    boundary("jointlin_store_pass_agree", || {
        // SAFETY: checked by the helper.
        let s = unsafe { store_ref(store) }?;
        check_ptr(reduced, "reduced")?;
        if len > PassSummary::encoded_len(1 << 24) {
            return Err(FfiError::new(
                JOINTLIN_ERR_OUT_OF_RANGE,
                format!("summary length {len}"),
            ));
        }
        // SAFETY: non-NULL, aligned, `len` readable ints by contract.
        let buf = unsafe { std::slice::from_raw_parts(reduced, len) };
        s.pass_agree(&PassSummary::decode(buf)?)?;
        Ok(())
    })
}

/// The agreement without a communicator, through files beside the restart files (in a
/// directory all ranks share): rank `rank` of `ranks` writes its summary to
/// `<restart_path>.r<rank>.pass<P>` (atomically: a temporary file, then a rename), waits
/// until the files of all ranks for pass P exist (polling every 20 ms, at most `timeout`
/// seconds), reduces them by maximum, agrees (jointlin_store_pass_agree) and deletes its
/// own file of pass P - 1. Call between the last LOP 2 and LOP 3 of every pass, on every
/// rank. The store must come from jointlin_store_new_ranked with the same rank and ranks
/// and a restart path. `ranks` = 1 agrees with itself and writes nothing.
///
/// Errors: JOINTLIN_ERR_NULL; JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_OUT_OF_RANGE (timeout
/// <= 0, rank, a store not made for this rank); JOINTLIN_ERR_IO (no restart path, files
/// that cannot be written or read, ranks still missing after `timeout`: the detail names
/// them); JOINTLIN_ERR_SEQUENCE (ranks at different passes or increments, no pass
/// running).
///
/// # Safety
/// `store` a live handle.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_agree_files(
    store: *const jointlin_store,
    rank: i32,
    ranks: i32,
    timeout: f64,
) -> i32 {
    boundary("jointlin_store_agree_files", || {
        // SAFETY: checked by the helper.
        let s = unsafe { store_ref(store) }?;
        let (r, n) = rank_pair(rank, ranks)?;
        finite(timeout, "timeout")?;
        let wait = Duration::try_from_secs_f64(timeout)
            .ok()
            .filter(|d| !d.is_zero())
            .ok_or_else(|| {
                FfiError::new(
                    JOINTLIN_ERR_OUT_OF_RANGE,
                    format!("timeout {timeout} s must be > 0"),
                )
            })?;
        s.agree_by_files(r, n, wait)?;
        Ok(())
    })
}
