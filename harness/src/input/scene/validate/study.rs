//! `[sweep]`, `[iteration]`, `[[outputs]]`, `[loss_study]` and `[field_output]`: what
//! the run computes and reports.

use std::collections::BTreeSet;

use super::{Checker, MAX_HARMONICS, MAX_SAMPLES};
use crate::names::MAX_FREQUENCY;

const TOO_HIGH: &str = "must be <= 1e150 (1/time): (2πf)² of a higher frequency overflows";
use crate::input::scene::error::KeyPath;
use crate::input::scene::schema::*;

/// The sweep's range and its refine bands.
pub(super) fn sweep(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    let sw = root.key("sweep");
    c.positive(sw.key("f_min"), s.sweep.f_min);
    c.positive(sw.key("f_max"), s.sweep.f_max);
    if s.sweep.f_max > MAX_FREQUENCY {
        c.fail(sw.key("f_max"), TOO_HIGH);
    }
    if s.sweep.count == 0 {
        c.fail(sw.key("count"), "must be >= 1");
    }
    c.positive(sw.key("bias"), s.sweep.bias);
    if s.sweep.f_max < s.sweep.f_min || (s.sweep.count > 1 && s.sweep.f_max == s.sweep.f_min) {
        c.fail(
            sw.key("f_max"),
            "must be > f_min (or equal to it with count = 1)",
        );
    }
    // Over a deck the deck's step may be mode-based: checked when it is attached.
    if s.sweep.method == SweepMethod::Direct && s.model.is_none() {
        for (key, given) in [
            ("modes", s.sweep.modes.is_some()),
            ("residual", s.sweep.residual.is_some()),
        ] {
            if given {
                c.fail(sw.key(key), "applies to method = \"modal\" only");
            }
        }
        if !s.sweep.modal_damping.is_empty() {
            c.fail(
                sw.key("modal_damping"),
                "applies to method = \"modal\" only",
            );
        }
    } else if s.sweep.modes == Some(0) {
        c.fail(sw.key("modes"), "must be >= 1");
    } else if s.iteration.mode == Mode::Thesis {
        c.fail(
            sw.key("method"),
            "\"modal\" is available in [iteration] modes \"fast\" and \"harmonic_balance\"",
        );
    }
    for (i, d) in s.sweep.modal_damping.iter().enumerate() {
        let dp = sw.key("modal_damping").index(i);
        for (key, v) in [("ratio", d.ratio), ("alpha", d.alpha), ("beta", d.beta)] {
            if !(v.is_finite() && v >= 0.0) {
                c.fail(dp.key(key), "must be a finite number >= 0");
            }
        }
        if let (Some(a), Some(b)) = (d.first_mode, d.last_mode) {
            if a == 0 || b < a {
                c.fail(
                    dp.key("last_mode"),
                    "modes are 1-based, first_mode <= last_mode",
                );
            }
        }
    }

    for (i, b) in s.sweep.refine.iter().enumerate() {
        let bp = sw.key("refine").index(i);
        c.positive(bp.key("f_min"), b.f_min);
        c.positive(bp.key("f_max"), b.f_max);
        if b.f_max > MAX_FREQUENCY {
            c.fail(bp.key("f_max"), TOO_HIGH);
        }
        c.positive(bp.key("bias"), b.bias);
        // count = 1 with f_max = f_min puts one exact frequency into the sweep (e.g. an
        // eigenfrequency from `jointlin modes`).
        if b.count == 0 || (b.count == 1 && b.f_max != b.f_min) {
            c.fail(
                bp.key("count"),
                "a refine band needs count >= 2 (or count = 1 with f_max = f_min)",
            );
        }
        if b.f_max < b.f_min || (b.count > 1 && b.f_max == b.f_min) {
            c.fail(
                bp.key("f_max"),
                "must be > f_min (or equal to it with count = 1)",
            );
        }
    }
}

/// The iteration's tolerance, passes and start, and the harmonic balance's keys.
pub(super) fn iteration(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    let it = root.key("iteration");
    let tol = s.iteration.tolerance;
    if !(tol > 0.0 && tol < 1.0) {
        c.fail(it.key("tolerance"), format!("must be in (0, 1), got {tol}"));
    }
    if s.iteration.max_passes == 0 {
        c.fail(it.key("max_passes"), "must be >= 1");
    }
    c.positive(it.key("initial_amplitude"), s.iteration.initial_amplitude);
    harmonic_balance(c, s);
}

/// At least one output, each a unique CSV name on a known body.
pub(super) fn outputs(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    if s.outputs.is_empty() {
        c.fail(root.key("outputs"), "at least one named output is needed");
    }
    let mut out_names = BTreeSet::new();
    for (i, o) in s.outputs.iter().enumerate() {
        let p = root.key("outputs").index(i);
        let ok_name = !o.name.is_empty()
            && o.name
                .chars()
                .all(|ch| ch.is_ascii_alphanumeric() || ch == '_' || ch == '-');
        if !ok_name {
            c.fail(
                p.key("name"),
                "output names use only A-Z a-z 0-9 _ - (CSV column names)",
            );
        }
        if !out_names.insert(o.name.as_str()) {
            c.fail(p.key("name"), format!("duplicate output `{}`", o.name));
        }
        match c.body(p.key("body"), &o.body) {
            Some(BodyKind::Box) if c.require(p.key("at"), &o.at, "for an output on a box") => {
                c.vec3(p.key("at"), o.at.as_ref().unwrap());
            }
            Some(BodyKind::Mass) => c.forbid(p.key("at"), &o.at, "for a mass body"),
            _ => {}
        }
        c.direction(p.key("direction"), &o.direction);
    }
}

/// The loss study's names and values.
pub(super) fn loss_study(c: &mut Checker, s: &SceneFile) {
    let root = KeyPath::root();
    if let Some(st) = &s.loss_study {
        let p = root.key("loss_study");
        if !s.outputs.iter().any(|o| o.name == st.output) {
            c.fail(p.key("output"), format!("no output named `{}`", st.output));
        }
        if !s.screws.iter().any(|x| x.name == st.screw) {
            c.fail(p.key("screw"), format!("no screw named `{}`", st.screw));
        }
        if st.amplitudes.is_empty() {
            c.fail(p.key("amplitudes"), "at least one amplitude is needed");
        }
        for (i, a) in st.amplitudes.iter().enumerate() {
            c.positive(p.key("amplitudes").index(i), *a);
        }
        if st.torques.is_empty() {
            c.fail(p.key("torques"), "at least one torque is needed");
        }
        for (i, t) in st.torques.iter().enumerate() {
            c.non_negative(p.key("torques").index(i), *t);
        }
        if c.finite(p.key("model_share"), st.model_share)
            && !(st.model_share > 0.0 && st.model_share <= 1.0)
        {
            c.fail(p.key("model_share"), "must be in (0, 1]");
        }
        c.positive(p.key("power_factor"), st.power_factor);
        c.positive(p.key("amplitude_factor"), st.amplitude_factor);
        for (i, r) in st.reference.iter().enumerate() {
            let rp = p.key("reference").index(i);
            c.non_negative(rp.key("torque"), r.torque);
            c.positive(rp.key("amplitude"), r.amplitude);
            c.positive(rp.key("power"), r.power);
        }
        if let Some(cal) = &st.calibration {
            calibration(c, p.key("calibration"), cal, st.reference.len());
        }
    }
}

/// A square calibration: distinct parameters, as many distinct reference points.
fn calibration(c: &mut Checker, p: KeyPath, cal: &CalibrationSpec, references: usize) {
    if cal.parameters.is_empty() {
        c.fail(p.key("parameters"), "name at least one of \"k_t0\", \"mu\"");
    }
    let distinct = |v: Vec<usize>| v.iter().collect::<BTreeSet<_>>().len() == v.len();
    if !distinct(cal.parameters.iter().map(|x| *x as usize).collect()) {
        c.fail(p.key("parameters"), "each parameter once");
    }
    if !distinct(cal.points.clone()) {
        c.fail(p.key("points"), "each reference point once");
    }
    if cal.points.len() != cal.parameters.len() {
        c.fail(
            p.key("points"),
            format!(
                "{} parameters need as many reference points, got {}",
                cal.parameters.len(),
                cal.points.len()
            ),
        );
    }
    for (i, &k) in cal.points.iter().enumerate() {
        if k >= references {
            c.fail(
                p.key("points").index(i),
                format!("the study has {references} reference points (indices from 0)"),
            );
        }
    }
}

/// `[iteration]` keys of the harmonic balance, and the effects it cannot switch off.
fn harmonic_balance(c: &mut Checker, s: &SceneFile) {
    let it = KeyPath::root().key("iteration");
    let spec = &s.iteration;
    if spec.mode != Mode::HarmonicBalance {
        let why = "unless mode = \"harmonic_balance\"";
        c.forbid(it.key("harmonics"), &spec.harmonics, why);
        c.forbid(it.key("samples"), &spec.samples, why);
        return;
    }
    let why = "for mode = \"harmonic_balance\" (e.g. 1, 3, 7, 15)";
    if !c.require(it.key("harmonics"), &spec.harmonics, why) {
        return;
    }
    let h = spec.harmonics.unwrap_or(0);
    if !(1..=MAX_HARMONICS).contains(&h) {
        c.fail(
            it.key("harmonics"),
            format!("must be in 1..={MAX_HARMONICS}, got {h}"),
        );
        return;
    }
    if let Some(n) = spec.samples {
        if n < 2 * h + 2 || n > MAX_SAMPLES {
            c.fail(
                it.key("samples"),
                format!(
                    "must be in {}..={MAX_SAMPLES} (at least 2H + 2 so that no retained harmonic aliases onto another), got {n}",
                    2 * h + 2
                ),
            );
        }
    }
    let eff = KeyPath::root().key("effects");
    let why = "must stay on with mode = \"harmonic_balance\": the balance marches the library's whole hysteresis loop (sliding and dissipation included)";
    if !s.effects.macroslip {
        c.fail(eff.key("macroslip"), why);
    }
    if !s.effects.contact_damping {
        c.fail(eff.key("contact_damping"), why);
    }
}

/// The `[time_domain]` table: the ranges `time::TimeSettings::check` enforces, here with
/// the key (the defaults stand in for keys not given).
pub(super) fn time_domain(c: &mut Checker, s: &SceneFile) {
    let Some(t) = &s.time_domain else { return };
    let p = KeyPath::root().key("time_domain");
    if let Some(n) = t.steps_per_cycle {
        if !(MIN_STEPS_PER_CYCLE..=MAX_STEPS_PER_CYCLE).contains(&n) {
            c.fail(
                p.key("steps_per_cycle"),
                format!("must be in {MIN_STEPS_PER_CYCLE}..={MAX_STEPS_PER_CYCLE}, got {n}"),
            );
        }
    }
    if let Some(r) = t.ramp_cycles {
        c.non_negative(p.key("ramp_cycles"), r);
    }
    if let Some(v) = t.tolerance {
        if !(v.is_finite() && (0.0..1.0).contains(&v)) {
            c.fail(p.key("tolerance"), format!("must be in [0, 1), got {v}"));
        }
    }
    if s.is_lumped() && t.integrator == crate::settings::Integrator::Newmark {
        c.fail(
            p.key("integrator"),
            "a lumped system is integrated by RK4 (\"rk4\" or \"auto\"), its step kept below the stability limit of its stiffest mode",
        );
    }
    if let Some(a) = t.alpha {
        if !(-1.0 / 3.0..=0.0).contains(&a) {
            c.fail(
                p.key("alpha"),
                format!("HHT-α must be in [-1/3, 0], got {a}"),
            );
        }
    }
    let min = t.min_cycles.unwrap_or(DEFAULT_MIN_CYCLES);
    let max = t.max_cycles.unwrap_or(DEFAULT_MAX_CYCLES);
    if max < 2 {
        c.fail(p.key("max_cycles"), format!("must be >= 2, got {max}"));
    } else if min > max {
        let (key, other) = if t.max_cycles.is_some() {
            ("max_cycles", "min_cycles")
        } else {
            ("min_cycles", "max_cycles")
        };
        c.fail(
            p.key(key),
            format!("{other} = {min} exceeds max_cycles = {max}: need min_cycles <= max_cycles"),
        );
    }
}

/// Most resonance peaks `[field_output]` may ask for (one VTU and one solve each).
pub const MAX_FIELD_PEAKS: usize = 20;

/// `[field_output]`: a few peaks, finite positive frequencies, a first-order mode and an
/// output to find the peaks of.
pub(super) fn field_output(c: &mut Checker, s: &SceneFile) {
    let Some(fo) = &s.field_output else { return };
    let root = KeyPath::root().key("field_output");
    if fo.peaks > MAX_FIELD_PEAKS {
        c.fail(
            root.key("peaks"),
            format!("at most {MAX_FIELD_PEAKS} (one solve and one file each)"),
        );
    }
    // With `model`, the deck's node outputs may be the outputs (checked on attaching).
    if fo.peaks > 0 && s.outputs.is_empty() && s.model.is_none() {
        c.fail(
            root.key("peaks"),
            "needs an [[outputs]] entry: the peaks are the first output's",
        );
    }
    for (i, &f) in fo.frequencies.iter().enumerate() {
        c.positive(root.key("frequencies").index(i), f);
    }
    if s.iteration.mode == Mode::HarmonicBalance {
        c.fail(
            root.clone(),
            "the fields are first order (solved in fast mode); the harmonic balance keeps only the contact directions: use mode fast or thesis",
        );
    }
}
