//! `jointlin_uinter`: Abaqus's UINTER contact law for one contact point (model.md §7):
//! Hertz or linear normal law, Mindlin/Jenkins hysteresis per tangential direction in a
//! general step (LINPER = 0), and the linearized k*, d* at the store's amplitude estimate in
//! a steady-state step (LINPER = 1). PROPS and STATEV layouts: see [`super::props`].

use std::ffi::c_char;

use super::error::{
    boundary, FfiError, FfiResult, JOINTLIN_ERR_NULL, JOINTLIN_ERR_OUT_OF_RANGE,
    JOINTLIN_ERR_OVERFLOW, JOINTLIN_ERR_SEQUENCE, JOINTLIN_ERR_SIZE,
};
use super::linearize::{regime_code, JOINTLIN_REGIME_OPEN};
use super::props::{slot, Damping, Props, JOINTLIN_UINTER_MIN_NPROPS, JOINTLIN_UINTER_MIN_NSTATV};
use super::store::{jointlin_store, key_from_raw, store_ref};
use super::{check_ptr, finite, load, load_finite, put, put_all};
use crate::hysteresis::{PointState, STATE_LEN};
use crate::linearize::{linearize, Contact};
use crate::store::props_checksum;

/// What one LINPER = 1 call of jointlin_uinter computed (all per unit area). Directions are
/// the tangential directions 1, 2 (RDISP(2), RDISP(3)); unused entries are 0.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct jointlin_uinter_report {
    /// Store point id queried (0 when the store was not queried: LINPER = 0, open point,
    /// or NDIR = 1).
    pub point: i64,
    /// 1 when the point is closed (p0 > 0), else 0.
    pub closed: i32,
    /// Tangential directions linearized (NDIR - 1, or 0 when open).
    pub directions: i32,
    /// Base pressure p0 used (positive in compression).
    pub pressure: f64,
    /// Amplitude estimates used (length).
    pub amplitude: [f64; 2],
    /// Equivalent stiffness k* per area (3.8).
    pub k_star: [f64; 2],
    /// Equivalent viscous damping d* per area (3.14).
    pub d_star: [f64; 2],
    /// Loss factor eta.
    pub eta: [f64; 2],
    /// JOINTLIN_REGIME_* per direction.
    pub regime: [i32; 2],
    /// Energy dissipated per cycle per area, both directions.
    pub energy_per_cycle: f64,
    /// Dissipated power per area = energy_per_cycle x FREQR.
    pub dissipated_power: f64,
}

/// Everything a call writes, assembled before any output is touched.
struct Outputs {
    stress: [f64; 3],
    ddsddr: [f64; 9],
    dviscous: [f64; 9],
    dstructural: [f64; 9],
    statev: [f64; slot::LEN],
    sfd: f64,
    lopenclose: i32,
    report: jointlin_uinter_report,
}

/// Relative pressure step of the one-sided difference for dτ/dp in DDSDDR(i,1): √ε-sized,
/// so truncation (∝ step) and rounding (∝ ε/step) errors are both ~1e-8 relative.
const PRESSURE_STEP: f64 = 1.5e-8;

/// A quantity derived from finite inputs that is not finite overflowed: a named error.
fn derived(value: f64, what: &str) -> FfiResult<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(err(
            JOINTLIN_ERR_OVERFLOW,
            format!("{what} is not representable"),
        ))
    }
}

fn err(code: i32, msg: String) -> FfiError {
    FfiError::new(code, msg)
}

/// Abaqus UINTER for one contact point, with Abaqus's conventions: STRESS(1) is the contact
/// pressure, positive in compression; RDISP(1) the overclosure, positive = penetration;
/// RDISP(2:3) the accumulated tangential slips and STRESS(2:3) the shear stresses (same
/// sign as the slip: positive stiffness); DDSDDR = dSTRESS/dRDISP, DVISCOUS and DSTRUCTURAL
/// are NDIR x NDIR, column-major (Fortran). All stresses and stiffnesses are per unit area:
/// the tangential friction limit is mu * p and PROPS(4) is k_T0 per area. FREQR is in
/// cycles per time unit (omega = 2 pi FREQR). PROPS and STATEV: see the tables in
/// src/ffi/props.rs (and the JOINTLIN_UINTER_MIN_* constants).
///
/// LINPER = 0 (general step, time domain): p = k_N h (linear) or F_N(h)/AREA (Hertz,
/// 2.34); each tangential direction is an independent hysteresis point (Fig. 4.26) stepped
/// to RDISP(i); a direction that was never stepped starts virgin at its slip at the start
/// of the increment, RDISP(i) - DRDISP(i). STRESS(i) = tau, DDSDDR(i,i) = tangent,
/// DDSDDR(1,1) = dp/dh, DDSDDR(i,1) = dtau/dp dp/dh at fixed slip history (one-sided
/// difference in p; mu dp/dh sign(tau) while sliding); DDSDDR(1,i) = 0. A change of pressure
/// re-derives the stored hysteresis forces from the slips, so tau is continuous in p. SFD = dissipation per area of this increment
/// (also added to STATEV(5)). Open (h <= 0): all stresses and stiffnesses 0, LOPENCLOSE = 0,
/// the tangential histories are reset. Closed: LOPENCLOSE = 1. STATEV(2:4) record p0, h0 and
/// the closed flag. DVISCOUS and DSTRUCTURAL are set to 0. The friction limit follows the
/// current pressure.
///
/// LINPER = 1 (steady-state step, linearized): the base pressure p0 is STATEV(2) when the
/// point closed in the last general step (STATEV(4) = 1), else STRESS(1) on entry (for hosts
/// that never call LINPER = 0). p0 <= 0: open, all matrices 0, store not queried. Else the
/// point is found in the store (STATEV(1) if it holds the id of this point's key, else
/// registered by (CINAME, NODE, COORDS) and written to STATEV(1)); the amplitude estimate
/// of each tangential direction for increment KINC is linearized at omega = 2 pi FREQR:
/// DDSDDR(i,i) = k*, and DVISCOUS(i,i) = d* (PROPS(10) = 0) or DSTRUCTURAL(i,i) = omega d*
/// = eta k* (PROPS(10) = 1), never both; DDSDDR(1,1) = dp/dh at p0; STRESS, LOPENCLOSE, SFD
/// (set 0) and the hysteresis state are not changed; STATEV(52:57) receive k*, d*, the
/// energy per cycle and the dissipated power per area. `report` (may be NULL) receives the
/// same numbers. The store must not be NULL when LINPER = 1 and NDIR >= 2; it may be NULL
/// otherwise. If the store iterates one step (sweep_step), KSTEP must be that step.
///
/// PNEWDT is checked but not changed. TIME, DTIME are checked but not used.
///
/// Threads: any number of jointlin_uinter calls may run at once on one store, each with its
/// own arrays (Abaqus's UINTER threads); at LINPER = 1 not overlapping the LOP 1 or LOP 2
/// of their increment (see jointlin_store).
///
/// Errors (no output written): JOINTLIN_ERR_NULL (any pointer but `store`/`report` as
/// above), JOINTLIN_ERR_NON_FINITE (NaN/Inf in STRESS, RDISP, DRDISP, TIME, DTIME, FREQR,
/// PROPS(1:min(NPROPS,12)), COORDS, AREA, PNEWDT, STATEV(1:57)), JOINTLIN_ERR_OUT_OF_RANGE
/// (NDIR not in 1..3, MCRD not in 1..3, AREA <= 0, LINPER not 0/1, FREQR <= 0 at LINPER = 1,
/// CINAME longer than 256, a corrupt hysteresis state), JOINTLIN_ERR_SIZE (NSTATV < 57,
/// NPROPS < 7), JOINTLIN_ERR_PROPS (see the PROPS table), JOINTLIN_ERR_OVERFLOW (a result
/// would not be finite, e.g. 2 pi FREQR for FREQR = 1e308; messages print numbers in
/// shortest round-trip form, 1e300 rather than its 301 digits), and the store's errors at
/// LINPER = 1 (JOINTLIN_ERR_SEQUENCE outside an open increment; JOINTLIN_ERR_IO after a
/// restore from a restart file that does not list this point, or lists it with other
/// PROPS; ...).
///
/// # Safety
/// Array arguments must hold the sizes Abaqus gives them: stress, rdisp, drdisp: NDIR;
/// ddsddr, dviscous, dstructural: NDIR*NDIR; statev: NSTATV; props: NPROPS; coords: MCRD;
/// time: 2; ciname: ciname_len bytes (not NUL-terminated, may be blank-padded); scalars
/// sfd, pnewdt, lopenclose: one value; report: NULL or writable; store: NULL or live.
#[no_mangle]
pub unsafe extern "C" fn jointlin_uinter(
    store: *const jointlin_store,
    stress: *mut f64,
    ddsddr: *mut f64,
    dviscous: *mut f64,
    dstructural: *mut f64,
    statev: *mut f64,
    sfd: *mut f64,
    pnewdt: *mut f64,
    rdisp: *const f64,
    drdisp: *const f64,
    time: *const f64,
    dtime: f64,
    freqr: f64,
    ciname: *const c_char,
    ciname_len: usize,
    props: *const f64,
    coords: *const f64,
    area: f64,
    node: i32,
    ndir: i32,
    nstatv: i32,
    nprops: i32,
    mcrd: i32,
    kstep: i32,
    kinc: i32,
    linper: i32,
    lopenclose: *mut i32,
    report: *mut jointlin_uinter_report,
) -> i32 {
    boundary("jointlin_uinter", || {
        if !(1..=3).contains(&ndir) {
            return Err(err(
                JOINTLIN_ERR_OUT_OF_RANGE,
                format!("NDIR {ndir} not in 1..=3"),
            ));
        }
        if nstatv < JOINTLIN_UINTER_MIN_NSTATV {
            return Err(err(JOINTLIN_ERR_SIZE, format!("NSTATV {nstatv} < 57")));
        }
        if nprops < JOINTLIN_UINTER_MIN_NPROPS {
            return Err(err(JOINTLIN_ERR_SIZE, format!("NPROPS {nprops} < 7")));
        }
        if !(0..=1).contains(&linper) {
            return Err(err(
                JOINTLIN_ERR_OUT_OF_RANGE,
                format!("LINPER {linper} not 0 or 1"),
            ));
        }
        if !(1..=3).contains(&mcrd) {
            return Err(err(
                JOINTLIN_ERR_OUT_OF_RANGE,
                format!("MCRD {mcrd} not in 1..=3"),
            ));
        }
        let n = ndir as usize;
        // SAFETY (all loads): pointers checked by the helpers, sizes by the contract above.
        let stress_in: [f64; 3] = unsafe { load_finite(stress, n, "STRESS") }?;
        let rdisp_in: [f64; 3] = unsafe { load_finite(rdisp, n, "RDISP") }?;
        let drdisp_in: [f64; 3] = unsafe { load_finite(drdisp, n, "DRDISP") }?;
        let statev_in: [f64; slot::LEN] = unsafe { load_finite(statev, slot::LEN, "STATEV") }?;
        let props_in: [f64; 12] =
            unsafe { load_finite(props, (nprops as usize).min(12), "PROPS") }?;
        let _: [f64; 2] = unsafe { load_finite(time, 2, "TIME") }?;
        let _: [f64; 3] = unsafe { load_finite(coords, mcrd as usize, "COORDS") }?;
        let _: [f64; 1] = unsafe { load_finite(pnewdt, 1, "PNEWDT") }?;
        let lopen_in = unsafe { load(lopenclose.cast_const(), "LOPENCLOSE") }?;
        check_ptr(ciname, "CINAME")?;
        for (p, what) in [
            (ddsddr, "DDSDDR"),
            (dviscous, "DVISCOUS"),
            (dstructural, "DSTRUCTURAL"),
            (sfd, "SFD"),
        ] {
            check_ptr(p, what)?;
        }
        if !report.is_null() {
            check_ptr(report, "report")?;
        }
        finite(dtime, "DTIME")?;
        finite(freqr, "FREQR")?;
        finite(area, "AREA")?;
        if area <= 0.0 {
            return Err(err(
                JOINTLIN_ERR_OUT_OF_RANGE,
                format!("AREA {area:?} must be > 0"),
            ));
        }
        let props_parsed = Props::parse(&props_in, area)?;
        let mut out = Outputs {
            stress: stress_in,
            ddsddr: [0.0; 9],
            dviscous: [0.0; 9],
            dstructural: [0.0; 9],
            statev: statev_in,
            sfd: 0.0,
            lopenclose: lopen_in,
            report: jointlin_uinter_report::default(),
        };
        if linper == 0 {
            general_step(&props_parsed, n, &rdisp_in, &drdisp_in, &mut out)?;
        } else {
            if freqr <= 0.0 {
                return Err(err(
                    JOINTLIN_ERR_OUT_OF_RANGE,
                    format!("FREQR {freqr:?} must be > 0 at LINPER = 1"),
                ));
            }
            let point = |dirs: usize| -> FfiResult<([f64; 2], i64)> {
                if store.is_null() {
                    return Err(err(JOINTLIN_ERR_NULL, "store is NULL at LINPER = 1".into()));
                }
                // SAFETY: non-NULL store is live by contract; name and coords by contract.
                let s = unsafe { store_ref(store) }?;
                let sweep = s.config().sweep_step;
                if sweep != 0 && kstep != sweep {
                    return Err(err(
                        JOINTLIN_ERR_SEQUENCE,
                        format!("LINPER = 1 in step {kstep}, but the store iterates step {sweep}"),
                    ));
                }
                let key = unsafe { key_from_raw(ciname, ciname_len, node, coords, mcrd) }?;
                let hint = statev_in[slot::ID];
                let hint = if hint.fract() == 0.0 && (1.0..9.0e15).contains(&hint) {
                    hint as i64
                } else {
                    0
                };
                let id = s.resolve(hint, key)?;
                s.check_props(id, props_checksum(&props_in[..(nprops as usize).min(12)]))?;
                Ok((s.estimate(id, kinc, dirs)?, id))
            };
            steady_state(&props_parsed, n, freqr, point, &mut out)?;
        }
        let sfd_out = [out.sfd];
        let mut all = out
            .stress
            .iter()
            .chain(&out.ddsddr)
            .chain(&out.dviscous)
            .chain(&out.dstructural)
            .chain(&out.statev)
            .chain(&sfd_out);
        if all.any(|v| !v.is_finite()) {
            return Err(err(JOINTLIN_ERR_OVERFLOW, "a result is not finite".into()));
        }
        // SAFETY: every pointer was checked non-NULL and aligned; sizes by contract. Each
        // write copies from a local, so aliasing outputs cannot cause undefined behaviour.
        unsafe {
            put_all(stress, &out.stress[..n]);
            put_all(ddsddr, &out.ddsddr[..n * n]);
            put_all(dviscous, &out.dviscous[..n * n]);
            put_all(dstructural, &out.dstructural[..n * n]);
            put_all(statev, &out.statev);
            put(sfd, out.sfd);
            put(lopenclose, out.lopenclose);
            if !report.is_null() {
                put(report, out.report);
            }
        }
        Ok(())
    })
}

/// LINPER = 0: normal law, then one hysteresis point per tangential direction (Fig. 4.26).
fn general_step(
    props: &Props,
    n: usize,
    rdisp: &[f64; 3],
    drdisp: &[f64; 3],
    out: &mut Outputs,
) -> FfiResult<()> {
    let h = rdisp[0];
    let normal = props.normal.response(h); // (2.34) or the linear penalty
    out.statev[slot::H0] = h;
    if !normal.closed || normal.pressure <= 0.0 {
        out.stress = [0.0; 3];
        out.statev[slot::P0] = 0.0;
        out.statev[slot::CLOSED] = 0.0;
        out.statev[slot::hysteresis(0)..slot::K_STAR].fill(0.0); // histories reset
        out.lopenclose = 0;
        return Ok(());
    }
    let (p, kn) = (normal.pressure, normal.stiffness);
    if !(p.is_finite() && kn.is_finite()) {
        return Err(err(
            JOINTLIN_ERR_OVERFLOW,
            format!("contact pressure or dp/dh overflows at overclosure {h:e}"),
        ));
    }
    out.stress[0] = p;
    out.ddsddr[0] = kn;
    let contact = Contact {
        law: props.law,
        rule: props.rule,
        mu: props.mu,
        normal_force: p, // stress form: friction limit mu p
        k_t0: derived(props.k_t0(p), "k_T0 from Hertz-Mindlin geometry (2.38)")?,
    };
    let point = contact.point()?;
    // The same point at a slightly higher pressure, for dτ/dp at fixed slip history.
    let p_plus = p * (1.0 + PRESSURE_STEP);
    let point_plus = Contact {
        normal_force: p_plus,
        k_t0: derived(
            props.k_t0(p_plus),
            "k_T0 from Hertz-Mindlin geometry (2.38)",
        )?,
        ..contact
    }
    .point()?;
    for i in 1..n {
        let range = slot::hysteresis(i - 1)..slot::hysteresis(i - 1) + STATE_LEN;
        let mut slots = [0.0; STATE_LEN];
        slots.copy_from_slice(&out.statev[range.clone()]);
        let (tau, tangent, dtau_dp) = match (&point, &point_plus) {
            (Some(pt), Some(pt_plus)) => {
                let origin = rdisp[i] - drdisp[i];
                let state = PointState::read(&slots, pt.rule, origin)?;
                let (next, r) = pt.step(&state, rdisp[i])?;
                let (_, r_plus) = pt_plus.step(&state, rdisp[i])?;
                next.write(&mut slots);
                out.sfd += r.dissipated;
                (r.force, r.tangent, (r_plus.force - r.force) / (p_plus - p))
            }
            _ => {
                slots = [0.0; STATE_LEN];
                (0.0, 0.0, 0.0)
            }
        };
        out.statev[range].copy_from_slice(&slots);
        out.stress[i] = tau;
        out.ddsddr[i + i * n] = tangent;
        // dτ/dh = dτ/dp · dp/dh: μ sign(τ) dp/dh while sliding (2.39), the load dependence
        // of the Mindlin branch (2.49) otherwise.
        out.ddsddr[i] = dtau_dp * kn;
    }
    out.statev[slot::DISSIPATION] += out.sfd;
    out.statev[slot::P0] = p;
    out.statev[slot::CLOSED] = 1.0;
    out.lopenclose = 1;
    Ok(())
}

/// LINPER = 1: k*, d* per tangential direction at the store's amplitude estimate.
fn steady_state(
    props: &Props,
    n: usize,
    freqr: f64,
    point: impl FnOnce(usize) -> FfiResult<([f64; 2], i64)>,
    out: &mut Outputs,
) -> FfiResult<()> {
    let p0 = if out.statev[slot::CLOSED] == 1.0 {
        out.statev[slot::P0]
    } else {
        out.stress[0]
    };
    out.sfd = 0.0;
    out.statev[slot::K_STAR..slot::LEN].fill(0.0);
    if p0 <= 0.0 {
        out.report.regime = [JOINTLIN_REGIME_OPEN; 2];
        return Ok(());
    }
    out.ddsddr[0] = props.normal_stiffness_at(p0); // (2.35)
    out.report.closed = 1;
    out.report.pressure = p0;
    if n == 1 {
        return Ok(());
    }
    let dirs = n - 1;
    let (amp, id) = point(dirs)?;
    // FREQR = 1e308 is finite, 2π FREQR is not: an overflow, not a non-finite input.
    let omega = derived(
        2.0 * std::f64::consts::PI * freqr,
        "angular frequency 2 pi FREQR",
    )?;
    let contact = Contact {
        law: props.law,
        rule: props.rule,
        mu: props.mu,
        normal_force: p0,
        k_t0: derived(props.k_t0(p0), "k_T0 from Hertz-Mindlin geometry (2.38)")?,
    };
    let mut energy = 0.0;
    for (d, &a) in amp.iter().enumerate().take(dirs) {
        let i = d + 1;
        let l = linearize(&contact, a, omega, props.method)?; // (3.8), (3.14)
        out.ddsddr[i + i * n] = l.k_star;
        match props.damping {
            Damping::Viscous => out.dviscous[i + i * n] = l.d_star,
            Damping::Structural => out.dstructural[i + i * n] = omega * l.d_star, // = eta k*
        }
        energy += l.energy_per_cycle;
        out.statev[slot::K_STAR + d] = l.k_star;
        out.statev[slot::D_STAR + d] = l.d_star;
        let r = &mut out.report;
        r.amplitude[d] = a;
        r.k_star[d] = l.k_star;
        r.d_star[d] = l.d_star;
        r.eta[d] = l.eta;
        r.regime[d] = regime_code(l.regime);
    }
    let power = derived(
        energy * freqr,
        "dissipated power (energy per cycle x FREQR)",
    )?;
    out.statev[slot::ID] = id as f64;
    out.statev[slot::ENERGY] = energy;
    out.statev[slot::POWER] = power; // energy per cycle x cycles per time
    out.report.point = id;
    out.report.directions = dirs as i32;
    out.report.energy_per_cycle = energy;
    out.report.dissipated_power = power;
    Ok(())
}
