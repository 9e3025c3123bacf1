//! The UEXTERNALDB-side iteration store (`jointlin_store`) through the C API: pass
//! actions, estimates, reports and pass statistics.

use std::ffi::c_char;
use std::ptr::{self, NonNull};

use jointlin::ffi::error::JOINTLIN_OK;
use jointlin::ffi::store::{
    jointlin_pass_stats, jointlin_store, jointlin_store_config, jointlin_store_config_default,
    jointlin_store_estimate, jointlin_store_free, jointlin_store_new, jointlin_store_next_action,
    jointlin_store_pass_stats, jointlin_store_register_point, jointlin_store_report,
    jointlin_store_rerun_increments, JOINTLIN_ACTION_DONE, JOINTLIN_ACTION_FAILED,
    JOINTLIN_ACTION_RUNNING, JOINTLIN_ACTION_RUN_FINAL, JOINTLIN_ACTION_RUN_PASS,
    JOINTLIN_ACTION_RUN_SWEEP, JOINTLIN_SCHEME_DIRECT, JOINTLIN_SCHEME_RELAXATION,
    JOINTLIN_SCHEME_SECANT,
};
use jointlin::ffi::uexternaldb::jointlin_uexternaldb;

use super::{check, count, CapiError};
use crate::names::SchemeName;

/// What the store says to do next.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Action {
    Running,
    RunSweep,
    RunPass(Vec<i32>),
    RunFinal(Vec<i32>),
    Done,
    Failed(Vec<i32>),
}

/// Counts of one pass (Fig. 4.33).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct PassStats {
    pub pass: i32,
    /// 0 first, 1 re-run, 2 final.
    pub kind: i32,
    pub increments_run: i32,
    pub increments_converged: i32,
}

/// An owned iteration store (`jointlin_store`).
#[derive(Debug)]
pub struct Store(pub(super) NonNull<jointlin_store>);

// SAFETY: the library documents the store as shareable between threads.
unsafe impl Send for Store {}
unsafe impl Sync for Store {}

impl Store {
    /// A store for the steady-state step `sweep_step`.
    pub fn new(
        initial_amplitude: f64,
        rtol: f64,
        atol: f64,
        scheme: SchemeName,
        max_passes: usize,
        sweep_step: i32,
    ) -> Result<Store, CapiError> {
        count(|c| c.store += 1);
        let mut cfg = jointlin_store_config {
            initial_amplitude: 0.0,
            rtol: 0.0,
            atol: 0.0,
            scheme: 0,
            max_passes: 0,
            sweep_step: 0,
            kinc_numbering: 0,
            restart_path: ptr::null(),
            restart_path_len: 0,
        };
        // SAFETY: cfg is a writable local.
        check("jointlin_store_config_default", unsafe {
            jointlin_store_config_default(&mut cfg)
        })?;
        cfg.initial_amplitude = initial_amplitude;
        cfg.rtol = rtol;
        cfg.atol = atol;
        cfg.scheme = match scheme {
            SchemeName::Direct => JOINTLIN_SCHEME_DIRECT,
            SchemeName::Relaxation => JOINTLIN_SCHEME_RELAXATION,
            SchemeName::Secant => JOINTLIN_SCHEME_SECANT,
        };
        cfg.max_passes = i32::try_from(max_passes).unwrap_or(i32::MAX);
        cfg.sweep_step = sweep_step;
        let mut out: *mut jointlin_store = ptr::null_mut();
        // SAFETY: cfg valid (no restart path); out writable.
        check("jointlin_store_new", unsafe {
            jointlin_store_new(&cfg, &mut out)
        })?;
        Ok(Store(NonNull::new(out).expect("OK status gives a handle")))
    }

    /// UEXTERNALDB(LOP, LRESTART = 0, TIME, DTIME, KSTEP, KINC).
    pub fn external_db(&self, lop: i32, kstep: i32, kinc: i32) -> Result<(), CapiError> {
        count(|c| c.uexternaldb += 1);
        let time = [0.0, 0.0];
        // SAFETY: live handle, time has 2 doubles.
        let code = unsafe {
            jointlin_uexternaldb(self.0.as_ptr(), lop, 0, time.as_ptr(), 0.0, kstep, kinc)
        };
        check("jointlin_uexternaldb", code)
    }

    /// Registers a point that the host linearizes itself (not through UINTER, e.g. a
    /// cubic spring) by its key (name, node, coordinates); returns its store id.
    pub fn register_point(
        &self,
        name: &str,
        node: i32,
        coords: [f64; 3],
    ) -> Result<i64, CapiError> {
        count(|c| c.store += 1);
        let mut id = 0i64;
        // SAFETY: live handle; name valid for its length, coords 3 doubles, id writable.
        check("jointlin_store_register_point", unsafe {
            jointlin_store_register_point(
                self.0.as_ptr(),
                name.as_ptr().cast::<c_char>(),
                name.len(),
                node,
                coords.as_ptr(),
                3,
                &mut id,
            )
        })?;
        Ok(id)
    }

    /// The amplitude estimates (length, two directions) of `point` for the open increment.
    pub fn estimate(&self, point: i64, kinc: i32) -> Result<[f64; 2], CapiError> {
        count(|c| c.store += 1);
        let mut amp = [0.0; 2];
        // SAFETY: live handle, amp has 2 writable doubles.
        check("jointlin_store_estimate", unsafe {
            jointlin_store_estimate(self.0.as_ptr(), point, kinc, amp.as_mut_ptr())
        })?;
        Ok(amp)
    }

    /// Reports the computed amplitudes (both tangential directions) of `point` in `kinc`.
    pub fn report(&self, point: i64, kinc: i32, amp: [f64; 2]) -> Result<(), CapiError> {
        count(|c| c.store += 1);
        // SAFETY: live handle, amp has 2 doubles.
        check("jointlin_store_report", unsafe {
            jointlin_store_report(self.0.as_ptr(), point, kinc, amp.as_ptr())
        })
    }

    /// The next action and the pass number it concerns.
    pub fn next_action(&self) -> Result<(Action, i32), CapiError> {
        count(|c| c.store += 1);
        let (mut action, mut pass) = (0i32, 0i32);
        // SAFETY: live handle, writable locals.
        check("jointlin_store_next_action", unsafe {
            jointlin_store_next_action(self.0.as_ptr(), &mut action, &mut pass)
        })?;
        let list = || -> Result<Vec<i32>, CapiError> {
            let mut n = 0usize;
            // SAFETY: cap 0 asks for the count; kinc not touched.
            let mut dummy = 0i32;
            let code =
                unsafe { jointlin_store_rerun_increments(self.0.as_ptr(), &mut dummy, 0, &mut n) };
            if n > 0 || code != JOINTLIN_OK {
                let mut v = vec![0i32; n];
                // SAFETY: v has n writable ints.
                check("jointlin_store_rerun_increments", unsafe {
                    jointlin_store_rerun_increments(self.0.as_ptr(), v.as_mut_ptr(), n, &mut n)
                })?;
                return Ok(v);
            }
            Ok(Vec::new())
        };
        let a = match action {
            JOINTLIN_ACTION_RUNNING => Action::Running,
            JOINTLIN_ACTION_RUN_SWEEP => Action::RunSweep,
            JOINTLIN_ACTION_RUN_PASS => Action::RunPass(list()?),
            JOINTLIN_ACTION_RUN_FINAL => Action::RunFinal(list()?),
            JOINTLIN_ACTION_DONE => Action::Done,
            JOINTLIN_ACTION_FAILED => Action::Failed(list()?),
            other => {
                return Err(CapiError {
                    function: "jointlin_store_next_action",
                    code: other,
                    message: "unknown action code".into(),
                    detail: String::new(),
                })
            }
        };
        Ok((a, pass))
    }

    /// Counts of pass `pass` (1-based).
    pub fn pass_stats(&self, pass: i32) -> Result<PassStats, CapiError> {
        count(|c| c.store += 1);
        let mut s = jointlin_pass_stats {
            pass: 0,
            kind: 0,
            increments_run: 0,
            increments_converged: 0,
            evaluations: 0,
            not_reported: 0,
        };
        // SAFETY: live handle, writable local.
        check("jointlin_store_pass_stats", unsafe {
            jointlin_store_pass_stats(self.0.as_ptr(), pass, &mut s)
        })?;
        Ok(PassStats {
            pass: s.pass,
            kind: s.kind,
            increments_run: s.increments_run,
            increments_converged: s.increments_converged,
        })
    }
}

impl Drop for Store {
    fn drop(&mut self) {
        // SAFETY: created by jointlin_store_new, freed once here.
        unsafe { jointlin_store_free(self.0.as_ptr()) };
    }
}
