//! The unit names a scene's `[units]` or a deck's units comment may state, each with its
//! value in SI, so that a stated system is checked: every name known, and the mass unit
//! equal to force·time²/length (the only consistent choice: t with N, mm, s; kg with N,
//! m, s). With the values known, material constants far outside those of solids are
//! flagged: the most common unit slip, a density in kg/m³ in an N-mm-t model, gives a
//! first mode near 0.001 Hz and no error.

use super::Units;

/// What a unit measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    Length,
    Force,
    Time,
    Mass,
}

/// (name, value in m, N, s or kg).
const LENGTHS: &[(&str, f64)] = &[
    ("m", 1.0),
    ("dm", 0.1),
    ("cm", 1e-2),
    ("mm", 1e-3),
    ("um", 1e-6),
    ("µm", 1e-6),
    ("μm", 1e-6),
    ("nm", 1e-9),
    ("km", 1e3),
    ("in", 0.0254),
    ("ft", 0.3048),
];
const FORCES: &[(&str, f64)] = &[
    ("N", 1.0),
    ("mN", 1e-3),
    ("uN", 1e-6),
    ("µN", 1e-6),
    ("μN", 1e-6),
    ("kN", 1e3),
    ("MN", 1e6),
    ("lbf", 4.448_221_615_260_5),
    ("kip", 4_448.221_615_260_5),
];
const TIMES: &[(&str, f64)] = &[
    ("s", 1.0),
    ("ms", 1e-3),
    ("us", 1e-6),
    ("µs", 1e-6),
    ("μs", 1e-6),
    ("min", 60.0),
    ("h", 3600.0),
];
const MASSES: &[(&str, f64)] = &[
    ("kg", 1.0),
    ("g", 1e-3),
    ("mg", 1e-6),
    ("t", 1e3),
    ("tonne", 1e3),
    ("Mg", 1e3),
    ("lb", 0.453_592_37),
    ("slug", 14.593_902_937_206_4),
    // lbf·s²/in, the mass unit of lbf-in-s models.
    ("lbf*s^2/in", 175.126_835_246_476_6),
];

/// Densities of solids, kg/m³ (aerogels excepted, osmium included with room).
const DENSITY_SI: (f64, f64) = (10.0, 1e5);
/// Young's moduli of solids, Pa (soft foams to diamond, with room).
const MODULUS_SI: (f64, f64) = (1e4, 1e13);

fn table(q: Quantity) -> &'static [(&'static str, f64)] {
    match q {
        Quantity::Length => LENGTHS,
        Quantity::Force => FORCES,
        Quantity::Time => TIMES,
        Quantity::Mass => MASSES,
    }
}

/// The SI value of unit `name` of quantity `q`, if the name is known.
pub fn si(q: Quantity, name: &str) -> Option<f64> {
    table(q)
        .iter()
        .find(|(n, _)| *n == name.trim())
        .map(|(_, v)| *v)
}

/// The known names of quantity `q`, for messages.
pub fn names(q: Quantity) -> String {
    table(q)
        .iter()
        .map(|(n, _)| format!("\"{n}\""))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What is wrong with a stated unit system, as (key, message): a name not known, or a
/// mass unit other than force·time²/length.
pub fn problems(u: &Units) -> Vec<(&'static str, String)> {
    let mut out = Vec::new();
    let mut value = |key: &'static str, q: Quantity, name: &str| {
        let v = si(q, name);
        if v.is_none() {
            out.push((key, format!("unknown unit \"{name}\": one of {}", names(q))));
        }
        v
    };
    let l = value("length", Quantity::Length, &u.length);
    let f = value("force", Quantity::Force, &u.force);
    let t = value("time", Quantity::Time, &u.time);
    let m = value("mass", Quantity::Mass, &u.mass);
    if let (Some(l), Some(f), Some(t), Some(m)) = (l, f, t, m) {
        let implied = f * t * t / l;
        if (m / implied - 1.0).abs() > 1e-6 {
            let fits: Vec<String> = MASSES
                .iter()
                .filter(|(_, v)| (v / implied - 1.0).abs() <= 1e-6)
                .map(|(n, _)| format!("\"{n}\""))
                .collect();
            let named = if fits.is_empty() {
                String::new()
            } else {
                format!(" ({})", fits.join(" or "))
            };
            out.push((
                "mass",
                format!(
                    "\"{}\" is not force·time²/length: {}·{}²/{} = {implied:e} kg{named}; with it the masses and the forces disagree",
                    u.mass, u.force, u.time, u.length
                ),
            ));
        }
    }
    out
}

/// A note when material `name`'s E (force/length²) or ρ (mass/length³) lies far outside
/// those of solids in the stated units (nothing when a unit is not known).
pub fn implausible_material(u: &Units, name: &str, e: f64, rho: f64) -> Option<String> {
    let l = si(Quantity::Length, &u.length)?;
    let f = si(Quantity::Force, &u.force)?;
    let m = si(Quantity::Mass, &u.mass)?;
    let rho_si = rho * m / (l * l * l);
    let e_si = e * f / (l * l);
    let mut notes = Vec::new();
    if rho > 0.0 && !(DENSITY_SI.0..=DENSITY_SI.1).contains(&rho_si) {
        notes.push(format!(
            "density {rho:e} {}/{}³ is {rho_si:.3e} kg/m³, outside {:e}…{:e} kg/m³ of solids (steel 7850 kg/m³ is {:.3e} {}/{}³)",
            u.mass,
            u.length,
            DENSITY_SI.0,
            DENSITY_SI.1,
            7850.0 * l * l * l / m,
            u.mass,
            u.length
        ));
    }
    if !(MODULUS_SI.0..=MODULUS_SI.1).contains(&e_si) {
        notes.push(format!(
            "E = {e:e} {}/{}² is {e_si:.3e} Pa, outside {:e}…{:e} Pa of solids (steel 210 GPa is {:.3e} {}/{}²)",
            u.force,
            u.length,
            MODULUS_SI.0,
            MODULUS_SI.1,
            2.1e11 * l * l / f,
            u.force,
            u.length
        ));
    }
    (!notes.is_empty()).then(|| {
        format!(
            "material {name}: {}: are the units right?",
            notes.join("; ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn units(l: &str, f: &str, t: &str, m: &str) -> Units {
        Units {
            length: l.into(),
            force: f.into(),
            time: t.into(),
            mass: m.into(),
            frequency: None,
        }
    }

    #[test]
    fn consistent_systems_pass_and_others_are_named() {
        for (l, f, t, m) in [
            ("mm", "N", "s", "t"),
            ("m", "N", "s", "kg"),
            ("mm", "kN", "ms", "kg"),
            ("in", "lbf", "s", "lbf*s^2/in"),
            ("ft", "lbf", "s", "slug"),
        ] {
            assert!(problems(&units(l, f, t, m)).is_empty(), "{l} {f} {t} {m}");
        }
        let p = problems(&units("mm", "N", "s", "kg"));
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].0, "mass");
        assert!(
            p[0].1.contains("1e3 kg (\"t\" or \"tonne\" or \"Mg\")"),
            "{}",
            p[0].1
        );
        let p = problems(&units("millimetre", "N", "s", "t"));
        assert_eq!(p[0].0, "length");
        assert!(p[0].1.contains("unknown unit \"millimetre\""), "{}", p[0].1);
    }

    #[test]
    fn a_density_in_kg_per_m3_in_an_n_mm_t_model_is_flagged() {
        let u = units("mm", "N", "s", "t");
        assert!(implausible_material(&u, "STEEL", 210000.0, 7.85e-9).is_none());
        let note = implausible_material(&u, "STEEL", 210000.0, 7850.0).unwrap();
        assert!(
            note.contains("7.850e15 kg/m³") && note.contains("7.850e-9 t/mm³"),
            "{note}"
        );
        let note = implausible_material(&u, "STEEL", 2.1e11, 7.85e-9).unwrap();
        assert!(note.contains("E = 2.1e11 N/mm²"), "{note}");
        // Units not known: nothing to judge.
        assert!(
            implausible_material(&units("deck length", "N", "s", "t"), "X", 1.0, 1.0).is_none()
        );
    }
}
