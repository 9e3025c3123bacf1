//! The UINTER property table (PROPS, the layout of src/ffi/props.rs and
//! fortran-shim/README.md) ⇄ an interface's [`ContactLaw`]: the harness's one encoding of
//! it. [`encode`] writes the table a run hands to `jointlin_uinter` and an exported deck
//! carries; [`decode`] reads a deck's table by asking the library first
//! (`jointlin_uinter_props_check`), so a table means in the harness what it means in the
//! shim, and an unknown code is refused, never guessed.

use jointlin::ffi::linearize::{
    JOINTLIN_LAW_JENKINS, JOINTLIN_LAW_MINDLIN, JOINTLIN_RULE_MASING, JOINTLIN_RULE_THESIS,
};
use jointlin::ffi::point3d::{JOINTLIN_NORMAL_HERTZ, JOINTLIN_NORMAL_LINEAR};
use jointlin::ffi::props::{jointlin_uinter_props_check, JOINTLIN_UINTER_MIN_NPROPS};
use thiserror::Error;

use super::{check, CapiError, Quadrature, NPROPS, QUADRATURE};
use crate::names::{ContactLaw, LawName, NormalLawName, RuleName};

/// The shortest table the library takes (NPROPS).
pub const MIN_PROPS: usize = JOINTLIN_UINTER_MIN_NPROPS as usize;

/// 1-based PROPS positions.
mod at {
    pub const LAW: usize = 1;
    pub const RULE: usize = 2;
    pub const MU: usize = 3;
    pub const K_T0: usize = 4;
    pub const NORMAL: usize = 5;
    pub const K_N_OR_E_STAR: usize = 6;
    pub const R_STAR: usize = 7;
    pub const K_T0_SOURCE: usize = 8;
    pub const QUADRATURE: usize = 11;
    pub const POINTS: usize = 12;
}

/// A property table the harness cannot take as a [`ContactLaw`].
#[derive(Debug, Clone, Error, PartialEq)]
pub enum PropsError {
    /// The library refuses the table (the reason names the entry).
    #[error("{0}")]
    Library(CapiError),
    /// A valid table with an entry a run does not read: PROPS(`entry`) = `value`.
    #[error("PROPS({entry}) = {value}: {reason}")]
    NotRead {
        entry: usize,
        value: f64,
        reason: &'static str,
    },
}

/// The JOINTLIN_LAW_* code of a law.
pub(super) fn law_code(l: LawName) -> i32 {
    match l {
        LawName::Mindlin => JOINTLIN_LAW_MINDLIN,
        LawName::Jenkins => JOINTLIN_LAW_JENKINS,
    }
}

/// The JOINTLIN_RULE_* code of a rule.
pub(super) fn rule_code(r: RuleName) -> i32 {
    match r {
        RuleName::Thesis => JOINTLIN_RULE_THESIS,
        RuleName::Masing => JOINTLIN_RULE_MASING,
    }
}

fn normal_code(n: NormalLawName) -> i32 {
    match n {
        NormalLawName::Linear => JOINTLIN_NORMAL_LINEAR,
        NormalLawName::Hertz => JOINTLIN_NORMAL_HERTZ,
    }
}

fn law_name(code: i32) -> Option<LawName> {
    [LawName::Mindlin, LawName::Jenkins]
        .into_iter()
        .find(|&l| law_code(l) == code)
}

fn rule_name(code: i32) -> Option<RuleName> {
    [RuleName::Thesis, RuleName::Masing]
        .into_iter()
        .find(|&r| rule_code(r) == code)
}

fn normal_name(code: i32) -> Option<NormalLawName> {
    [NormalLawName::Linear, NormalLawName::Hertz]
        .into_iter()
        .find(|&n| normal_code(n) == code)
}

/// The PROPS of `law`: k_T0 given per area (PROPS 8 = 0), viscous damping output, the
/// quadrature set by [`super::set_quadrature`] on this thread (default: the library's).
pub fn encode(law: &ContactLaw) -> [f64; NPROPS] {
    let (k6, r) = match law.normal_law {
        NormalLawName::Linear => (law.normal_stiffness_per_area.unwrap_or(0.0), 0.0),
        NormalLawName::Hertz => (
            law.hertz_e_star.unwrap_or(0.0),
            law.hertz_radius.unwrap_or(0.0),
        ),
    };
    let (qk, qn) = QUADRATURE
        .with(|c| c.get())
        .map_or((0, 0), Quadrature::code);
    let mut p = [0.0; NPROPS];
    p[at::LAW - 1] = f64::from(law_code(law.law));
    p[at::RULE - 1] = f64::from(rule_code(law.rule));
    p[at::MU - 1] = law.mu;
    p[at::K_T0 - 1] = law.k_t0_per_area;
    p[at::NORMAL - 1] = f64::from(normal_code(law.normal_law));
    p[at::K_N_OR_E_STAR - 1] = k6;
    p[at::R_STAR - 1] = r;
    p[at::QUADRATURE - 1] = f64::from(qk);
    p[at::POINTS - 1] = f64::from(qn);
    p
}

/// The contact law of a property table (PROPS(1…n), n ≥ 7, entries past n 0), as the
/// library reads it. A run takes k_T0 per area (PROPS 8 = 0) and the library's default
/// quadrature (PROPS 11 = 12 = 0); PROPS 10 (viscous or structural output) gives the same
/// dynamic stiffness at a frequency, so either is taken.
pub fn decode(props: &[f64]) -> Result<ContactLaw, PropsError> {
    let n = i32::try_from(props.len()).unwrap_or(i32::MAX);
    // SAFETY: `props` holds n readable doubles.
    let status = unsafe { jointlin_uinter_props_check(props.as_ptr(), n) };
    check("jointlin_uinter_props_check", status).map_err(PropsError::Library)?;
    let get = |i: usize| props.get(i - 1).copied().unwrap_or(0.0);
    let not_read = |entry: usize, reason| PropsError::NotRead {
        entry,
        value: get(entry),
        reason,
    };
    if get(at::K_T0_SOURCE) != 0.0 {
        return Err(not_read(
            at::K_T0_SOURCE,
            "k_T0 from Hertz–Mindlin (2.38) is not read by a run: give k_T0 per area in PROPS(4) and PROPS(8) = 0",
        ));
    }
    for entry in [at::QUADRATURE, at::POINTS] {
        if get(entry) != 0.0 {
            return Err(not_read(
                entry,
                "a run linearizes with the library's default quadrature (PROPS(11) = PROPS(12) = 0)",
            ));
        }
    }
    // Codes the library accepted are exact integers it knows.
    let code = |i: usize| get(i) as i32;
    let law = law_name(code(at::LAW)).expect("law code checked by the library");
    let rule = rule_name(code(at::RULE)).expect("rule code checked by the library");
    let normal_law = normal_name(code(at::NORMAL)).expect("normal code checked by the library");
    let linear = normal_law == NormalLawName::Linear;
    let k6 = get(at::K_N_OR_E_STAR);
    Ok(ContactLaw {
        law,
        rule,
        mu: get(at::MU),
        k_t0_per_area: get(at::K_T0),
        normal_law,
        normal_stiffness_per_area: linear.then_some(k6),
        hertz_radius: (!linear).then_some(get(at::R_STAR)),
        hertz_e_star: (!linear).then_some(k6),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hertz() -> ContactLaw {
        ContactLaw {
            law: LawName::Jenkins,
            rule: RuleName::Masing,
            mu: 0.2,
            k_t0_per_area: 3e4,
            normal_law: NormalLawName::Hertz,
            normal_stiffness_per_area: None,
            hertz_radius: Some(5.0),
            hertz_e_star: Some(1.1e5),
        }
    }

    #[test]
    fn every_law_survives_encode_then_decode() {
        let linear = ContactLaw {
            law: LawName::Mindlin,
            rule: RuleName::Thesis,
            normal_law: NormalLawName::Linear,
            normal_stiffness_per_area: Some(1e6),
            hertz_radius: None,
            hertz_e_star: None,
            ..hertz()
        };
        for law in [linear, hertz()] {
            assert_eq!(decode(&encode(&law)), Ok(law));
        }
        // A short table (PROPERTIES = 7) is the same law.
        assert_eq!(decode(&encode(&linear)[..7]), Ok(linear));
    }

    #[test]
    fn the_library_refuses_what_it_does_not_know() {
        let good = encode(&hertz());
        for (i, v) in [(0, 2.0), (1, 7.0), (4, 2.0), (0, 0.5), (6, 0.0), (2, -1.0)] {
            let mut p = good;
            p[i] = v;
            match decode(&p) {
                Err(PropsError::Library(e)) => {
                    assert!(e.detail.contains(&format!("PROPS({})", i + 1)), "{e}")
                }
                other => panic!("PROPS({}) = {v}: {other:?}", i + 1),
            }
        }
        assert!(matches!(decode(&good[..6]), Err(PropsError::Library(_))));
        let mut p = good;
        p[10] = 1.0;
        assert!(matches!(
            decode(&p),
            Err(PropsError::NotRead { entry: 11, .. })
        ));
    }
}
