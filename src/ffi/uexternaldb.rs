//! `jointlin_uexternaldb`: Abaqus's UEXTERNALDB(LOP, LRESTART, TIME, DTIME, KSTEP, KINC)
//! forwarded to the iteration store (thesis §4.3.2, Fig. 4.27).

use super::error::boundary;
use super::store::{jointlin_store, store_ref};
use super::{finite, load_finite};

/// Drives the store's iteration from Abaqus's UEXTERNALDB arguments:
///
/// | LOP | Abaqus meaning              | store action                                        |
/// |-----|-----------------------------|-----------------------------------------------------|
/// | 0   | start of the analysis       | starts the next pass (pass 1, a re-run, the final)  |
/// | 1   | start of increment KINC     | opens the increment (ignored outside the sweep step)|
/// | 2   | end of increment KINC       | compares estimates and reported amplitudes of every point queried in it (queried but not reported = not converged); writes the restart file when LRESTART >= 1 and a path is set |
/// | 3   | end of the analysis         | closes the pass, decides the next action, writes the restart file if a path is set |
/// | 4   | start of a restart analysis | restores the store from its restart file            |
/// | 5/6 | start/end of step KSTEP     | tracks the step                                     |
///
/// `time` (2 doubles) and `dtime` are checked but not used. Errors: JOINTLIN_ERR_NULL,
/// JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_OUT_OF_RANGE (LOP not in 0..6),
/// JOINTLIN_ERR_SEQUENCE (a call out of order, e.g. LOP 1 twice without LOP 2, LOP 0 while a
/// pass runs or after DONE), JOINTLIN_ERR_IO (restart file).
///
/// Threads: one thread at a time per store (Abaqus: one thread per process), never
/// overlapping the per-point calls (jointlin_uinter, estimate, report) of the increment it
/// opens (LOP 1: they start after it returns) or closes (LOP 2: it starts after they all
/// returned); see jointlin_store.
///
/// # Safety
/// `store` a live handle; `time` points to 2 readable doubles.
#[no_mangle]
pub unsafe extern "C" fn jointlin_uexternaldb(
    store: *const jointlin_store,
    lop: i32,
    lrestart: i32,
    time: *const f64,
    dtime: f64,
    kstep: i32,
    kinc: i32,
) -> i32 {
    boundary("jointlin_uexternaldb", || {
        // SAFETY: checked by the helpers.
        let s = unsafe { store_ref(store) }?;
        let _: [f64; 2] = unsafe { load_finite(time, 2, "time") }?;
        finite(dtime, "dtime")?;
        s.external_db(lop, lrestart, kstep, kinc)?;
        Ok(())
    })
}
