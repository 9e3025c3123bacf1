//! Scene interface data → what the C API takes (PROPS, tangential contact data).

use crate::capi::{self, NormalProps, Tangential, NPROPS};
use crate::model::Interface;
use crate::scene::NormalLawName;

/// UINTER PROPS of an interface (src/ffi/props.rs layout).
pub fn interface_props(i: &Interface) -> [f64; NPROPS] {
    let normal = match i.normal_law {
        NormalLawName::Linear => NormalProps::Linear {
            k_n: i.normal_stiffness_per_area.expect("validated"),
        },
        NormalLawName::Hertz => NormalProps::Hertz {
            e_star: i.hertz_e_star.expect("validated"),
            r_star: i.hertz_radius.expect("validated"),
        },
    };
    capi::props(i.law, i.rule, i.mu, i.k_t0_per_area, normal)
}

/// Constant normal stiffness per area used when the normal nonlinearity is off.
pub fn normal_stiffness(i: &Interface) -> f64 {
    i.normal_stiffness_per_area.expect("validated")
}

/// Tangential data of a point of this interface at pressure `p` (stress form).
pub fn tangential(i: &Interface, p: f64) -> Tangential {
    Tangential {
        law: i.law,
        rule: i.rule,
        mu: i.mu,
        normal: p,
        k_t0: i.k_t0_per_area,
    }
}
