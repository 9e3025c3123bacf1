//! The iteration store object `jointlin_store` (thesis §4.3.2, Fig. 4.27): per contact
//! point × frequency increment, amplitude estimates handed out, amplitudes reported back,
//! and the decision which increments to re-run.

use std::ffi::c_char;
use std::path::PathBuf;

use super::error::{boundary, FfiError, FfiResult, JOINTLIN_ERR_OUT_OF_RANGE, JOINTLIN_ERR_SIZE};
use super::{check_ptr, load, load_finite, put, put_all};
use crate::iterate::Scheme;
use crate::store::{Action, KincNumbering, PassKind, PointKey, Reason, Store, StoreConfig};

/// An iteration store. Opaque; create with jointlin_store_new, destroy with
/// jointlin_store_free.
///
/// Threads. Every function may be called from any thread and is memory-safe with any
/// overlap: the store locks internally, each lock held for a few map operations, never
/// during file I/O. What the results mean depends on which calls overlap on one store:
///
/// - per-point calls (jointlin_uinter, jointlin_store_register_point,
///   jointlin_store_estimate, jointlin_store_report) and the queries
///   (jointlin_store_point_status, _point_count, _next_action, _rerun_increments,
///   _pass_stats, _restart_path): any number of threads at once, as Abaqus calls UINTER
///   from its threads, each call with its own arrays (one point's STATEV, STRESS, ... must
///   not be in two calls at once). The results do not depend on the threads' order;
/// - sequence calls (jointlin_uexternaldb, jointlin_store_restore,
///   jointlin_store_pass_summary, _pass_agree, _agree_files): one thread at a time, as
///   Abaqus calls UEXTERNALDB from one thread per process, and not overlapping the
///   per-point calls of the increment they open or close: LOP 1 returns before the
///   increment's LINPER = 1 calls start; LOP 2 starts after all of them and their reports
///   returned; LOP 0, 3, 4 and the pass calls while no per-point call runs. A call that
///   overlaps anyway returns JOINTLIN_OK or a named code (JOINTLIN_ERR_SEQUENCE,
///   JOINTLIN_ERR_UNKNOWN_POINT) and the store stays usable, but which increment the
///   overlapping call counted for is undefined;
/// - jointlin_store_free: no other call on the store during or after it.
///
/// Different stores (one per rank, or per analysis) are independent. jointlin_last_error
/// is per thread. The functions without a store (jointlin_linearize, jointlin_point_step,
/// jointlin_uinter at LINPER = 0, ...) may run anywhere at any time.
pub struct jointlin_store {
    _private: [u8; 0],
}

/// Update rule code: a <- a* (the thesis's "last computed amplitude"; may 2-cycle).
pub const JOINTLIN_SCHEME_DIRECT: i32 = 0;
/// Update rule code: a <- (a + a*)/2 (Fig. 4.14).
pub const JOINTLIN_SCHEME_RELAXATION: i32 = 1;
/// Update rule code: secant on ln a* - ln a, bracketed (default).
pub const JOINTLIN_SCHEME_SECANT: i32 = 2;
/// Increment numbering code: KINC is the sweep increment number in every pass.
pub const JOINTLIN_KINC_ORIGINAL: i32 = 0;
/// Increment numbering code: every pass numbers its increments 1..m; KINC = i is the i-th
/// scheduled sweep increment (ascending), as in a new Abaqus analysis over the re-run
/// frequencies.
pub const JOINTLIN_KINC_SEQUENTIAL: i32 = 1;

/// Next-action code: a pass is running (between LOP 0 and LOP 3).
pub const JOINTLIN_ACTION_RUNNING: i32 = 0;
/// Next-action code: run pass 1, the whole sweep.
pub const JOINTLIN_ACTION_RUN_SWEEP: i32 = 1;
/// Next-action code: re-run the increments listed by jointlin_store_rerun_increments.
pub const JOINTLIN_ACTION_RUN_PASS: i32 = 2;
/// Next-action code: all increments converged; run the final pass over the listed (all)
/// increments.
pub const JOINTLIN_ACTION_RUN_FINAL: i32 = 3;
/// Next-action code: the final pass confirmed every increment; finished.
pub const JOINTLIN_ACTION_DONE: i32 = 4;
/// Next-action code: increments (listed) still out of tolerance after max_passes.
pub const JOINTLIN_ACTION_FAILED: i32 = 5;

/// Settings of a store. Get the defaults from jointlin_store_config_default, then set at
/// least `initial_amplitude`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct jointlin_store_config {
    /// Amplitude estimate for the first increment of pass 1 (length, > 0; no default).
    pub initial_amplitude: f64,
    /// Relative tolerance, 0 <= rtol < 1 (default 1e-3): a point is converged when
    /// |a - a*| <= rtol * max(a, a*) + atol in every tangential direction.
    pub rtol: f64,
    /// Absolute tolerance (length, >= 0; default 0).
    pub atol: f64,
    /// JOINTLIN_SCHEME_* (default JOINTLIN_SCHEME_SECANT).
    pub scheme: i32,
    /// Most iteration passes (pass 1 plus re-runs), >= 1 (default 20); the final pass
    /// comes on top.
    pub max_passes: i32,
    /// KSTEP of the steady-state step that is iterated; 0 = every step (default 0).
    pub sweep_step: i32,
    /// JOINTLIN_KINC_* (default JOINTLIN_KINC_ORIGINAL).
    pub kinc_numbering: i32,
    /// Restart file path bytes (not NUL-terminated; NULL with length 0 = none; default
    /// none). Written atomically at LOP 2 when LRESTART >= 1 and at LOP 3; read at LOP 4
    /// and by jointlin_store_restore.
    pub restart_path: *const c_char,
    /// Length of `restart_path` in bytes.
    pub restart_path_len: usize,
}

/// Counts of one pass (Fig. 4.33: frequencies per analysis).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct jointlin_pass_stats {
    /// Pass number, 1-based.
    pub pass: i32,
    /// 0 first pass (whole sweep), 1 re-run, 2 final.
    pub kind: i32,
    /// Increments run in the pass.
    pub increments_run: i32,
    /// Of those, the increments where every queried point converged.
    pub increments_converged: i32,
    /// Point x increment comparisons made at LOP 2.
    pub evaluations: i64,
    /// Of those, points queried but never reported back.
    pub not_reported: i64,
}

/// What the store knows about one point at one sweep increment.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct jointlin_point_status {
    /// Estimates handed out in the latest pass that queried the point there (length).
    pub estimate: [f64; 2],
    /// Latest amplitudes reported back (length; 0 when none yet).
    pub computed: [f64; 2],
    /// Tangential directions compared (1 or 2).
    pub directions: i32,
    /// 1 when converged at the latest comparison, else 0.
    pub converged: i32,
    /// Passes in which the point was compared at this increment.
    pub passes: i32,
    /// 0 converged or not compared yet, 1 out of tolerance, 2 queried but not reported.
    pub reason: i32,
}

/// Borrows the store behind a handle.
///
/// # Safety
/// `store` must be NULL or a handle from jointlin_store_new that was not freed.
pub(crate) unsafe fn store_ref<'a>(store: *const jointlin_store) -> FfiResult<&'a Store> {
    check_ptr(store.cast::<Store>(), "store")?;
    // SAFETY: a live handle is a `Box<Store>` turned into a pointer by jointlin_store_new.
    Ok(unsafe { &*store.cast::<Store>() })
}

fn range(msg: String) -> FfiError {
    FfiError::new(JOINTLIN_ERR_OUT_OF_RANGE, msg)
}

/// Writes the default settings to `*out`: initial_amplitude 0 (must be set), rtol 1e-3,
/// atol 0, secant, 20 passes, every step, original numbering, no restart file.
///
/// # Safety
/// `out` must be NULL or point to a writable jointlin_store_config.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_config_default(out: *mut jointlin_store_config) -> i32 {
    boundary("jointlin_store_config_default", || {
        check_ptr(out, "out")?;
        let d = StoreConfig::new(0.0);
        let config = jointlin_store_config {
            initial_amplitude: 0.0,
            rtol: d.rtol,
            atol: d.atol,
            scheme: JOINTLIN_SCHEME_SECANT,
            max_passes: d.max_passes as i32,
            sweep_step: d.sweep_step,
            kinc_numbering: JOINTLIN_KINC_ORIGINAL,
            restart_path: std::ptr::null(),
            restart_path_len: 0,
        };
        // SAFETY: checked.
        unsafe { put(out, config) };
        Ok(())
    })
}

fn path_from_bytes(bytes: &[u8]) -> FfiResult<PathBuf> {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        Ok(PathBuf::from(std::ffi::OsStr::from_bytes(bytes)))
    }
    #[cfg(not(unix))]
    {
        std::str::from_utf8(bytes)
            .map(PathBuf::from)
            .map_err(|_| range("restart_path is not UTF-8".into()))
    }
}

/// Creates a store. On JOINTLIN_OK, `*out` receives a new handle owned by the caller, to be
/// released with jointlin_store_free; otherwise `*out` is not written. The configuration
/// (including the path bytes) is copied; the caller keeps ownership of it.
///
/// Errors: JOINTLIN_ERR_NULL (config, out, or restart_path NULL with a nonzero length),
/// JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_OUT_OF_RANGE (initial_amplitude <= 0, rtol outside
/// [0, 1), atol < 0, max_passes < 1, sweep_step < 0, unknown codes).
///
/// # Safety
/// `config` must point to a valid config whose restart_path (if not NULL) has
/// restart_path_len readable bytes; `out` must point to a writable handle.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_new(
    config: *const jointlin_store_config,
    out: *mut *mut jointlin_store,
) -> i32 {
    boundary("jointlin_store_new", || {
        // SAFETY: checked by `load`.
        let c = unsafe { load(config, "config") }?;
        check_ptr(out, "out")?;
        let scheme = match c.scheme {
            JOINTLIN_SCHEME_DIRECT => Scheme::Direct,
            JOINTLIN_SCHEME_RELAXATION => Scheme::Relaxation,
            JOINTLIN_SCHEME_SECANT => Scheme::Secant,
            s => return Err(range(format!("unknown scheme code {s}"))),
        };
        let numbering = match c.kinc_numbering {
            JOINTLIN_KINC_ORIGINAL => KincNumbering::Original,
            JOINTLIN_KINC_SEQUENTIAL => KincNumbering::Sequential,
            n => return Err(range(format!("unknown kinc_numbering code {n}"))),
        };
        let max_passes = u32::try_from(c.max_passes)
            .map_err(|_| range(format!("max_passes {} must be >= 1", c.max_passes)))?;
        let restart_path = if c.restart_path.is_null() && c.restart_path_len == 0 {
            None
        } else {
            check_ptr(c.restart_path, "config restart_path")?;
            if c.restart_path_len == 0 || c.restart_path_len > 4096 {
                return Err(range("restart_path_len must be 1..=4096".into()));
            }
            // SAFETY: non-NULL, `restart_path_len` readable bytes by contract.
            let bytes = unsafe {
                std::slice::from_raw_parts(c.restart_path.cast::<u8>(), c.restart_path_len)
            };
            Some(path_from_bytes(bytes)?)
        };
        let store = Store::new(StoreConfig {
            initial_amplitude: c.initial_amplitude,
            rtol: c.rtol,
            atol: c.atol,
            scheme,
            max_passes,
            sweep_step: c.sweep_step,
            numbering,
            restart_path,
        })?;
        let handle = Box::into_raw(Box::new(store)).cast::<jointlin_store>();
        // SAFETY: checked.
        unsafe { put(out, handle) };
        Ok(())
    })
}

/// Destroys a store created by jointlin_store_new. NULL is ignored. No other thread may use
/// the store during or after this call.
///
/// # Safety
/// `store` must be NULL or a live handle from jointlin_store_new, freed only once.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_free(store: *mut jointlin_store) {
    if !store.is_null() {
        // SAFETY: a live handle from jointlin_store_new is a leaked Box<Store>. Dropping it
        // only frees memory (no user code), so it cannot unwind.
        drop(unsafe { Box::from_raw(store.cast::<Store>()) });
    }
}

/// Registers a contact point by its key (interaction name, NODE, coordinates) and writes
/// its stable 1-based id to `*id`. The same key always gives the same id; NODE alone is not
/// a key (it is 0 for surface-to-surface contact). Trailing blanks and NULs of the name
/// are ignored (Fortran CHARACTER padding); -0.0 equals 0.0.
///
/// `name` has `name_len` bytes (0..256, not NUL-terminated; must not be NULL even when
/// empty); `coords` has `mcrd` doubles (1..3). Errors: JOINTLIN_ERR_NULL,
/// JOINTLIN_ERR_NON_FINITE (coords), JOINTLIN_ERR_OUT_OF_RANGE (mcrd, name_len).
///
/// # Safety
/// Pointers must be valid for the given lengths; `id` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_register_point(
    store: *const jointlin_store,
    name: *const c_char,
    name_len: usize,
    node: i32,
    coords: *const f64,
    mcrd: i32,
    id: *mut i64,
) -> i32 {
    boundary("jointlin_store_register_point", || {
        // SAFETY: checked by the helpers; lengths by contract.
        let s = unsafe { store_ref(store) }?;
        check_ptr(id, "id")?;
        let key = unsafe { key_from_raw(name, name_len, node, coords, mcrd) }?;
        let point = s.register(key)?;
        // SAFETY: checked.
        unsafe { put(id, point) };
        Ok(())
    })
}

/// The key of a point from raw UINTER-style arguments.
///
/// # Safety
/// `name` valid for `name_len` bytes, `coords` for `mcrd` doubles (when non-NULL).
pub(crate) unsafe fn key_from_raw(
    name: *const c_char,
    name_len: usize,
    node: i32,
    coords: *const f64,
    mcrd: i32,
) -> FfiResult<PointKey> {
    check_ptr(name, "name")?;
    if name_len > crate::store::MAX_NAME_LEN {
        return Err(range(format!("name length {name_len} > 256")));
    }
    if !(1..=3).contains(&mcrd) {
        return Err(range(format!("mcrd {mcrd} not in 1..=3")));
    }
    // SAFETY: by the caller's contract.
    let xyz: [f64; 3] = unsafe { load_finite(coords, mcrd as usize, "coords") }?;
    let bytes = unsafe { std::slice::from_raw_parts(name.cast::<u8>(), name_len) };
    Ok(PointKey::new(bytes, node, &xyz[..mcrd as usize])?)
}

/// Writes the amplitude estimates (length) of point `point` for increment `kinc` of the
/// running pass to `amp[0]`, `amp[1]` (tangential directions 1 and 2). The estimate is
/// fixed at the first query in a pass; pass 1: the initial amplitude at the first
/// increment, else the amplitude computed at the nearest earlier increment; later passes:
/// the configured update rule on the point's history, in the point's own scale (no floor
/// tied to initial_amplitude): a point whose latest computed amplitude was exactly 0 gets
/// 0, so a zero load gives zero and converges. Both directions take part in the
/// convergence test (jointlin_uinter queries only NDIR - 1 of them).
///
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_UNKNOWN_POINT, JOINTLIN_ERR_SEQUENCE (no pass
/// running, no increment open, or `kinc` is not the open increment).
///
/// # Safety
/// `store` a live handle; `amp` points to 2 writable doubles.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_estimate(
    store: *const jointlin_store,
    point: i64,
    kinc: i32,
    amp: *mut f64,
) -> i32 {
    boundary("jointlin_store_estimate", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        check_ptr(amp, "amp")?;
        let a = s.estimate(point, kinc, 2)?;
        // SAFETY: checked; 2 doubles by contract.
        unsafe { put_all(amp, &a) };
        Ok(())
    })
}

/// Reports the amplitudes (length, >= 0) the host computed for point `point` in the open
/// increment `kinc`, after its estimate was queried there (by jointlin_store_estimate or
/// jointlin_uinter). A later report in the same increment replaces an earlier one.
///
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_OUT_OF_RANGE (negative),
/// JOINTLIN_ERR_UNKNOWN_POINT, JOINTLIN_ERR_SEQUENCE (not queried in this increment, or no
/// increment open).
///
/// # Safety
/// `store` a live handle; `amp` points to 2 readable doubles.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_report(
    store: *const jointlin_store,
    point: i64,
    kinc: i32,
    amp: *const f64,
) -> i32 {
    boundary("jointlin_store_report", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        let a: [f64; 2] = unsafe { load_finite(amp, 2, "amp") }?;
        s.report(point, kinc, a)?;
        Ok(())
    })
}

/// jointlin_store_report for the point registered for host node `node` (the NODE of its
/// jointlin_uinter calls), for hosts that know their results per node, such as an Abaqus
/// URDFIL reading the contact output of an increment. Writes 1 to `*reported` if it
/// reported, 0 if no point has that node (a slave node UINTER never saw: nothing to do).
///
/// Errors: those of jointlin_store_report, and JOINTLIN_ERR_UNKNOWN_POINT when several
/// points (one per interaction) have that node.
///
/// # Safety
/// `store` a live handle; `amp` points to 2 readable doubles; `reported` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_report_node(
    store: *const jointlin_store,
    node: i32,
    kinc: i32,
    amp: *const f64,
    reported: *mut i32,
) -> i32 {
    boundary("jointlin_store_report_node", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        let a: [f64; 2] = unsafe { load_finite(amp, 2, "amp") }?;
        check_ptr(reported, "reported")?;
        let done = match s.point_of_node(node)? {
            Some(point) => {
                s.report(point, kinc, a)?;
                1
            }
            None => 0,
        };
        // SAFETY: checked.
        unsafe { put(reported, done) };
        Ok(())
    })
}

/// Writes the next action (JOINTLIN_ACTION_*) to `*action` and to `*pass` the number of the
/// pass it would run (for DONE and FAILED: the last pass run; while RUNNING: the running
/// pass). For RUN_PASS, RUN_FINAL and FAILED, jointlin_store_rerun_increments lists the
/// increments.
///
/// # Safety
/// `store` a live handle; `action`, `pass` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_next_action(
    store: *const jointlin_store,
    action: *mut i32,
    pass: *mut i32,
) -> i32 {
    boundary("jointlin_store_next_action", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        check_ptr(action, "action")?;
        check_ptr(pass, "pass")?;
        let (code, number) = match s.next_action()? {
            None => (JOINTLIN_ACTION_RUNNING, s.passes()?),
            Some((a, n)) => (action_code(&a), n),
        };
        // SAFETY: checked.
        unsafe {
            put(action, code);
            put(pass, number as i32);
        }
        Ok(())
    })
}

fn action_code(a: &Action) -> i32 {
    match a {
        Action::RunSweep => JOINTLIN_ACTION_RUN_SWEEP,
        Action::RunPass(_) => JOINTLIN_ACTION_RUN_PASS,
        Action::RunFinal(_) => JOINTLIN_ACTION_RUN_FINAL,
        Action::Done => JOINTLIN_ACTION_DONE,
        Action::Failed(_) => JOINTLIN_ACTION_FAILED,
    }
}

/// Lists the sweep increments (KINC of pass 1, ascending) of the next action: to re-run
/// (RUN_PASS), all of them (RUN_FINAL), or those left unconverged (FAILED); none otherwise.
/// `*count` receives the number of increments. When it exceeds `cap`, the call returns
/// JOINTLIN_ERR_SIZE, writes `*count` only (so the caller can size its buffer) and leaves
/// `kinc` untouched. With `cap` = 0, `kinc` may be NULL (a pure size query).
///
/// # Safety
/// `store` a live handle; `kinc` points to `cap` writable ints (or is NULL when `cap` is 0);
/// `count` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_rerun_increments(
    store: *const jointlin_store,
    kinc: *mut i32,
    cap: usize,
    count: *mut usize,
) -> i32 {
    boundary("jointlin_store_rerun_increments", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        if cap > 0 {
            check_ptr(kinc, "kinc")?;
        }
        check_ptr(count, "count")?;
        let list = match s.next_action()? {
            Some((Action::RunPass(l) | Action::RunFinal(l) | Action::Failed(l), _)) => l,
            _ => Vec::new(),
        };
        // SAFETY: checked.
        unsafe { put(count, list.len()) };
        if list.len() > cap {
            return Err(FfiError::new(
                JOINTLIN_ERR_SIZE,
                format!("{} increments do not fit in {cap}", list.len()),
            ));
        }
        if !list.is_empty() {
            // SAFETY: cap >= len > 0, so kinc was checked non-NULL; cap writable ints by contract.
            unsafe { std::ptr::copy_nonoverlapping(list.as_ptr(), kinc, list.len()) };
        }
        Ok(())
    })
}

/// Writes the counts of pass `pass` (1-based, started already) to `*out`.
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_OUT_OF_RANGE (no such pass).
///
/// # Safety
/// `store` a live handle; `out` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_pass_stats(
    store: *const jointlin_store,
    pass: i32,
    out: *mut jointlin_pass_stats,
) -> i32 {
    boundary("jointlin_store_pass_stats", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        check_ptr(out, "out")?;
        let st = u32::try_from(pass)
            .ok()
            .map(|p| s.pass_stats(p))
            .transpose()?
            .flatten()
            .ok_or_else(|| range(format!("pass {pass} was not started")))?;
        let stats = jointlin_pass_stats {
            pass: st.number as i32,
            kind: match st.kind {
                PassKind::First => 0,
                PassKind::Rerun => 1,
                PassKind::Final => 2,
            },
            increments_run: st.increments_run as i32,
            increments_converged: st.increments_converged as i32,
            evaluations: st.evaluations as i64,
            not_reported: st.not_reported as i64,
        };
        // SAFETY: checked.
        unsafe { put(out, stats) };
        Ok(())
    })
}

/// Writes what the store knows about point `point` at sweep increment `kinc` to `*out`.
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_UNKNOWN_POINT, JOINTLIN_ERR_OUT_OF_RANGE (the
/// point was never queried at that increment).
///
/// # Safety
/// `store` a live handle; `out` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_point_status(
    store: *const jointlin_store,
    point: i64,
    kinc: i32,
    out: *mut jointlin_point_status,
) -> i32 {
    boundary("jointlin_store_point_status", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        check_ptr(out, "out")?;
        let st = s
            .point_status(point, kinc)?
            .ok_or_else(|| range(format!("point {point} never queried at increment {kinc}")))?;
        let status = jointlin_point_status {
            estimate: st.estimate,
            computed: st.computed,
            directions: st.directions as i32,
            converged: i32::from(st.converged),
            passes: st.passes as i32,
            reason: match st.reason {
                Reason::None => 0,
                Reason::OutOfTolerance => 1,
                Reason::NotReported => 2,
            },
        };
        // SAFETY: checked.
        unsafe { put(out, status) };
        Ok(())
    })
}

/// Writes the number of registered points to `*count`.
///
/// # Safety
/// `store` a live handle; `count` writable.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_point_count(
    store: *const jointlin_store,
    count: *mut i64,
) -> i32 {
    boundary("jointlin_store_point_count", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        check_ptr(count, "count")?;
        let n = s.point_count()?;
        // SAFETY: checked.
        unsafe { put(count, n) };
        Ok(())
    })
}

/// Replaces the store's points and iteration state by the content of its restart file
/// (what LOP 4 does); a sequence call (see jointlin_store: not during per-point calls). Use it when a new analysis job continues the iteration of an earlier
/// one (each Abaqus pass is a separate job): restore, then LOP 0.
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_IO (no path configured, unreadable or corrupt
/// file; the store is unchanged then).
///
/// # Safety
/// `store` a live handle.
#[no_mangle]
pub unsafe extern "C" fn jointlin_store_restore(store: *const jointlin_store) -> i32 {
    boundary("jointlin_store_restore", || {
        // SAFETY: checked by the helper.
        unsafe { store_ref(store) }?.restore()?;
        Ok(())
    })
}
