//! The frequency-domain rungs of the ladder (the parent module's list): first order
//! with its quadratures and tolerances, the harmonic balance at [`HARMONICS`] and, for the
//! thesis's point model, with the normal load varying.

use std::time::Instant;

use super::{report, Rung, HARMONICS, HARMONICS_NORMAL_LOAD, HB_TOLERANCE};
use crate::capi::{set_quadrature, Quadrature};
use crate::mhb::default_samples;
use crate::model::{Job, Problem};
use crate::run::{run as run_scene, Extras};
use crate::settings::Mode;
use crate::solve::sweep::harmonic_fe_point3d::{check_effects, PointModel};

/// The frequency-domain rungs of `base` (one frequency; `problem` its model,
/// `scene_model` the point model its `[effects]` choose), each named in `log` as it
/// starts.
pub(super) fn run(
    base: &Job,
    problem: &Problem,
    scene_model: PointModel,
    log: &dyn Fn(&str),
) -> Result<Vec<Rung>, String> {
    // The first-order rungs: the thesis's point model.
    let first_order = base.with_settings(base.settings.thesis_points());
    let mut rungs = Vec::new();
    let mut push_fd = |family, label: String, s: &Job, q| -> Result<(), String> {
        log(&label);
        let (a, e, c, secs) = fd(s, q)?;
        rungs.push(Rung {
            family,
            label,
            seconds: secs,
            amplitude: a,
            energy: e,
            amplitude_error: 0.0,
            energy_error: 0.0,
            converged: c,
            frequency_domain: true,
        });
        Ok(())
    };
    let mut lin_settings = first_order.settings.clone();
    lin_settings.effects.tangential_microslip = false;
    lin_settings.effects.contact_damping = false;
    let lin = first_order.with_settings(lin_settings);
    push_fd(
        "linear",
        "linear stick (k_T0, no contact damping)".into(),
        &lin,
        None,
    )?;
    for n in [4, 16, 64, 256, 1024] {
        push_fd(
            "simpson",
            format!("HBM/EBM, Simpson {n} intervals"),
            &first_order,
            Some(Quadrature::Simpson(n)),
        )?;
    }
    push_fd(
        "default",
        format!(
            "default (graded Gauss, tolerance {:.0e})",
            base.settings.iteration.tolerance
        ),
        &first_order,
        None,
    )?;
    for tol in [1e-1, 1e-2, 1e-4, 1e-6, 1e-8] {
        let mut s = first_order.settings.clone();
        s.iteration.tolerance = tol;
        s.iteration.max_passes = s.iteration.max_passes.max(200);
        push_fd(
            "tolerance",
            format!("default quadrature, tolerance {tol:.0e}"),
            &first_order.with_settings(s),
            None,
        )?;
    }
    // The scene's point model, or `normal_load_variation` added to the thesis's.
    let harmonic = |h: usize, normal_load_variation: bool| {
        let mut s = base.settings.clone();
        let it = &mut s.iteration;
        it.mode = Mode::HarmonicBalance;
        (it.harmonics, it.samples) = (Some(h), None);
        it.tolerance = HB_TOLERANCE;
        it.max_passes = it.max_passes.max(50);
        s.effects.normal_load_variation |= normal_load_variation;
        base.with_settings(s)
    };
    let with = report::effects_label(scene_model.coupled_slip, scene_model.normal_load_variation);
    for h in HARMONICS {
        push_fd(
            "harmonic",
            format!(
                "harmonic balance H = {h} (N = {}){with}, Newton to {HB_TOLERANCE:.0e}",
                default_samples(h)
            ),
            &harmonic(h, false),
            None,
        )?;
    }
    if scene_model.coupled_slip {
        // First order with the coupled element: the describing function of each point's
        // ellipse (docs/contact3d.md §4), no harmonic balance.
        let mut s = base.settings.clone();
        s.iteration.mode = Mode::Fast;
        s.effects.normal_load_variation = false;
        push_fd(
            "coupled_first_order",
            "first order with coupled_slip (describing function of the ellipse, tabulated)".into(),
            &base.with_settings(s),
            None,
        )?;
    }
    let normal = harmonic(1, true);
    match check_effects(problem, &normal.settings.effects, Mode::HarmonicBalance) {
        _ if !scene_model.is_thesis() => {}
        Ok(()) => {
            for h in HARMONICS_NORMAL_LOAD {
                push_fd(
                    "normal_load",
                    format!(
                        "harmonic balance H = {h} (N = {}) with normal_load_variation, Newton to {HB_TOLERANCE:.0e}",
                        default_samples(h)
                    ),
                    &harmonic(h, true),
                    None,
                )?;
            }
        }
        Err(e) => log(&format!("no normal_load_variation rungs: {e}")),
    }

    Ok(rungs)
}

/// (amplitude, energy, converged, seconds) of the frequency domain, repeated until 0.2 s.
fn fd(scene: &Job, q: Option<Quadrature>) -> Result<(f64, f64, bool, f64), String> {
    let prev = set_quadrature(q);
    let t = Instant::now();
    let mut reps = 0;
    let mut out = (0.0, 0.0, false);
    let res = loop {
        let r = match run_scene(scene, Extras::default(), &|_, _, _| {}) {
            Ok(r) => r,
            Err(e) => break Err(e.to_string()),
        };
        out = (
            r.main.outputs[0][0].norm(),
            r.main.power[0] / r.main.freqs[0],
            r.main.converged[0],
        );
        reps += 1;
        if t.elapsed().as_secs_f64() >= 0.2 {
            break Ok(());
        }
    };
    set_quadrature(prev);
    res?;
    Ok((out.0, out.1, out.2, t.elapsed().as_secs_f64() / reps as f64))
}
