//! A contact pair's USER interaction → its contact law: the PROPS table of
//! fortran-shim/README.md (`src/ffi/props.rs`) read exactly as the Fortran shim reads it,
//! so the same deck runs in Abaqus with the shim's UINTER.

use super::{ContactPair, DeckError, DeckErrorKind as K, Interaction};
use crate::names::{ContactLaw, LawName, NormalLawName, RuleName};

/// PROPS entries a run needs (the shim's NPROPS ≥ 7).
const MIN_PROPS: usize = 7;

/// The contact law (stress form: per unit area) of contact pair `pair` with interaction
/// `inter` (PROPS 1…12).
pub fn user_law(pair: &ContactPair, inter: &Interaction) -> Result<ContactLaw, DeckError> {
    let err = |m: String| pair.origin.error(K::Unsupported, "*CONTACT PAIR", m);
    if !inter.user || inter.properties.len() < MIN_PROPS {
        return Err(err(format!(
            "interaction {} (line {}) needs USER, PROPERTIES >= {MIN_PROPS} and the property table of fortran-shim/README.md (law, rule, mu, k_T0 per area, normal law, k_N or E*, r*)",
            inter.name, inter.origin.line
        )));
    }
    let p = &inter.properties;
    let get = |i: usize| p.get(i - 1).copied().unwrap_or(0.0);
    let bad = |i: usize, what: &str| {
        err(format!(
            "interaction {}: PROPS({i}) = {}: {what}",
            inter.name,
            get(i)
        ))
    };
    let code = |i: usize, n: u8| -> Result<u8, DeckError> {
        let v = get(i);
        (0..n)
            .find(|&c| v == f64::from(c))
            .ok_or_else(|| bad(i, &format!("must be one of 0…{}", n - 1)))
    };
    let law = [LawName::Mindlin, LawName::Jenkins][code(1, 2)? as usize];
    let rule = [RuleName::Thesis, RuleName::Masing][code(2, 2)? as usize];
    let mu = get(3);
    if !(mu.is_finite() && mu >= 0.0) {
        return Err(bad(3, "friction coefficient must be >= 0"));
    }
    if code(8, 2)? == 1 {
        return Err(bad(
            8,
            "k_T0 from Hertz–Mindlin (2.38) is not read by a run: give k_T0 per area in PROPS(4) and PROPS(8) = 0",
        ));
    }
    let k_t0 = get(4);
    if !(k_t0.is_finite() && k_t0 > 0.0) {
        return Err(bad(4, "k_T0 per area must be > 0"));
    }
    let normal_law = [NormalLawName::Linear, NormalLawName::Hertz][code(5, 2)? as usize];
    let k6 = get(6);
    if !(k6.is_finite() && k6 > 0.0) {
        return Err(bad(6, "k_N per area (linear) or E* (Hertz) must be > 0"));
    }
    let r = get(7);
    if normal_law == NormalLawName::Hertz && !(r.is_finite() && r > 0.0) {
        return Err(bad(7, "r* must be > 0 for Hertz"));
    }
    // PROPS(10): viscous d* or structural ω d* = η k*: the same dynamic stiffness at a
    // given frequency, which is what a run assembles; either is accepted.
    code(10, 2)?;
    if code(11, 1).is_err() || get(12) != 0.0 {
        return Err(bad(
            if get(11) != 0.0 { 11 } else { 12 },
            "a run linearizes with the library's default quadrature (PROPS(11) = PROPS(12) = 0)",
        ));
    }
    let linear = normal_law == NormalLawName::Linear;
    Ok(ContactLaw {
        law,
        rule,
        mu,
        k_t0_per_area: k_t0,
        normal_law,
        normal_stiffness_per_area: linear.then_some(k6),
        hertz_radius: (!linear).then_some(r),
        hertz_e_star: (!linear).then_some(k6),
    })
}
