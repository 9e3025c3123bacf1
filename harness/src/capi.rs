//! The harness's only door to jointlin: safe wrappers over the `extern "C"` functions of
//! `jointlin::ffi`, called exactly as a C or Fortran host would (raw pointers, status
//! codes). A non-OK status becomes a [`CapiError`] with the library's status message and
//! the thread's last-error detail.
//!
//! Every call is counted per thread ([`counts`]), so tests can show that switched-off
//! effects make no calls.

use std::cell::Cell;
use std::ffi::{c_char, CStr};
use std::ptr::{self, NonNull};

use jointlin::ffi::cubic::{
    jointlin_cubic_force, jointlin_cubic_linearization, jointlin_linearize_cubic,
};
use jointlin::ffi::error::{jointlin_last_error, jointlin_status_message, JOINTLIN_OK};
use jointlin::ffi::linearize::{
    jointlin_contact, jointlin_linearization, jointlin_linearize, jointlin_method,
    JOINTLIN_LAW_JENKINS, JOINTLIN_LAW_MINDLIN, JOINTLIN_METHOD_GAUSS, JOINTLIN_METHOD_GRADED,
    JOINTLIN_METHOD_SIMPSON, JOINTLIN_RULE_MASING, JOINTLIN_RULE_THESIS,
};
use jointlin::ffi::point::{jointlin_point_step, jointlin_step, JOINTLIN_POINT_STATE_LEN};
use jointlin::ffi::screw::jointlin_screw_preload;
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
use jointlin::ffi::uinter::{jointlin_uinter, jointlin_uinter_report};
use thiserror::Error;

use crate::names::{LawName, RuleName, SchemeName};

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

/// Sets the quadrature of this thread's [`linearize`] calls and of the PROPS built by
/// [`props`] afterwards (`None`: the library's default). For fidelity studies
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

fn law_code(l: LawName) -> i32 {
    match l {
        LawName::Mindlin => JOINTLIN_LAW_MINDLIN,
        LawName::Jenkins => JOINTLIN_LAW_JENKINS,
    }
}

fn rule_code(r: RuleName) -> i32 {
    match r {
        RuleName::Thesis => JOINTLIN_RULE_THESIS,
        RuleName::Masing => JOINTLIN_RULE_MASING,
    }
}

/// One point's tangential data for [`linearize`] (stress form: normal "force" = pressure,
/// k_T0 per area; results are then per area too).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    pub law: LawName,
    pub rule: RuleName,
    pub mu: f64,
    /// Normal pressure (or force), positive in compression.
    pub normal: f64,
    pub k_t0: f64,
}

/// `jointlin_linearize` output.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Linearized {
    pub k_star: f64,
    pub d_star: f64,
    pub eta: f64,
    pub energy_per_cycle: f64,
    pub slip_limit: f64,
    pub amplitude_ratio: f64,
    pub regime: i32,
}

/// Preload (force) of a screw tightened to `torque` (force·length) by the library's
/// screw formula (VDI 2230); lengths in one unit.
pub fn screw_preload(
    torque: f64,
    pitch: f64,
    d2: f64,
    mu_thread: f64,
    mu_head: f64,
    d_km: f64,
) -> Result<f64, CapiError> {
    let mut f = 0.0;
    // SAFETY: f is a valid local.
    let code =
        unsafe { jointlin_screw_preload(torque, pitch, d2, mu_thread, mu_head, d_km, &mut f) };
    check("jointlin_screw_preload", code)?;
    Ok(f)
}

/// The C description of a point's tangential law.
fn c_contact(t: &Tangential) -> jointlin_contact {
    jointlin_contact {
        law: law_code(t.law),
        rule: rule_code(t.rule),
        mu: t.mu,
        normal_force: t.normal,
        k_t0: t.k_t0,
    }
}

/// k*, d*, η, energy per cycle, δ*, A/δ*, regime of one point for amplitude A (length)
/// at ω (rad/time), default quadrature.
pub fn linearize(t: &Tangential, amplitude: f64, omega: f64) -> Result<Linearized, CapiError> {
    count(|c| c.linearize += 1);
    let contact = c_contact(t);
    let mut out = jointlin_linearization {
        k_star: 0.0,
        d_star: 0.0,
        eta: 0.0,
        energy_per_cycle: 0.0,
        peak_force: 0.0,
        slip_limit: 0.0,
        amplitude_ratio: 0.0,
        regime: 0,
    };
    let method = QUADRATURE.with(|c| c.get()).map(|q| {
        let (kind, points) = q.code();
        jointlin_method { kind, points }
    });
    let mptr = method
        .as_ref()
        .map_or(ptr::null(), |m| m as *const jointlin_method);
    // SAFETY: contact and out are valid locals; method NULL = default, else a local.
    let code = unsafe { jointlin_linearize(&contact, amplitude, omega, mptr, &mut out) };
    check("jointlin_linearize", code)?;
    Ok(Linearized {
        k_star: out.k_star,
        d_star: out.d_star,
        eta: out.eta,
        energy_per_cycle: out.energy_per_cycle,
        slip_limit: out.slip_limit,
        amplitude_ratio: out.amplitude_ratio,
        regime: out.regime,
    })
}

/// k* (force/length) of the cubic spring F(x) = k·x + α·x³ for the amplitude A (length)
/// by first-order harmonic balance (`jointlin_linearize_cubic`, thesis (3.8)); its d* is 0.
pub fn linearize_cubic(k: f64, alpha: f64, amplitude: f64) -> Result<f64, CapiError> {
    count(|c| c.linearize_cubic += 1);
    let mut out = jointlin_cubic_linearization {
        k_star: 0.0,
        d_star: 0.0,
        energy_per_cycle: 0.0,
    };
    // SAFETY: out is a writable local.
    let code = unsafe { jointlin_linearize_cubic(k, alpha, amplitude, &mut out) };
    check("jointlin_linearize_cubic", code)?;
    Ok(out.k_star)
}

/// Force (force units) and tangent (force/length) of the cubic spring F = k·x + α·x³ at
/// the elongation x, through `jointlin_cubic_force`.
pub fn cubic_force(k: f64, alpha: f64, x: f64) -> Result<(f64, f64), CapiError> {
    let (mut force, mut tangent) = (0.0, 0.0);
    // SAFETY: both are writable locals.
    let code = unsafe { jointlin_cubic_force(k, alpha, x, &mut force, &mut tangent) };
    check("jointlin_cubic_force", code)?;
    Ok((force, tangent))
}

thread_local! {
    static POINT_STEPS: Cell<u64> = const { Cell::new(0) };
}

/// Doubles in the state of one tangential direction of a time-domain point.
pub const POINT_STATE_LEN: usize = JOINTLIN_POINT_STATE_LEN;

/// `jointlin_point_step` output: force (sign of the slip), tangent dF/dslip for continued
/// motion (>= 0), energy dissipated in the increment.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointStep {
    pub force: f64,
    pub tangent: f64,
    pub dissipated: f64,
}

/// Moves one tangential direction of a point from `state` to `slip` (`jointlin_point_step`,
/// the stateful hysteresis of thesis §2.3.3); the new state goes to `state_out` (an
/// all-zero state is a virgin point at slip 0).
pub fn point_step(
    t: &Tangential,
    state: &[f64; POINT_STATE_LEN],
    slip: f64,
    state_out: &mut [f64; POINT_STATE_LEN],
) -> Result<PointStep, CapiError> {
    POINT_STEPS.with(|c| c.set(c.get() + 1));
    let contact = c_contact(t);
    let mut out = jointlin_step::default();
    // SAFETY: contact and out are valid locals; both state arrays hold
    // JOINTLIN_POINT_STATE_LEN doubles.
    let code = unsafe {
        jointlin_point_step(
            &contact,
            state.as_ptr(),
            slip,
            state_out.as_mut_ptr(),
            &mut out,
        )
    };
    check("jointlin_point_step", code)?;
    Ok(PointStep {
        force: out.force,
        tangent: out.tangent,
        dissipated: out.dissipated,
    })
}

/// `jointlin_point_step` calls made on this thread so far.
pub fn point_steps() -> u64 {
    POINT_STEPS.with(|c| c.get())
}

/// Normal law of the PROPS table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NormalProps {
    /// p = k_N h (k_N per area).
    Linear { k_n: f64 },
    /// Hertz with E* and r*.
    Hertz { e_star: f64, r_star: f64 },
}

/// UINTER PROPS (src/ffi/props.rs): law, rule, μ, k_T0 per area, normal law; viscous
/// damping output; quadrature as set by [`set_quadrature`] (default: the library's).
pub fn props(
    law: LawName,
    rule: RuleName,
    mu: f64,
    k_t0: f64,
    normal: NormalProps,
) -> [f64; NPROPS] {
    let (nl, p6, p7) = match normal {
        NormalProps::Linear { k_n } => (0.0, k_n, 0.0),
        NormalProps::Hertz { e_star, r_star } => (1.0, e_star, r_star),
    };
    let (qk, qn) = QUADRATURE
        .with(|c| c.get())
        .map_or((0, 0), Quadrature::code);
    [
        law_code(law) as f64,
        rule_code(rule) as f64,
        mu,
        k_t0,
        nl,
        p6,
        p7,
        0.0,
        0.0,
        0.0,
        f64::from(qk),
        f64::from(qn),
    ]
}

/// Identity and data of one contact point as UINTER sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UinterPoint<'a> {
    /// Interaction name (CINAME).
    pub name: &'a str,
    pub props: &'a [f64; NPROPS],
    pub coords: [f64; 3],
    /// Tributary area (length²).
    pub area: f64,
}

/// What one jointlin_uinter call returned (matrices row-major here).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UinterOut {
    pub stress: [f64; 3],
    /// ∂STRESS/∂RDISP, `[row][col]`.
    pub ddsddr: [[f64; 3]; 3],
    pub dviscous: [[f64; 3]; 3],
    pub closed: bool,
    pub report: jointlin_uinter_report,
}

#[allow(clippy::too_many_arguments)]
fn uinter(
    store: Option<&Store>,
    p: &UinterPoint,
    statev: &mut [f64; NSTATV],
    stress_in: [f64; 3],
    rdisp: [f64; 3],
    drdisp: [f64; 3],
    freq: f64,
    kstep: i32,
    kinc: i32,
    linper: i32,
) -> Result<UinterOut, CapiError> {
    count(|c| {
        if linper == 0 {
            c.uinter_general += 1
        } else {
            c.uinter_linear += 1
        }
    });
    let mut stress = stress_in;
    let mut ddsddr = [0.0; 9];
    let mut dvisc = [0.0; 9];
    let mut dstruct = [0.0; 9];
    let mut sfd = 0.0;
    let mut pnewdt = 1.0;
    let time = [0.0, 0.0];
    let mut lopen = -1i32;
    let mut report = jointlin_uinter_report::default();
    let store_ptr = store.map_or(ptr::null(), |s| s.0.as_ptr().cast_const());
    // SAFETY: every array has the size UINTER expects for NDIR = 3, NSTATV = 57,
    // NPROPS = 12, MCRD = 3; the name bytes are valid for their length.
    let code = unsafe {
        jointlin_uinter(
            store_ptr,
            stress.as_mut_ptr(),
            ddsddr.as_mut_ptr(),
            dvisc.as_mut_ptr(),
            dstruct.as_mut_ptr(),
            statev.as_mut_ptr(),
            &mut sfd,
            &mut pnewdt,
            rdisp.as_ptr(),
            drdisp.as_ptr(),
            time.as_ptr(),
            0.0,
            freq,
            p.name.as_ptr().cast::<c_char>(),
            p.name.len(),
            p.props.as_ptr(),
            p.coords.as_ptr(),
            p.area,
            0,
            3,
            NSTATV as i32,
            NPROPS as i32,
            3,
            kstep,
            kinc,
            linper,
            &mut lopen,
            &mut report,
        )
    };
    check("jointlin_uinter", code)?;
    // Column-major (Fortran) → [row][col].
    let rm = |m: [f64; 9]| std::array::from_fn(|r| std::array::from_fn(|c| m[r + 3 * c]));
    Ok(UinterOut {
        stress,
        ddsddr: rm(ddsddr),
        dviscous: rm(dvisc),
        closed: lopen == 1,
        report,
    })
}

/// UINTER in a general (static) step, LINPER = 0: `rdisp` = [overclosure, slip₁, slip₂],
/// `drdisp` their increments in this increment; `statev` holds the start-of-increment
/// state on entry and the updated one on return.
pub fn uinter_general(
    p: &UinterPoint,
    statev: &mut [f64; NSTATV],
    rdisp: [f64; 3],
    drdisp: [f64; 3],
    kstep: i32,
    kinc: i32,
) -> Result<UinterOut, CapiError> {
    uinter(
        None, p, statev, [0.0; 3], rdisp, drdisp, 0.0, kstep, kinc, 0,
    )
}

/// UINTER in the steady-state step, LINPER = 1, at `freq` (cycles/time): k* in DDSDDR,
/// d* in DVISCOUS for the store's amplitude estimate of increment `kinc`.
pub fn uinter_linear(
    store: &Store,
    p: &UinterPoint,
    statev: &mut [f64; NSTATV],
    freq: f64,
    kstep: i32,
    kinc: i32,
) -> Result<UinterOut, CapiError> {
    uinter(
        Some(store),
        p,
        statev,
        [0.0; 3],
        [0.0; 3],
        [0.0; 3],
        freq,
        kstep,
        kinc,
        1,
    )
}

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
pub struct Store(NonNull<jointlin_store>);

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_of_the_linearization_through_the_c_api() {
        // Block of Appendix C: μ = 0.3, F_N = 2 N, k_T0 = 1282.7 N/mm.
        let t = Tangential {
            law: LawName::Mindlin,
            rule: RuleName::Thesis,
            mu: 0.3,
            normal: 2.0,
            k_t0: 1282.7,
        };
        let small = linearize(&t, 1e-12, 1.3).unwrap();
        // A → 0: k* → k_T0 (relative deviation ~A/δ*), d* → 0.
        assert!((small.k_star / 1282.7 - 1.0).abs() < 1e-6);
        // δ* = 1.5 μ F_N / k_T0 (2.46).
        approx::assert_relative_eq!(small.slip_limit, 1.5 * 0.6 / 1282.7, max_relative = 1e-12);
        let before = counts().linearize;
        let bad = linearize(&t, -1.0, 1.3).unwrap_err();
        assert_eq!(counts().linearize, before + 1);
        assert!(bad.detail.contains("amplitude"), "{bad}");
    }

    #[test]
    fn quadrature_setting_reaches_the_library() {
        let t = Tangential {
            law: LawName::Mindlin,
            rule: RuleName::Thesis,
            mu: 0.3,
            normal: 2.0,
            k_t0: 1282.7,
        };
        // A/δ* = 0.8 (microslip): Simpson with 16 intervals is off by 4e-6 here (README
        // table: worst 2.5e-2 over A/δ*), the default by < 1e-12, so they must differ.
        let a = 0.8 * 1.5 * 0.6 / 1282.7;
        let d = linearize(&t, a, 1.3).unwrap();
        assert_eq!(set_quadrature(Some(Quadrature::Simpson(16))), None);
        let s = linearize(&t, a, 1.3).unwrap();
        let pr = props(
            LawName::Mindlin,
            RuleName::Thesis,
            0.3,
            1.0,
            NormalProps::Linear { k_n: 1.0 },
        );
        assert_eq!(set_quadrature(None), Some(Quadrature::Simpson(16)));
        assert_eq!((pr[10], pr[11]), (1.0, 16.0));
        let rel = (s.k_star / d.k_star - 1.0).abs();
        assert!(rel > 1e-7 && rel < 5e-2, "{rel}");
        assert_eq!(linearize(&t, a, 1.3).unwrap(), d);
    }

    #[test]
    fn uinter_general_linear_normal_law() {
        let pr = props(
            LawName::Mindlin,
            RuleName::Thesis,
            0.3,
            100.0,
            NormalProps::Linear { k_n: 1e4 },
        );
        let p = UinterPoint {
            name: "joint",
            props: &pr,
            coords: [0.0; 3],
            area: 2.0,
        };
        let mut sv = [0.0; NSTATV];
        let out = uinter_general(&p, &mut sv, [1e-3, 0.0, 0.0], [1e-3, 0.0, 0.0], 1, 1).unwrap();
        // p = k_N h, dp/dh = k_N, stick tangent k_T0.
        assert_eq!(out.stress[0], 10.0);
        assert_eq!(out.ddsddr[0][0], 1e4);
        assert_eq!(out.ddsddr[1][1], 100.0);
        assert!(out.closed);
        let open = uinter_general(&p, &mut sv, [-1e-3, 0.0, 0.0], [-2e-3, 0.0, 0.0], 1, 2).unwrap();
        assert!(!open.closed && open.stress == [0.0; 3]);
    }
}
