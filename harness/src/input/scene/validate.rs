//! Validation of a deserialized scene: every check names the key it is about.

use std::collections::{BTreeMap, BTreeSet};

use super::error::KeyPath;
use super::schema::*;

/// A failed check: where and why.
pub type Problem = (KeyPath, String);

/// Name of the implicit fixed body a mass body can rest on.
pub const GROUND: &str = "ground";

struct Checker {
    problems: Vec<Problem>,
}

impl Checker {
    fn fail(&mut self, path: KeyPath, msg: impl Into<String>) {
        self.problems.push((path, msg.into()));
    }

    fn finite(&mut self, path: KeyPath, v: f64) -> bool {
        if v.is_finite() {
            true
        } else {
            self.fail(path, format!("must be finite, got {v}"));
            false
        }
    }

    fn positive(&mut self, path: KeyPath, v: f64) {
        if self.finite(path.clone(), v) && v <= 0.0 {
            self.fail(path, format!("must be > 0, got {v}"));
        }
    }

    fn non_negative(&mut self, path: KeyPath, v: f64) {
        if self.finite(path.clone(), v) && v < 0.0 {
            self.fail(path, format!("must be >= 0, got {v}"));
        }
    }

    fn vec3(&mut self, path: KeyPath, v: &[f64; 3]) {
        for (i, x) in v.iter().enumerate() {
            self.finite(path.index(i), *x);
        }
    }

    fn direction(&mut self, path: KeyPath, v: &[f64; 3]) {
        self.vec3(path.clone(), v);
        let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(n > 0.0 && n.is_finite()) {
            self.fail(path, "direction must be a nonzero vector");
        }
    }

    fn require<T>(&mut self, path: KeyPath, v: &Option<T>, why: &str) -> bool {
        if v.is_none() {
            self.fail(path, format!("missing: required {why}"));
            false
        } else {
            true
        }
    }

    fn forbid<T>(&mut self, path: KeyPath, v: &Option<T>, why: &str) {
        if v.is_some() {
            self.fail(path, format!("not allowed {why}"));
        }
    }
}

/// Checks a scene; returns every problem found, in file order of the tables.
pub fn validate(s: &SceneFile) -> Vec<Problem> {
    let mut c = Checker {
        problems: Vec::new(),
    };
    let root = KeyPath::root();
    let u = root.key("units");
    for (k, v) in [
        ("length", &s.units.length),
        ("force", &s.units.force),
        ("time", &s.units.time),
        ("mass", &s.units.mass),
    ] {
        if v.trim().is_empty() {
            c.fail(u.key(k), "unit name must not be empty");
        }
    }

    for (name, m) in &s.materials {
        let p = root.key("materials").key(name);
        c.positive(p.key("E"), m.e);
        if c.finite(p.key("nu"), m.nu) && !(m.nu > -1.0 && m.nu < 0.5) {
            c.fail(p.key("nu"), format!("must be in (-1, 0.5), got {}", m.nu));
        }
        c.non_negative(p.key("rho"), m.rho);
        c.non_negative(p.key("rayleigh_alpha"), m.rayleigh_alpha);
        c.non_negative(p.key("rayleigh_beta"), m.rayleigh_beta);
    }

    let mut kinds: BTreeMap<&str, BodyKind> = BTreeMap::new();
    if s.bodies.is_empty() {
        c.fail(root.key("bodies"), "at least one body is needed");
    }
    for (i, b) in s.bodies.iter().enumerate() {
        let p = root.key("bodies").index(i);
        if b.name.is_empty() || b.name == GROUND {
            c.fail(
                p.key("name"),
                format!("body name must be non-empty and not `{GROUND}`"),
            );
        }
        if kinds.insert(&b.name, b.kind).is_some() {
            c.fail(p.key("name"), format!("duplicate body name `{}`", b.name));
        }
        match b.kind {
            BodyKind::Box => {
                let why = "for kind = \"box\"";
                if c.require(p.key("origin"), &b.origin, why) {
                    c.vec3(p.key("origin"), b.origin.as_ref().unwrap());
                }
                if let Some(size) = &b.size {
                    for (a, v) in size.iter().enumerate() {
                        c.positive(p.key("size").index(a), *v);
                    }
                } else {
                    c.require(p.key("size"), &b.size, why);
                }
                if let Some(d) = &b.divisions {
                    for (a, v) in d.iter().enumerate() {
                        if *v == 0 {
                            c.fail(p.key("divisions").index(a), "must be >= 1");
                        }
                    }
                } else {
                    c.require(p.key("divisions"), &b.divisions, why);
                }
                if let Some(g) = &b.grading {
                    for (name, a) in [("x", g.x), ("y", g.y), ("z", g.z)] {
                        if let Some(a) = a {
                            if !(a.ratio.is_finite() && a.ratio >= 1.0) {
                                c.fail(
                                    p.key("grading").key(name).key("ratio"),
                                    "must be finite and >= 1",
                                );
                            }
                        }
                    }
                }
                match &b.material {
                    Some(m) if !s.materials.contains_key(m) => c.fail(
                        p.key("material"),
                        format!("unknown material `{m}` (not in [materials])"),
                    ),
                    None => {
                        c.require(p.key("material"), &b.material, why);
                    }
                    _ => {}
                }
                c.forbid(p.key("position"), &b.position, why);
                c.forbid(p.key("mass"), &b.mass, why);
            }
            BodyKind::Mass => {
                let why = "for kind = \"mass\"";
                if c.require(p.key("position"), &b.position, why) {
                    c.vec3(p.key("position"), b.position.as_ref().unwrap());
                }
                match b.mass {
                    Some(m) => c.positive(p.key("mass"), m),
                    None => {
                        c.require(p.key("mass"), &b.mass, why);
                    }
                }
                c.forbid(p.key("origin"), &b.origin, why);
                c.forbid(p.key("size"), &b.size, why);
                c.forbid(p.key("divisions"), &b.divisions, why);
                c.forbid(p.key("grading"), &b.grading, why);
                c.forbid(p.key("material"), &b.material, why);
            }
        }
    }
    let body_kind = |name: &str| kinds.get(name).copied();
    let check_body = |c: &mut Checker, path: KeyPath, name: &str| -> Option<BodyKind> {
        let k = body_kind(name);
        if k.is_none() {
            c.fail(path, format!("unknown body `{name}`"));
        }
        k
    };

    let mut iface_names = BTreeSet::new();
    for (i, f) in s.interfaces.iter().enumerate() {
        let p = root.key("interfaces").index(i);
        if !iface_names.insert(f.name.as_str()) {
            c.fail(p.key("name"), format!("duplicate interface `{}`", f.name));
        }
        let [lo, hi] = &f.between;
        let hi_kind = check_body(&mut c, p.key("between").index(1), hi);
        if lo == GROUND {
            if hi_kind.is_some_and(|k| k != BodyKind::Mass) {
                c.fail(
                    p.key("between").index(0),
                    "`ground` can only be the lower side of a mass body",
                );
            }
        } else {
            let k = check_body(&mut c, p.key("between").index(0), lo);
            if k.is_some() && (k != Some(BodyKind::Box) || hi_kind != Some(BodyKind::Box)) {
                c.fail(
                    p.key("between"),
                    "an interface joins two boxes, or `ground` and a mass body",
                );
            }
        }
        if lo == hi {
            c.fail(p.key("between"), "an interface needs two different bodies");
        }
        let lumped = lo == GROUND;
        c.non_negative(p.key("mu"), f.mu);
        c.positive(p.key("k_t0_per_area"), f.k_t0_per_area);
        if let Some(k) = f.normal_stiffness_per_area {
            c.positive(p.key("normal_stiffness_per_area"), k);
        }
        match f.normal_law {
            NormalLawName::Linear => {
                c.require(
                    p.key("normal_stiffness_per_area"),
                    &f.normal_stiffness_per_area,
                    "for normal_law = \"linear\"",
                );
                c.forbid(
                    p.key("hertz_radius"),
                    &f.hertz_radius,
                    "for normal_law = \"linear\"",
                );
            }
            NormalLawName::Hertz => {
                if c.require(
                    p.key("hertz_radius"),
                    &f.hertz_radius,
                    "for normal_law = \"hertz\"",
                ) {
                    c.positive(p.key("hertz_radius"), f.hertz_radius.unwrap());
                }
                if c.require(
                    p.key("hertz_e_star"),
                    &f.hertz_e_star,
                    "for normal_law = \"hertz\"",
                ) {
                    c.positive(p.key("hertz_e_star"), f.hertz_e_star.unwrap());
                }
                if !s.effects.normal_contact_nonlinearity {
                    c.require(
                        p.key("normal_stiffness_per_area"),
                        &f.normal_stiffness_per_area,
                        "when effects.normal_contact_nonlinearity = false",
                    );
                }
            }
        }
        if c.finite(p.key("initial_gap"), f.initial_gap) && f.initial_gap < 0.0 {
            c.fail(
                p.key("initial_gap"),
                format!("must be >= 0, got {}", f.initial_gap),
            );
        }
        for (k, r) in f.exclude.iter().enumerate() {
            let rp = p.key("exclude").index(k);
            c.vec3(rp.key("min"), &r.min);
            c.vec3(rp.key("max"), &r.max);
            if (0..3).any(|a| r.max[a] < r.min[a]) {
                c.fail(rp.key("max"), "must be >= min in every component");
            }
        }
        if lumped && !f.exclude.is_empty() {
            c.fail(p.key("exclude"), "only for box interfaces");
        }
        if let Some(n) = f.area_samples {
            if lumped {
                c.fail(p.key("area_samples"), "only for box interfaces");
            } else if !(1..=MAX_AREA_SAMPLES).contains(&n) {
                c.fail(
                    p.key("area_samples"),
                    format!("must be 1 ..= {MAX_AREA_SAMPLES}, got {n}"),
                );
            }
            if s.iteration.mode != Mode::Fast {
                c.fail(
                    p.key("area_samples"),
                    "needs [iteration] mode = \"fast\" (the other modes evaluate each point at its node)",
                );
            }
        }
        if lumped {
            match f.area {
                Some(a) => c.positive(p.key("area"), a),
                None => {
                    c.require(p.key("area"), &f.area, "for a ground-mass interface");
                }
            }
        } else {
            c.forbid(
                p.key("area"),
                &f.area,
                "for box interfaces (tributary areas are used)",
            );
        }
    }

    for (i, t) in s.ties.iter().enumerate() {
        let p = root.key("ties").index(i);
        let [a, b] = &t.between;
        let ka = check_body(&mut c, p.key("between").index(0), a);
        let kb = check_body(&mut c, p.key("between").index(1), b);
        if ka == Some(BodyKind::Mass) || kb == Some(BodyKind::Mass) {
            c.fail(p.key("between"), "a tie joins two boxes");
        }
        if a == b {
            c.fail(p.key("between"), "a tie needs two different bodies");
        }
    }

    let mut screw_names = BTreeSet::new();
    for (i, sc) in s.screws.iter().enumerate() {
        let p = root.key("screws").index(i);
        if !screw_names.insert(sc.name.as_str()) {
            c.fail(p.key("name"), format!("duplicate screw `{}`", sc.name));
        }
        c.non_negative(p.key("torque"), sc.torque);
        c.positive(p.key("pitch"), sc.pitch);
        c.positive(p.key("d2"), sc.d2);
        c.non_negative(p.key("mu_thread"), sc.mu_thread);
        c.non_negative(p.key("mu_head"), sc.mu_head);
        c.non_negative(p.key("d_km"), sc.d_km);
        if c.finite(p.key("share"), sc.share) && !(sc.share > 0.0 && sc.share <= 1.0) {
            c.fail(
                p.key("share"),
                format!("must be in (0, 1], got {}", sc.share),
            );
        }
        for (k, bp) in [("head", &sc.head), ("nut", &sc.nut)] {
            check_body(&mut c, p.key(k).key("body"), &bp.body);
            c.vec3(p.key(k).key("at"), &bp.at);
        }
        c.direction(p.key("direction"), &sc.direction);
    }

    for (i, l) in s.preload.iter().enumerate() {
        let p = root.key("preload").index(i);
        let kind = check_body(&mut c, p.key("body"), &l.body);
        match l.kind {
            PreloadKind::Pressure => {
                let why = "for kind = \"pressure\"";
                if kind == Some(BodyKind::Mass) {
                    c.fail(p.key("kind"), "a pressure needs a box body");
                }
                c.require(p.key("face"), &l.face, why);
                if c.require(p.key("pressure"), &l.pressure, why) {
                    c.finite(p.key("pressure"), l.pressure.unwrap());
                }
                c.forbid(p.key("force"), &l.force, why);
                c.forbid(p.key("at"), &l.at, why);
            }
            PreloadKind::Force => {
                let why = "for kind = \"force\"";
                if kind == Some(BodyKind::Box) && c.require(p.key("at"), &l.at, why) {
                    c.vec3(p.key("at"), l.at.as_ref().unwrap());
                }
                if c.require(p.key("force"), &l.force, why) {
                    c.vec3(p.key("force"), l.force.as_ref().unwrap());
                }
                c.forbid(p.key("face"), &l.face, why);
                c.forbid(p.key("pressure"), &l.pressure, why);
            }
        }
    }

    for (i, cl) in s.clamp.iter().enumerate() {
        let p = root.key("clamp").index(i);
        match check_body(&mut c, p.key("body"), &cl.body) {
            Some(BodyKind::Box) => {
                c.require(p.key("face"), &cl.face, "for a box body");
            }
            Some(BodyKind::Mass) => c.forbid(p.key("face"), &cl.face, "for a mass body"),
            None => {}
        }
    }

    let mut joint_names = BTreeSet::new();
    for (i, j) in s.joints.iter().enumerate() {
        let p = root.key("joints").index(i);
        if !joint_names.insert(j.name.as_str()) {
            c.fail(p.key("name"), format!("duplicate joint `{}`", j.name));
        }
        lumped_ends(&mut c, p.key("between"), &j.between, &body_kind);
        c.direction(p.key("direction"), &j.direction);
        if j.direction.iter().filter(|v| **v != 0.0).count() > 1 {
            c.fail(
                p.key("direction"),
                "must be a coordinate axis, e.g. [1, 0, 0]",
            );
        }
        c.positive(p.key("mu"), j.mu);
        c.positive(p.key("normal_force"), j.normal_force);
        c.positive(p.key("k_t0"), j.k_t0);
    }

    for (i, sp) in s.springs.iter().enumerate() {
        let p = root.key("springs").index(i);
        if let Some(ends) = &sp.between {
            if !sp.body.is_empty() {
                c.fail(p.key("body"), "not allowed with `between`");
            }
            lumped_ends(&mut c, p.key("between"), ends, &body_kind);
        } else if check_body(&mut c, p.key("body"), &sp.body) == Some(BodyKind::Box) {
            c.fail(p.key("body"), "springs attach to mass bodies");
        }
        c.direction(p.key("direction"), &sp.direction);
        c.non_negative(p.key("stiffness"), sp.stiffness);
        c.finite(p.key("cubic"), sp.cubic);
        c.non_negative(p.key("damping"), sp.damping);
        // The first-order balance linearizes the cubic term about x = 0: a static
        // preload would move the operating point, which the static step (linear springs)
        // does not follow.
        if sp.cubic != 0.0 && s.iteration.mode == Mode::HarmonicBalance {
            c.fail(
                p.key("cubic"),
                "cubic springs are linearized to first order: use mode \"fast\" or \"thesis\"",
            );
        }
        // A preload across the spring (e.g. the normal load of a friction contact under
        // the mass) leaves its elongation at zero; one with a component along it would not.
        let along = |l: &PreloadSpec| {
            l.force
                .is_none_or(|f| f.iter().zip(&sp.direction).any(|(a, b)| a * b != 0.0))
        };
        if sp.cubic != 0.0 && s.preload.iter().any(|l| l.body == sp.body && along(l)) {
            c.fail(
                p.key("cubic"),
                format!(
                    "a cubic spring is linearized about zero static elongation: body `{}` must carry no preload along the spring",
                    sp.body
                ),
            );
        }
    }

    if s.excitation.is_empty() {
        c.fail(root.key("excitation"), "at least one excitation is needed");
    }
    for (i, e) in s.excitation.iter().enumerate() {
        let p = root.key("excitation").index(i);
        let kind = check_body(&mut c, p.key("body"), &e.body);
        match e.kind {
            ExcitationKind::Point => {
                if kind == Some(BodyKind::Box)
                    && c.require(p.key("at"), &e.at, "for a point force on a box")
                {
                    c.vec3(p.key("at"), e.at.as_ref().unwrap());
                }
                c.forbid(p.key("face"), &e.face, "for kind = \"point\"");
            }
            ExcitationKind::Face => {
                if kind == Some(BodyKind::Mass) {
                    c.fail(p.key("kind"), "a face excitation needs a box body");
                }
                c.require(p.key("face"), &e.face, "for kind = \"face\"");
                c.forbid(p.key("at"), &e.at, "for kind = \"face\"");
            }
        }
        c.direction(p.key("direction"), &e.direction);
        c.finite(p.key("amplitude"), e.amplitude);
        c.finite(p.key("phase_deg"), e.phase_deg);
    }

    let sw = root.key("sweep");
    c.positive(sw.key("f_min"), s.sweep.f_min);
    c.positive(sw.key("f_max"), s.sweep.f_max);
    if s.sweep.count == 0 {
        c.fail(sw.key("count"), "must be >= 1");
    }
    if s.sweep.f_max < s.sweep.f_min || (s.sweep.count > 1 && s.sweep.f_max == s.sweep.f_min) {
        c.fail(
            sw.key("f_max"),
            "must be > f_min (or equal to it with count = 1)",
        );
    }

    for (i, b) in s.sweep.refine.iter().enumerate() {
        let bp = sw.key("refine").index(i);
        c.positive(bp.key("f_min"), b.f_min);
        c.positive(bp.key("f_max"), b.f_max);
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

    let it = root.key("iteration");
    let tol = s.iteration.tolerance;
    if !(tol > 0.0 && tol < 1.0) {
        c.fail(it.key("tolerance"), format!("must be in (0, 1), got {tol}"));
    }
    if s.iteration.max_passes == 0 {
        c.fail(it.key("max_passes"), "must be >= 1");
    }
    c.positive(it.key("initial_amplitude"), s.iteration.initial_amplitude);
    harmonic_balance(&mut c, s);

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
        match check_body(&mut c, p.key("body"), &o.body) {
            Some(BodyKind::Box) if c.require(p.key("at"), &o.at, "for an output on a box") => {
                c.vec3(p.key("at"), o.at.as_ref().unwrap());
            }
            Some(BodyKind::Mass) => c.forbid(p.key("at"), &o.at, "for a mass body"),
            _ => {}
        }
        c.direction(p.key("direction"), &o.direction);
    }

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
    }
    super::model_file::adjust(s, c.problems)
}

/// Most harmonics and samples per period a scene may ask for (H = 64 is far past where
/// the rungs have converged on any scene here; N bounds the march's memory and time).
pub const MAX_HARMONICS: usize = 64;
/// Most sub-grid samples per quarter face and direction (`area_samples`).
pub const MAX_AREA_SAMPLES: usize = 32;
pub const MAX_SAMPLES: usize = 1 << 16;

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

/// The two ends of a lumped element: mass bodies or `"ground"`, not the same twice.
fn lumped_ends(
    c: &mut Checker,
    path: KeyPath,
    ends: &[String; 2],
    kind: &dyn Fn(&str) -> Option<BodyKind>,
) {
    for (k, e) in ends.iter().enumerate() {
        if e == GROUND {
            continue;
        }
        match kind(e) {
            Some(BodyKind::Mass) => {}
            Some(BodyKind::Box) => c.fail(path.index(k), "must be a mass body or \"ground\""),
            None => c.fail(path.index(k), format!("unknown body `{e}`")),
        }
    }
    if ends[0] == ends[1] {
        c.fail(path, "the two ends must differ");
    }
}
