//! `jointlin_linearize`: k*, d*, η and the energy per cycle of one contact point for one
//! amplitude and one frequency (HBM (3.8) on the Ersatzfunktion (4.3), EBM (3.14)).

use super::error::{boundary, FfiError, FfiResult, JOINTLIN_ERR_OUT_OF_RANGE};
use super::{check_ptr, finite, load, put};
use crate::hysteresis::Rule;
use crate::law::TangentialLaw;
use crate::linearize::{linearize, Contact, Method, Regime, DEFAULT_POINTS};

/// Tangential law code: Hertz–Mindlin microslip (2.49) then Coulomb sliding (2.39).
pub const JOINTLIN_LAW_MINDLIN: i32 = 0;
/// Tangential law code: Jenkins element (linear spring k_T0 + Coulomb slider).
pub const JOINTLIN_LAW_JENKINS: i32 = 1;
/// Unloading rule code: the thesis's rule (elastic unloading with k_T0 until the force
/// changes sign, §2.3.3; an excursion past zero force shallower than a quarter of the
/// branch before it keeps a fading memory of that branch, docs/model.md §4).
pub const JOINTLIN_RULE_THESIS: i32 = 0;
/// Unloading rule code: Masing's rule (Mindlin–Deresiewicz).
pub const JOINTLIN_RULE_MASING: i32 = 1;
/// Quadrature code: closed-form loop area, graded Gauss–Legendre for k* (default).
pub const JOINTLIN_METHOD_GRADED: i32 = 0;
/// Quadrature code: the thesis's composite Simpson rule (Fig. 4.11); `points` = intervals.
pub const JOINTLIN_METHOD_SIMPSON: i32 = 1;
/// Quadrature code: plain Gauss–Legendre over the loop; `points` = Gauss points.
pub const JOINTLIN_METHOD_GAUSS: i32 = 2;
/// Simpson intervals used when `points` is 0.
pub const JOINTLIN_SIMPSON_DEFAULT_INTERVALS: i32 = 256;
/// Gauss points used by JOINTLIN_METHOD_GAUSS when `points` is 0.
pub const JOINTLIN_GAUSS_DEFAULT_POINTS: i32 = 64;
/// Regime code: open contact (F_N <= 0) or no friction (mu = 0): everything 0.
pub const JOINTLIN_REGIME_OPEN: i32 = 0;
/// Regime code: no slip in the loop.
pub const JOINTLIN_REGIME_STICK: i32 = 1;
/// Regime code: Mindlin microslip, no Coulomb sliding.
pub const JOINTLIN_REGIME_MICROSLIP: i32 = 2;
/// Regime code: part of every cycle is Coulomb sliding.
pub const JOINTLIN_REGIME_SLIDING: i32 = 3;

/// One contact point's tangential data. Forces may be stresses (and k_t0 a stiffness per
/// area) as long as units are consistent.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct jointlin_contact {
    /// JOINTLIN_LAW_MINDLIN or JOINTLIN_LAW_JENKINS.
    pub law: i32,
    /// JOINTLIN_RULE_THESIS or JOINTLIN_RULE_MASING.
    pub rule: i32,
    /// Friction coefficient mu >= 0.
    pub mu: f64,
    /// Normal force F_N, positive in compression (force, or pressure in stress form);
    /// F_N <= 0 is an open contact.
    pub normal_force: f64,
    /// Full-stick tangential stiffness k_T0 > 0 (force/length, or per area).
    pub k_t0: f64,
}

/// Quadrature of the loop integrals. Pass NULL for the default (graded, 8 points per panel).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct jointlin_method {
    /// JOINTLIN_METHOD_GRADED, _SIMPSON or _GAUSS.
    pub kind: i32,
    /// Gauss points per panel (graded, 1..128), Gauss points (gauss, 2..128) or Simpson
    /// intervals (simpson, even, 2..2^26); 0 = the method's default.
    pub points: i32,
}

/// The linearized point.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct jointlin_linearization {
    /// Equivalent stiffness k* (3.8), 0 <= k* <= k_T0.
    pub k_star: f64,
    /// Equivalent viscous damping d* = A_hys / (pi omega A^2) (3.14), >= 0.
    pub d_star: f64,
    /// Loss factor eta = A_hys / (pi k* A^2) (0 when nothing dissipates).
    pub eta: f64,
    /// Energy dissipated per cycle A_hys >= 0 (force x length).
    pub energy_per_cycle: f64,
    /// Peak force of the loop (<= mu F_N).
    pub peak_force: f64,
    /// Slip limit delta* (length; 0 when open).
    pub slip_limit: f64,
    /// A / delta* (0 when open).
    pub amplitude_ratio: f64,
    /// JOINTLIN_REGIME_* code.
    pub regime: i32,
}

impl jointlin_contact {
    /// The core contact, or JOINTLIN_ERR_OUT_OF_RANGE for an unknown law or rule code.
    pub(crate) fn to_core(self) -> FfiResult<Contact> {
        Ok(Contact {
            law: law_from_code(self.law).ok_or_else(|| bad_code("contact law", self.law))?,
            rule: rule_from_code(self.rule).ok_or_else(|| bad_code("contact rule", self.rule))?,
            mu: finite(self.mu, "contact mu")?,
            normal_force: finite(self.normal_force, "contact normal_force")?,
            k_t0: finite(self.k_t0, "contact k_t0")?,
        })
    }
}

/// The tangential law of a JOINTLIN_LAW_* code; None for an unknown code.
pub(crate) fn law_from_code(code: i32) -> Option<TangentialLaw> {
    match code {
        JOINTLIN_LAW_MINDLIN => Some(TangentialLaw::Mindlin),
        JOINTLIN_LAW_JENKINS => Some(TangentialLaw::Jenkins),
        _ => None,
    }
}

/// The unloading rule of a JOINTLIN_RULE_* code; None for an unknown code.
pub(crate) fn rule_from_code(code: i32) -> Option<Rule> {
    match code {
        JOINTLIN_RULE_THESIS => Some(Rule::Thesis),
        JOINTLIN_RULE_MASING => Some(Rule::Masing),
        _ => None,
    }
}

fn bad_code(what: &str, code: i32) -> FfiError {
    FfiError::new(
        JOINTLIN_ERR_OUT_OF_RANGE,
        format!("unknown {what} code {code}"),
    )
}

/// The core method for (kind, points), points 0 = default; None for an invalid pair.
pub(crate) fn method_from_codes(kind: i32, points: i32) -> Option<Method> {
    let n = |default: i32| usize::try_from(if points == 0 { default } else { points }).ok();
    let m = match kind {
        JOINTLIN_METHOD_GRADED => Method::Graded {
            points: n(DEFAULT_POINTS as i32)?,
        },
        JOINTLIN_METHOD_SIMPSON => Method::Simpson {
            intervals: n(JOINTLIN_SIMPSON_DEFAULT_INTERVALS)?,
        },
        JOINTLIN_METHOD_GAUSS => Method::Gauss {
            points: n(JOINTLIN_GAUSS_DEFAULT_POINTS)?,
        },
        _ => return None,
    };
    m.validate().ok()
}

impl From<crate::linearize::Linearization> for jointlin_linearization {
    fn from(l: crate::linearize::Linearization) -> Self {
        Self {
            k_star: l.k_star,
            d_star: l.d_star,
            eta: l.eta,
            energy_per_cycle: l.energy_per_cycle,
            peak_force: l.peak_force,
            slip_limit: l.slip_limit,
            amplitude_ratio: l.amplitude_ratio,
            regime: regime_code(l.regime),
        }
    }
}

pub(crate) fn regime_code(r: Regime) -> i32 {
    match r {
        Regime::Open => JOINTLIN_REGIME_OPEN,
        Regime::Stick => JOINTLIN_REGIME_STICK,
        Regime::Microslip => JOINTLIN_REGIME_MICROSLIP,
        Regime::Sliding => JOINTLIN_REGIME_SLIDING,
    }
}

/// Linearizes one contact point for the tangential displacement amplitude `amplitude`
/// (length, >= 0) at the angular frequency `omega` (rad per time unit, > 0): k* by
/// first-order harmonic balance on the mean of the loop's branches (3.8, 4.3), d* by
/// energy balance (3.14). An open contact (F_N <= 0) or mu = 0 gives all zeros and
/// JOINTLIN_REGIME_OPEN with status JOINTLIN_OK.
///
/// Every output is right over the whole double range: the loop is evaluated in the
/// point's own units (mu F_N = 1, delta* = 1) and scaled back without intermediate
/// overflow or underflow, so a subnormal delta* (k_t0 = DBL_MAX) or A/delta*
/// (F_N = 1e308, A = 1e-8), or mu F_N = 1e-165, give the scaled loop; an output below the
/// smallest double is 0 or subnormal. A = 0 is JOINTLIN_REGIME_STICK with k* = k_t0; any
/// A > 0 on a Mindlin point is at least JOINTLIN_REGIME_MICROSLIP.
///
/// `contact` and `out` must not be NULL; `method` may be NULL (default quadrature).
/// Errors: JOINTLIN_ERR_NULL, JOINTLIN_ERR_NON_FINITE (any NaN/Inf input),
/// JOINTLIN_ERR_OUT_OF_RANGE (amplitude < 0, omega <= 0, mu < 0, k_t0 <= 0, unknown codes,
/// bad point count: plain Gauss needs >= 2 points), JOINTLIN_ERR_OVERFLOW (an output
/// beyond DBL_MAX: mu F_N, delta*, A/delta*, the energy per cycle, d* or eta). `*out` is
/// written only on JOINTLIN_OK.
///
/// # Safety
/// Non-NULL pointers must point to valid, aligned objects of their types.
#[no_mangle]
pub unsafe extern "C" fn jointlin_linearize(
    contact: *const jointlin_contact,
    amplitude: f64,
    omega: f64,
    method: *const jointlin_method,
    out: *mut jointlin_linearization,
) -> i32 {
    boundary("jointlin_linearize", || {
        // SAFETY: checked by `load`; valid by contract.
        let c = unsafe { load(contact, "contact") }?.to_core()?;
        check_ptr(out, "out")?;
        let method = if method.is_null() {
            Method::default()
        } else {
            // SAFETY: non-NULL, valid by contract.
            let m = unsafe { load(method, "method") }?;
            method_from_codes(m.kind, m.points).ok_or_else(|| {
                FfiError::new(
                    JOINTLIN_ERR_OUT_OF_RANGE,
                    format!("method kind {} with points {}", m.kind, m.points),
                )
            })?
        };
        finite(amplitude, "amplitude")?;
        finite(omega, "omega")?;
        let l = linearize(&c, amplitude, omega, method)?;
        // SAFETY: checked non-NULL and aligned above.
        unsafe { put(out, l.into()) };
        Ok(())
    })
}
