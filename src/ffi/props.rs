//! The UINTER property (PROPS) and state-variable (STATEV) layouts.
//!
//! The two tables are the documentation of [`JOINTLIN_UINTER_MIN_NPROPS`] and
//! [`JOINTLIN_UINTER_MIN_NSTATV`], so that they appear in include/jointlin.h too.

use super::error::{boundary, FfiError, FfiResult, JOINTLIN_ERR_PROPS, JOINTLIN_ERR_SIZE};
use super::linearize::{law_from_code, method_from_codes, rule_from_code};
use super::load_finite;
use super::point3d::{JOINTLIN_NORMAL_HERTZ, JOINTLIN_NORMAL_LINEAR};
use crate::hysteresis::{Rule, STATE_LEN};
use crate::law::hertz::{Hertz, NormalLaw};
use crate::law::mindlin::Mindlin;
use crate::law::TangentialLaw;
use crate::linearize::Method;

/// Smallest NPROPS accepted by jointlin_uinter. The UINTER property layout:
///
/// PROPS (1-based as in the Abaqus input file; NPROPS >= 7, entries past NPROPS take the
/// default; only the first 12 are read, later ones are the host's):
///
/// | #  | meaning                                                           | default |
/// |----|-------------------------------------------------------------------|---------|
/// | 1  | tangential law: 0 Mindlin (2.49), 1 Jenkins                       | —       |
/// | 2  | unloading rule: 0 thesis (§2.3.3), 1 Masing                       | —       |
/// | 3  | friction coefficient μ ≥ 0                                        | —       |
/// | 4  | k_T0 per unit area (stress/length), > 0 when PROPS 8 = 0          | —       |
/// | 5  | normal law: 0 linear penalty p = k_N h, 1 Hertz (2.34) over AREA  | —       |
/// | 6  | k_N per unit area (> 0) for PROPS 5 = 0, E* (> 0) for PROPS 5 = 1  | —       |
/// | 7  | r* (> 0) for Hertz (2.31); ignored (any finite) for linear         | —       |
/// | 8  | k_T0 source: 0 PROPS 4, 1 Hertz–Mindlin k_T0 = 8 r_A G* / AREA (2.38) | 0       |
/// | 9  | G* (> 0) when PROPS 8 = 1 (2.37)                                   | 0       |
/// | 10 | damping output at LINPER = 1: 0 viscous DVISCOUS = d*, 1 structural DSTRUCTURAL = ω d* = η k* | 0 |
/// | 11 | quadrature: 0 graded (default), 1 Simpson, 2 Gauss                 | 0       |
/// | 12 | points per panel / intervals / points; 0 = the method's default    | 0       |
///
/// Integer codes must be given exactly (1.0, not 1.2). With Hertz, the point's normal force
/// is F_N = p·AREA and r_A = (3 F_N r* / (4 E*))^(1/3) (2.32).
pub const JOINTLIN_UINTER_MIN_NPROPS: i32 = 7;
/// PROPS entries read by jointlin_uinter.
pub const JOINTLIN_UINTER_MAX_NPROPS: i32 = 12;
/// Smallest NSTATV accepted by jointlin_uinter. The UINTER state-variable layout:
///
/// STATEV (NSTATV >= 57; entries past 57 are left to the host):
///
/// | #     | meaning                                                             |
/// |-------|---------------------------------------------------------------------|
/// | 1     | store point id (written at LINPER = 1; 0 before)                    |
/// | 2     | base pressure p0 of the last LINPER = 0 call (0 when open)          |
/// | 3     | base overclosure h0 of the last LINPER = 0 call                      |
/// | 4     | closed flag of the last LINPER = 0 call (1 closed, 0 open/never)    |
/// | 5     | accumulated frictional dissipation per unit area (LINPER = 0)       |
/// | 6–28  | direction-1 hysteresis state (JOINTLIN_POINT_STATE_LEN = 23 values)  |
/// | 29–51 | direction-2 hysteresis state                                        |
/// | 52–53 | k* per area, directions 1 and 2 (LINPER = 1)                        |
/// | 54–55 | d* per area, directions 1 and 2 (LINPER = 1)                        |
/// | 56    | energy dissipated per cycle per unit area, both directions (LINPER = 1) |
/// | 57    | dissipated power per unit area = energy per cycle × FREQR (LINPER = 1) |
///
/// A fresh (all-zero) STATEV is a never-closed point with virgin hysteresis.
pub const JOINTLIN_UINTER_MIN_NSTATV: i32 = 57;

/// Checks a UINTER property table as jointlin_uinter reads it, before a job runs: NPROPS
/// ≥ 7, integer codes exact and known, values in range (see the table above). A point's
/// AREA enters only Hertz's contact radius, so the table is read for a unit area.
///
/// Returns JOINTLIN_OK, JOINTLIN_ERR_NULL, JOINTLIN_ERR_SIZE (NPROPS < 7),
/// JOINTLIN_ERR_NON_FINITE or JOINTLIN_ERR_PROPS, with the entry and the reason in
/// jointlin_last_error.
///
/// # Safety
/// `props` must be NULL or point to `nprops` readable doubles.
#[no_mangle]
pub unsafe extern "C" fn jointlin_uinter_props_check(props: *const f64, nprops: i32) -> i32 {
    boundary("jointlin_uinter_props_check", || {
        if nprops < JOINTLIN_UINTER_MIN_NPROPS {
            return Err(FfiError::new(
                JOINTLIN_ERR_SIZE,
                format!("NPROPS {nprops} < {JOINTLIN_UINTER_MIN_NPROPS}"),
            ));
        }
        let n = (nprops as usize).min(JOINTLIN_UINTER_MAX_NPROPS as usize);
        // SAFETY: NULL/alignment checked by load_finite; n ≤ nprops readable by contract.
        let table: [f64; 12] = unsafe { load_finite(props, n, "PROPS") }?;
        Props::parse(&table, 1.0).map(|_| ())
    })
}

/// 0-based STATEV slots.
pub(crate) mod slot {
    pub(crate) const ID: usize = 0;
    pub(crate) const P0: usize = 1;
    pub(crate) const H0: usize = 2;
    pub(crate) const CLOSED: usize = 3;
    pub(crate) const DISSIPATION: usize = 4;
    /// First slot of direction d (0 or 1) hysteresis state.
    pub(crate) const fn hysteresis(d: usize) -> usize {
        5 + d * super::STATE_LEN
    }
    pub(crate) const K_STAR: usize = 51;
    pub(crate) const D_STAR: usize = 53;
    pub(crate) const ENERGY: usize = 55;
    pub(crate) const POWER: usize = 56;
    pub(crate) const LEN: usize = 57;
}
const _: () = assert!(slot::hysteresis(2) == slot::K_STAR);
const _: () = assert!(slot::LEN == JOINTLIN_UINTER_MIN_NSTATV as usize);

/// How the damping of the linearized point is handed to the solver at LINPER = 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Damping {
    Viscous,
    Structural,
}

/// Source of k_T0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum KSource {
    Given(f64),
    /// k_T0 = 8 r_A G* (2.38), per area.
    HertzMindlin {
        g_star: f64,
    },
}

/// Parsed and validated PROPS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Props {
    pub law: TangentialLaw,
    pub rule: Rule,
    pub mu: f64,
    pub normal: NormalLaw,
    pub k_source: KSource,
    pub damping: Damping,
    pub method: Method,
}

fn bad(msg: String) -> FfiError {
    FfiError::new(JOINTLIN_ERR_PROPS, msg)
}

/// An exact integer code in `0..=max` at 1-based position `pos`.
fn code(props: &[f64; 12], pos: usize, max: i32) -> FfiResult<i32> {
    let v = props[pos - 1];
    if v.fract() == 0.0 && (0.0..=f64::from(max)).contains(&v) {
        Ok(v as i32)
    } else {
        let range = if max == i32::MAX {
            "an integer code >= 0".to_string()
        } else {
            format!("a code in 0..={max}")
        };
        Err(bad(format!("PROPS({pos}) = {v:?} is not {range}")))
    }
}

fn positive(props: &[f64; 12], pos: usize, what: &str) -> FfiResult<f64> {
    let v = props[pos - 1];
    if v > 0.0 {
        Ok(v)
    } else {
        Err(bad(format!("PROPS({pos}) = {v:?}: {what} must be > 0")))
    }
}

impl Props {
    /// Parses PROPS (already checked finite, unread entries 0) for a point of area `area` > 0.
    pub fn parse(props: &[f64; 12], area: f64) -> FfiResult<Self> {
        let law = law_from_code(code(props, 1, i32::MAX)?).ok_or_else(|| {
            bad(format!(
                "PROPS(1) = {:?} is not a tangential law code",
                props[0]
            ))
        })?;
        let rule = rule_from_code(code(props, 2, i32::MAX)?).ok_or_else(|| {
            bad(format!(
                "PROPS(2) = {:?} is not an unloading rule code",
                props[1]
            ))
        })?;
        let mu = props[2];
        if mu < 0.0 {
            return Err(bad(format!(
                "PROPS(3) = {mu:?}: friction coefficient must be >= 0"
            )));
        }
        let normal = match code(props, 5, i32::MAX)? {
            JOINTLIN_NORMAL_LINEAR => NormalLaw::Linear {
                stiffness_per_area: positive(props, 6, "k_N")?,
            },
            JOINTLIN_NORMAL_HERTZ => {
                let e_star = positive(props, 6, "E*")?;
                let r_star = positive(props, 7, "r*")?;
                NormalLaw::Hertz {
                    hertz: Hertz::new(r_star, e_star)?,
                    area,
                }
            }
            _ => {
                return Err(bad(format!(
                    "PROPS(5) = {:?} is not a normal law code",
                    props[4]
                )))
            }
        };
        let k_source = match code(props, 8, 1)? {
            0 => KSource::Given(positive(props, 4, "k_T0")?),
            _ => {
                if !matches!(normal, NormalLaw::Hertz { .. }) {
                    return Err(bad(
                        "PROPS(8) = 1 (Hertz–Mindlin k_T0) needs PROPS(5) = 1 (Hertz)".into(),
                    ));
                }
                KSource::HertzMindlin {
                    g_star: positive(props, 9, "G*")?,
                }
            }
        };
        let damping = match code(props, 10, 1)? {
            0 => Damping::Viscous,
            _ => Damping::Structural,
        };
        let kind = code(props, 11, 2)?;
        let points = props[11];
        if points.fract() != 0.0 || !(0.0..=f64::from(1 << 26)).contains(&points) {
            return Err(bad(format!("PROPS(12) = {points:?} is not a point count")));
        }
        let method = method_from_codes(kind, points as i32).ok_or_else(|| {
            bad(format!(
                "PROPS(11..12) = {kind:?}, {points:?}: invalid quadrature"
            ))
        })?;
        Ok(Self {
            law,
            rule,
            mu,
            normal,
            k_source,
            damping,
            method,
        })
    }

    /// k_T0 per area at pressure p > 0: PROPS 4, or 8 r_A G* / AREA (2.38) with r_A from
    /// F_N = p·AREA (2.32).
    pub fn k_t0(&self, pressure: f64) -> f64 {
        match (self.k_source, self.normal) {
            (KSource::Given(k), _) => k,
            (KSource::HertzMindlin { g_star }, NormalLaw::Hertz { hertz, area }) => {
                Mindlin::k_t0_from_geometry(hertz.contact_radius(pressure * area), g_star) / area
                // (2.38)
            }
            (KSource::HertzMindlin { .. }, NormalLaw::Linear { .. }) => {
                unreachable!("rejected by parse")
            }
        }
    }

    /// dp/dh at the base pressure p > 0: k_N, or for Hertz k_N(F_N)/AREA = 2 r_A E*/AREA
    /// (2.35) with F_N = p·AREA.
    pub fn normal_stiffness_at(&self, pressure: f64) -> f64 {
        match self.normal {
            NormalLaw::Linear { stiffness_per_area } => stiffness_per_area,
            NormalLaw::Hertz { hertz, area } => hertz.normal_stiffness(pressure * area) / area, // (2.35)
        }
    }
}
