//! `jointlin_point3d_step` and `jointlin_linearize3d`: the contact point in three directions
//! (unilateral normal law, coupled circular slip limit in the tangent plane;
//! docs/contact3d.md) for hosts that integrate in time or sweep in frequency themselves.

use super::error::{boundary, FfiError, FfiResult, JOINTLIN_ERR_OUT_OF_RANGE};
use super::linearize::{regime_code, JOINTLIN_LAW_JENKINS, JOINTLIN_LAW_MINDLIN};
use super::{check_ptr, finite, load, load_finite, put, put_all};
use crate::iterate::Complex64;
use crate::law::hertz::{Hertz, NormalLaw};
use crate::point3d::describing::{describe, Method};
use crate::point3d::phasors::describe_phasors;
use crate::point3d::{Contact3d, State3d, Tangential3d, DEFAULT_CELLS, MAX_CELLS, STATE3D_LEN};

/// Normal law code: linear penalty N = k_N h for h > 0 (k_N in force/length).
pub const JOINTLIN_NORMAL_LINEAR: i32 = 0;
/// Normal law code: Hertz N = (4/3) E* sqrt(r*) h^(3/2) for h > 0 (2.34).
pub const JOINTLIN_NORMAL_HERTZ: i32 = 1;
/// Largest number of Jenkins cells of a Mindlin–Masing point.
pub const JOINTLIN_POINT3D_MAX_CELLS: i32 = 128;
/// Cells used by a Mindlin–Masing point when `cells` is 0.
pub const JOINTLIN_POINT3D_DEFAULT_CELLS: i32 = 32;
/// Number of doubles in the state of a three-direction point: slot 0 the cell count, 1–2
/// the tangential displacement of the last step, 3 its overclosure, 4 the energy dissipated
/// since the virgin state, then two slider coordinates per cell.
pub const JOINTLIN_POINT3D_STATE_LEN: usize = 261;
const _: () = assert!(JOINTLIN_POINT3D_STATE_LEN == STATE3D_LEN);
const _: () = assert!(JOINTLIN_POINT3D_MAX_CELLS as usize == MAX_CELLS);
const _: () = assert!(JOINTLIN_POINT3D_DEFAULT_CELLS as usize == DEFAULT_CELLS);

/// A contact point in three directions (force form: forces, force/length).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct jointlin_contact3d {
    /// JOINTLIN_LAW_JENKINS (one cell: k_t0 and mu N) or JOINTLIN_LAW_MINDLIN (Mindlin's
    /// curve and Masing's rule by parallel Jenkins cells).
    pub law: i32,
    /// Cells of a Mindlin point, 1..JOINTLIN_POINT3D_MAX_CELLS, 0 = default; 0 or 1 for
    /// Jenkins.
    pub cells: i32,
    /// Friction coefficient mu >= 0.
    pub mu: f64,
    /// Full-stick tangential stiffness k_T0 > 0 (force/length), both directions.
    pub k_t0: f64,
    /// JOINTLIN_NORMAL_LINEAR or JOINTLIN_NORMAL_HERTZ.
    pub normal_law: i32,
    /// k_N > 0 (force/length) for the linear law, E* > 0 (force/length^2) for Hertz.
    pub normal_stiffness: f64,
    /// r* > 0 (length) for Hertz (2.31); ignored (any finite value) for the linear law.
    pub r_star: f64,
}

/// Result of one step of a three-direction point.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct jointlin_step3d {
    /// (t1, t2, N): tangential forces with the sign of the displacement (positive stiffness
    /// convention) and the normal force (>= 0, compression).
    pub force: [f64; 3],
    /// d force / d (u1, u2, h) for continued motion, row-major (rows t1, t2, N).
    pub stiffness: [f64; 9],
    /// Energy dissipated during the step (>= 0, force x length).
    pub dissipated: f64,
    /// JOINTLIN_REGIME_* of the step: open (N = 0 or mu = 0), stick (no cell slipped),
    /// microslip (some cells slipped), sliding (all cells slipped).
    pub regime: i32,
}

/// Describing function of a three-direction point on an elliptic path.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct jointlin_linearization3d {
    /// Equivalent stiffness per tangential direction (force/length).
    pub k_star: [f64; 2],
    /// Equivalent viscous damping per tangential direction, energy of the direction per
    /// cycle / (pi omega A^2) (3.14).
    pub d_star: [f64; 2],
    /// Energy dissipated per cycle by the point (force x length).
    pub energy_per_cycle: f64,
    /// JOINTLIN_REGIME_* code.
    pub regime: i32,
}

/// Describing function of a three-direction point for a complex tangential amplitude:
/// the first harmonic of the tangential force is t = (K* + i omega D*) u.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct jointlin_linearization3d_matrix {
    /// K*, symmetric 2 x 2, row-major (force/length).
    pub k_star: [f64; 4],
    /// D*, symmetric 2 x 2, row-major (force x time/length).
    pub d_star: [f64; 4],
    /// Semi-axes A1 >= A2 >= 0 of the elliptic path (length).
    pub semi_axes: [f64; 2],
    /// Angle of the major axis from tangential direction 1 (rad, -pi/2 < angle <= pi/2).
    pub angle: f64,
    /// Energy dissipated per cycle by the point (force x length).
    pub energy_per_cycle: f64,
    /// JOINTLIN_REGIME_* code.
    pub regime: i32,
}

/// Method code: the cells' harmonics by closed forms or integration over the cycle (the
/// reference; 0.1-0.5 s per 32-cell point).
pub const JOINTLIN_DESCRIBE_INTEGRATED: i32 = 0;
/// Method code: the cells' harmonics interpolated from the unit cell's table
/// (microseconds per point; each cell's force harmonics within 2e-3 of its limit force).
pub const JOINTLIN_DESCRIBE_TABULATED: i32 = 1;

impl jointlin_contact3d {
    fn to_core(self) -> FfiResult<Contact3d> {
        let tangential = match (self.law, self.cells) {
            (JOINTLIN_LAW_JENKINS, 0 | 1) => Tangential3d::Jenkins,
            (JOINTLIN_LAW_MINDLIN, 0) => Tangential3d::MindlinMasing {
                cells: DEFAULT_CELLS,
            },
            (JOINTLIN_LAW_MINDLIN, 1..=JOINTLIN_POINT3D_MAX_CELLS) => Tangential3d::MindlinMasing {
                cells: self.cells as usize,
            },
            (law, cells) => {
                return Err(FfiError::new(
                    JOINTLIN_ERR_OUT_OF_RANGE,
                    format!("contact3d law {law} with cells {cells}"),
                ))
            }
        };
        let stiffness = finite(self.normal_stiffness, "contact3d normal_stiffness")?;
        let r_star = finite(self.r_star, "contact3d r_star")?;
        let normal = match self.normal_law {
            JOINTLIN_NORMAL_LINEAR => NormalLaw::Linear {
                stiffness_per_area: stiffness,
            },
            JOINTLIN_NORMAL_HERTZ => NormalLaw::Hertz {
                hertz: Hertz::new(r_star, stiffness)?,
                area: 1.0,
            },
            other => {
                return Err(FfiError::new(
                    JOINTLIN_ERR_OUT_OF_RANGE,
                    format!("unknown contact3d normal_law code {other}"),
                ))
            }
        };
        let c = Contact3d {
            tangential,
            mu: finite(self.mu, "contact3d mu")?,
            k_t0: finite(self.k_t0, "contact3d k_t0")?,
            normal,
        };
        c.validate()?;
        Ok(c)
    }
}

/// Moves a three-direction contact point from `state` to the displacement `disp`: the two
/// tangential relative displacements u1, u2 (length) and the overclosure h (length;
/// penetration when positive, open when h <= 0). Writes the new state to `state_out` and
/// the forces, stiffness, dissipated energy and regime to `out`. Both state arrays hold
/// JOINTLIN_POINT3D_STATE_LEN doubles; an all-zero state is a virgin point at the
/// displacement 0. `state_out` may equal `state`. Pure (no hidden state): trial steps may
/// be evaluated and only accepted states kept.
///
/// The tangential path between two calls is taken as the straight segment; the friction
/// limit of each cell is its share of mu N(h) at the new displacement. An open contact
/// carries no force; the tangential elastic energy it held is counted as dissipated.
///
/// No pointer may be NULL. Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_NON_FINITE (NaN/Inf in
/// the contact, the state or `disp`), JOINTLIN_ERR_OUT_OF_RANGE (unknown codes, mu < 0,
/// k_t0 <= 0, normal constants <= 0, a cell count out of range, a state written for
/// another cell count or corrupt), JOINTLIN_ERR_OVERFLOW (a displacement so large that the
/// forces are not representable). Outputs are written only on JOINTLIN_OK.
///
/// # Safety
/// `contact` must point to a valid jointlin_contact3d, `disp` to 3 doubles, `state` and
/// `state_out` to JOINTLIN_POINT3D_STATE_LEN doubles each, `out` to a writable
/// jointlin_step3d.
#[no_mangle]
pub unsafe extern "C" fn jointlin_point3d_step(
    contact: *const jointlin_contact3d,
    state: *const f64,
    disp: *const f64,
    state_out: *mut f64,
    out: *mut jointlin_step3d,
) -> i32 {
    boundary("jointlin_point3d_step", || {
        // SAFETY: pointers checked by `load`, `load_finite` and `check_ptr`; sizes by contract.
        let c = unsafe { load(contact, "contact") }?.to_core()?;
        let slots: [f64; STATE3D_LEN] = unsafe { load_finite(state, STATE3D_LEN, "state") }?;
        let d: [f64; 3] = unsafe { load_finite(disp, 3, "disp") }?;
        check_ptr(state_out, "state_out")?;
        check_ptr(out, "out")?;
        let cells = c.cell_count();
        let st = State3d::read(&slots, cells)?;
        let (next, r) = c.step(&st, d)?;
        let mut buf = [0.0; STATE3D_LEN];
        next.write(cells, &mut buf);
        let mut stiffness = [0.0; 9];
        for (i, row) in r.stiffness.iter().enumerate() {
            stiffness[3 * i..3 * i + 3].copy_from_slice(row);
        }
        let step = jointlin_step3d {
            force: r.force,
            stiffness,
            dissipated: r.dissipated,
            regime: regime_code(r.regime),
        };
        // SAFETY: both checked non-NULL and aligned; sizes by contract.
        unsafe {
            put_all(state_out, &buf);
            put(out, step);
        }
        Ok(())
    })
}

/// Describing function of a three-direction point at the constant normal force
/// `normal_force` (force; <= 0 open: all zeros, JOINTLIN_REGIME_OPEN) on the elliptic path
/// u = (amplitude_1 cos(omega t), amplitude_2 sin(omega t)) in the point's principal axes,
/// from a virgin start: per direction k* (in-phase first harmonic over the amplitude,
/// (3.8)) and d* (the direction's energy per cycle over pi omega A^2, (3.14)), and the
/// energy per cycle. The normal law is not used. A direction with zero amplitude gets
/// k* = d* = 0 (nothing to balance); both zero give k* = k_t0 (stick). Meaningful only
/// while the normal force stays constant and positive over the cycle (docs/contact3d.md).
///
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_OUT_OF_RANGE
/// (amplitudes < 0, omega <= 0, invalid contact), JOINTLIN_ERR_OVERFLOW (d* not
/// representable). `*out` is written only on JOINTLIN_OK.
///
/// # Safety
/// `contact` must point to a valid jointlin_contact3d and `out` to a writable
/// jointlin_linearization3d.
#[no_mangle]
pub unsafe extern "C" fn jointlin_linearize3d(
    contact: *const jointlin_contact3d,
    normal_force: f64,
    amplitude_1: f64,
    amplitude_2: f64,
    omega: f64,
    out: *mut jointlin_linearization3d,
) -> i32 {
    boundary("jointlin_linearize3d", || {
        // SAFETY: checked by `load`; valid by contract.
        let c = unsafe { load(contact, "contact") }?.to_core()?;
        check_ptr(out, "out")?;
        let d = describe(&c, normal_force, [amplitude_1, amplitude_2], omega)?;
        let l = jointlin_linearization3d {
            k_star: d.k_star,
            d_star: d.d_star,
            energy_per_cycle: d.energy_per_cycle,
            regime: regime_code(d.regime),
        };
        // SAFETY: checked non-NULL and aligned above.
        unsafe { put(out, l) };
        Ok(())
    })
}

/// Describing function of a three-direction point at the constant normal force
/// `normal_force` (force; <= 0 open: all zeros, JOINTLIN_REGIME_OPEN) for the tangential
/// motion u(t) = Re(u_hat e^{i omega t}), `u_hat` = (re u1, im u1, re u2, im u2) (length):
/// the path is an ellipse, described in its principal axes as by jointlin_linearize3d and
/// rotated back, so t = (K* + i omega D*) u_hat with symmetric K*, D*. A minor axis below
/// 1e-6 of the major one is evaluated there (its coefficient is then the thin path's
/// limit, not 0); u_hat = 0 gives K* = k_t0 I. `method`: JOINTLIN_DESCRIBE_INTEGRATED or
/// JOINTLIN_DESCRIBE_TABULATED. Meaningful only while the normal force stays constant and
/// positive over the cycle (docs/contact3d.md).
///
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_OUT_OF_RANGE (omega
/// <= 0, an unknown method, invalid contact), JOINTLIN_ERR_OVERFLOW. `*out` is written only
/// on JOINTLIN_OK.
///
/// # Safety
/// `contact` must point to a valid jointlin_contact3d, `u_hat` to 4 doubles and `out` to
/// a writable jointlin_linearization3d_matrix.
#[no_mangle]
pub unsafe extern "C" fn jointlin_linearize3d_phasors(
    contact: *const jointlin_contact3d,
    normal_force: f64,
    u_hat: *const f64,
    omega: f64,
    method: i32,
    out: *mut jointlin_linearization3d_matrix,
) -> i32 {
    boundary("jointlin_linearize3d_phasors", || {
        // SAFETY: checked by `load`/`load_finite`; valid by contract.
        let c = unsafe { load(contact, "contact") }?.to_core()?;
        let u: [f64; 4] = unsafe { load_finite(u_hat, 4, "u_hat") }?;
        check_ptr(out, "out")?;
        let method = match method {
            JOINTLIN_DESCRIBE_INTEGRATED => Method::Integrated,
            JOINTLIN_DESCRIBE_TABULATED => Method::Tabulated,
            _ => return Err(FfiError::new(JOINTLIN_ERR_OUT_OF_RANGE, "unknown method")),
        };
        let phasors = [Complex64::new(u[0], u[1]), Complex64::new(u[2], u[3])];
        let d = describe_phasors(&c, normal_force, phasors, omega, method)?;
        let flat = |m: [[f64; 2]; 2]| [m[0][0], m[0][1], m[1][0], m[1][1]];
        let l = jointlin_linearization3d_matrix {
            k_star: flat(d.k_star),
            d_star: flat(d.d_star),
            semi_axes: d.semi_axes,
            angle: d.angle,
            energy_per_cycle: d.energy_per_cycle,
            regime: regime_code(d.regime),
        };
        // SAFETY: checked non-NULL and aligned above.
        unsafe { put(out, l) };
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::error::{JOINTLIN_ERR_NON_FINITE, JOINTLIN_ERR_NULL, JOINTLIN_OK};

    fn jenkins() -> jointlin_contact3d {
        jointlin_contact3d {
            law: JOINTLIN_LAW_JENKINS,
            cells: 0,
            mu: 0.5,
            k_t0: 1000.0,
            normal_law: JOINTLIN_NORMAL_LINEAR,
            normal_stiffness: 2000.0,
            r_star: 0.0,
        }
    }

    #[test]
    fn steps_through_the_c_api_like_the_core() {
        let c = jenkins();
        let mut state = [0.0; JOINTLIN_POINT3D_STATE_LEN];
        let mut out = jointlin_step3d::default();
        let disp = [2e-3, 1e-3, 1e-3];
        let p = state.as_mut_ptr();
        // state_out may equal state.
        let rc = unsafe { jointlin_point3d_step(&c, p, disp.as_ptr(), p, &mut out) };
        assert_eq!(rc, JOINTLIN_OK);
        let (_, r) = c
            .to_core()
            .unwrap()
            .step(&State3d::default(), disp)
            .unwrap();
        assert_eq!(out.force, r.force);
        assert_eq!(out.force[2], 2.0);
        assert!((out.force[0].hypot(out.force[1]) - 1.0).abs() < 1e-15);
        assert_eq!(state[0], 1.0);
    }

    #[test]
    fn hard_inputs_give_codes_and_leave_outputs_alone() {
        let c = jenkins();
        let state = [0.0; JOINTLIN_POINT3D_STATE_LEN];
        let mut next = [7.0; JOINTLIN_POINT3D_STATE_LEN];
        let mut out = jointlin_step3d::default();
        let bad = [f64::NAN, 0.0, 0.0];
        let rc = unsafe {
            jointlin_point3d_step(
                &c,
                state.as_ptr(),
                bad.as_ptr(),
                next.as_mut_ptr(),
                &mut out,
            )
        };
        assert_eq!(rc, JOINTLIN_ERR_NON_FINITE);
        assert!(next.iter().all(|&v| v == 7.0));
        let rc = unsafe {
            jointlin_point3d_step(
                std::ptr::null(),
                state.as_ptr(),
                bad.as_ptr(),
                next.as_mut_ptr(),
                &mut out,
            )
        };
        assert_eq!(rc, JOINTLIN_ERR_NULL);
        for broken in [
            jointlin_contact3d { law: 7, ..c },
            jointlin_contact3d { cells: 2, ..c },
            jointlin_contact3d { normal_law: 2, ..c },
            jointlin_contact3d { mu: -0.1, ..c },
            jointlin_contact3d {
                law: JOINTLIN_LAW_MINDLIN,
                cells: 129,
                ..c
            },
        ] {
            let rc = unsafe {
                jointlin_point3d_step(
                    &broken,
                    state.as_ptr(),
                    [0.0; 3].as_ptr(),
                    next.as_mut_ptr(),
                    &mut out,
                )
            };
            assert_eq!(rc, JOINTLIN_ERR_OUT_OF_RANGE);
        }
        let mut l = jointlin_linearization3d::default();
        let rc = unsafe { jointlin_linearize3d(&c, 1.0, 1e-3, f64::INFINITY, 1.0, &mut l) };
        assert_eq!(rc, JOINTLIN_ERR_NON_FINITE);
        let rc = unsafe { jointlin_linearize3d(&c, 1.0, 1e-3, 1e-3, 0.0, &mut l) };
        assert_eq!(rc, JOINTLIN_ERR_OUT_OF_RANGE);
        // A circle at R = 2x: k* = k/4, energy 2π √3 x μN.
        let rc = unsafe { jointlin_linearize3d(&c, 2.0, 2e-3, 2e-3, 1.0, &mut l) };
        assert_eq!(rc, JOINTLIN_OK);
        assert!((l.k_star[0] - 250.0).abs() < 1e-12 && (l.k_star[1] - 250.0).abs() < 1e-12);
        let e = 2.0 * std::f64::consts::PI * 3f64.sqrt() * 1e-3;
        assert!((l.energy_per_cycle - e).abs() < 1e-15);
    }
}
