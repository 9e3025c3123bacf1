//! UINTER through the C API: the PROPS table (fortran-shim/README.md), one contact
//! point's general or steady-state (LINPER = 1) call.

use std::ffi::c_char;
use std::ptr;

use jointlin::ffi::uinter::{jointlin_uinter, jointlin_uinter_report};

use super::store::Store;
use super::{check, count, CapiError, NPROPS, NSTATV};

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
