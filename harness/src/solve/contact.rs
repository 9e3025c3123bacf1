//! Scene interface data → what the C API takes (PROPS, tangential contact data).

use crate::capi::{self, Tangential, NPROPS};
use crate::model::Interface;

/// UINTER PROPS of an interface (src/ffi/props.rs layout).
pub fn interface_props(i: &Interface) -> [f64; NPROPS] {
    capi::props::encode(&i.contact)
}

/// Constant normal stiffness per area used when the normal nonlinearity is off.
pub fn normal_stiffness(i: &Interface) -> f64 {
    i.contact.normal_stiffness_per_area.expect("validated")
}

/// Tangential data of a point of this interface at pressure `p` (stress form).
pub fn tangential(i: &Interface, p: f64) -> Tangential {
    let c = &i.contact;
    Tangential {
        law: c.law,
        rule: c.rule,
        mu: c.mu,
        normal: p,
        k_t0: c.k_t0_per_area,
    }
}

/// The law of a sampled point (`model::subgrid`) for amplitude A at ω: k*, d* and the
/// energy per cycle (per area) are the area averages Σ fᵢ·(k*, d*, E)(pᵢ, A) over its
/// samples (fraction fᵢ, pressure pᵢ > 0); η = ω d*/k*. δ*, A/δ* and the regime stay
/// those of `node` (the law at the point's average pressure), which the maps and the
/// macroslip cap use.
pub fn area_average(
    node: &capi::Linearized,
    samples: &[(Tangential, f64)],
    amplitude: f64,
    omega: f64,
) -> Result<capi::Linearized, capi::CapiError> {
    let mut out = *node;
    out.k_star = 0.0;
    out.d_star = 0.0;
    out.energy_per_cycle = 0.0;
    for (t, f) in samples {
        let l = capi::linearize(t, amplitude, omega)?;
        out.k_star += f * l.k_star;
        out.d_star += f * l.d_star;
        out.energy_per_cycle += f * l.energy_per_cycle;
    }
    out.eta = if out.k_star > 0.0 {
        omega * out.d_star / out.k_star
    } else {
        0.0
    };
    Ok(out)
}

#[cfg(test)]
mod tests {
    use crate::input::scene::{Mode, Scene};
    use crate::model::build;
    use crate::solve::static_step;
    use crate::solve::sweep::{self, Options, SweepError};

    /// Two plates pressed by 1 N/mm² with a tip force: the samples of every point have
    /// (nearly) the same pressure, so the area average is the node's law and the sweep
    /// with `area_samples` must repeat the node-based one.
    #[test]
    fn uniform_pressure_makes_area_samples_the_node_law() {
        let base = crate::input::scene::tests::GOOD.to_string()
            + "\n[[preload]]\nkind = \"pressure\"\nbody = \"upper\"\nface = \"z_max\"\npressure = 1.0\n\
               [[preload]]\nkind = \"pressure\"\nbody = \"lower\"\nface = \"z_min\"\npressure = 1.0\n";
        let sampled = base.replace(
            "normal_stiffness_per_area = 1e5\n",
            "normal_stiffness_per_area = 1e5\narea_samples = 3\n",
        );
        let run = |text: &str| {
            let scene = Scene::parse("x", text).unwrap();
            let p = build(&scene).unwrap();
            let stat = static_step::solve(&p, true).unwrap();
            let mut opts = Options::from_scene(scene.spec.iteration, scene.spec.effects);
            opts.point_results = true;
            let r = sweep::run(&p, &stat, &scene.frequencies(), &opts, &|_, _, _| {}).unwrap();
            (p, stat, opts, r)
        };
        let (_, st0, _, node) = run(&base);
        let (p, stat, mut opts, area) = run(&sampled);
        // The clamped plates bend a little: the pressures vary by ±5e-4 along the face,
        // and averaging that field over the samples moves them by ~5e-6 (a curvature
        // term); the steady state follows to that order.
        for (a, b) in st0.pressure.iter().zip(&stat.pressure) {
            approx::assert_relative_eq!(a, b, max_relative = 1e-5);
        }
        assert!(p.has_area_samples());
        for (a, b) in node.power.iter().zip(&area.power) {
            assert!(*a > 0.0);
            approx::assert_relative_eq!(a, b, max_relative = 1e-5);
        }
        for (a, b) in node.outputs.iter().zip(&area.outputs) {
            approx::assert_relative_eq!(a[0].norm(), b[0].norm(), max_relative = 1e-5);
        }
        // The other modes evaluate points at their nodes: asked for, they refuse.
        opts.iteration.mode = Mode::Thesis;
        let e = sweep::run(&p, &stat, &[150.0], &opts, &|_, _, _| {}).unwrap_err();
        assert!(matches!(e, SweepError::AreaSamplesNeedFastMode), "{e}");
    }
}
