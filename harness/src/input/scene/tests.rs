//! Scene parsing and validation: a valid scene round-trips; bad ones name file, line
//! and key.

use super::*;

pub(crate) const GOOD: &str = r#"
title = "two plates"
[units]
length = "mm"
force = "N"
time = "s"
mass = "t"

[materials.steel]
E = 210000.0
nu = 0.3
rho = 7.85e-9

[[bodies]]
name = "lower"
kind = "box"
origin = [0.0, 0.0, 0.0]
size = [20.0, 5.0, 1.0]
divisions = [4, 1, 1]
material = "steel"

[[bodies]]
name = "upper"
kind = "box"
origin = [0.0, 0.0, 1.0]
size = [20.0, 5.0, 1.0]
divisions = [4, 1, 1]
material = "steel"

[[interfaces]]
name = "joint"
between = ["lower", "upper"]
law = "mindlin"
mu = 0.3
k_t0_per_area = 1e4
normal_law = "linear"
normal_stiffness_per_area = 1e5

[[clamp]]
body = "lower"
face = "x_min"

[[excitation]]
kind = "point"
body = "upper"
at = [20.0, 2.5, 2.0]
direction = [0.0, 0.0, 1.0]
amplitude = 1.0

[sweep]
f_min = 100.0
f_max = 200.0
count = 3

[[outputs]]
name = "tip"
body = "upper"
at = [20.0, 2.5, 2.0]
direction = [0.0, 0.0, 1.0]
"#;

fn err(text: &str) -> SceneError {
    Scene::parse("bad.toml", text).unwrap_err()
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).unwrap() + 1
}

#[test]
fn good_scene_parses_with_defaults() {
    let s = Scene::parse("good.toml", GOOD).unwrap();
    assert_eq!(s.spec.bodies.len(), 2);
    assert_eq!(s.spec.iteration.mode, Mode::Fast);
    assert!(s.spec.effects.contact_damping && !s.spec.effects.point_energy_output);
    assert_eq!(s.frequencies(), vec![100.0, 150.0, 200.0]);
}

#[test]
fn type_error_names_line_and_key() {
    let text = GOOD.replace("nu = 0.3", "nu = \"soft\"");
    let e = err(&text);
    assert_eq!(e.file, "bad.toml");
    assert_eq!(e.line, line_of(&text, "nu = \"soft\""));
    assert_eq!(e.key, "materials.steel.nu");
    assert!(e.to_string().starts_with(&format!("bad.toml:{}:", e.line)));
}

#[test]
fn unknown_and_missing_keys_are_named() {
    let text = GOOD.replace("count = 3", "count = 3\ncuont = 4");
    let e = err(&text);
    assert!(e.message.contains("cuont"), "{e}");
    assert_eq!(e.key, "sweep.cuont");
    assert_eq!(e.line, line_of(&text, "cuont"));
    let text = GOOD.replace("mu = 0.3\n", "");
    let e = err(&text);
    assert_eq!(e.key, "interfaces[0].mu", "{e}");
    assert_eq!(e.line, line_of(&text, "[[interfaces]]"));
}

#[test]
fn validation_errors_point_at_the_value() {
    let text = GOOD.replace(
        "size = [20.0, 5.0, 1.0]\ndivisions = [4, 1, 1]\nmaterial = \"steel\"\n\n[[interfaces]]",
        "size = [20.0, -5.0, 1.0]\ndivisions = [4, 1, 1]\nmaterial = \"steel\"\n\n[[interfaces]]",
    );
    let e = err(&text);
    assert_eq!(e.key, "bodies[1].size[1]");
    assert_eq!(e.line, line_of(&text, "-5.0"));
    let text = GOOD.replace(
        "material = \"steel\"\n\n[[bodies]]",
        "material = \"stel\"\n\n[[bodies]]",
    );
    let e = err(&text);
    assert_eq!(e.key, "bodies[0].material");
    assert!(e.message.contains("stel"));
    assert_eq!(e.line, line_of(&text, "\"stel\""));
    let text = GOOD.replace(
        "between = [\"lower\", \"upper\"]",
        "between = [\"lower\", \"top\"]",
    );
    let e = err(&text);
    assert_eq!(e.key, "interfaces[0].between[1]");
    let text = GOOD.replace("f_max = 200.0", "f_max = 50.0");
    assert_eq!(err(&text).key, "sweep.f_max");
    let text = GOOD.replacen(
        "divisions = [4, 1, 1]\n",
        "divisions = [4, 1, 1]\ngrading = { x = { ratio = 0.5, toward = \"min\" } }\n",
        1,
    );
    let e = err(&text);
    assert_eq!(e.key, "bodies[0].grading.x.ratio", "{e}");
    assert_eq!(e.line, line_of(&text, "grading"));
}

#[test]
fn syntax_error_has_a_line() {
    let text = GOOD.replace("count = 3", "count = = 3");
    let e = err(&text);
    assert_eq!(e.line, line_of(&text, "count = = 3"));
}

#[test]
fn log_spacing() {
    let text = GOOD.replace("count = 3", "count = 3\nspacing = \"log\"");
    let f = Scene::parse("x", &text).unwrap().frequencies();
    approx::assert_relative_eq!(f[1], (100.0f64 * 200.0).sqrt(), max_relative = 1e-14);
}

/// Abaqus's steady-state bias p: y = −1 … 1 evenly, points at ½(f₁ + f₂) + ½(f₂ − f₁)
/// sign(y)|y|^{1/p}; p = 3 over 100 … 200 Hz with 5 points: 100, 150 − 50·0.5^{1/3}, 150,
/// 150 + 50·0.5^{1/3}, 200 (denser toward the ends). In bands too; p ≤ 0 is named.
#[test]
fn biased_points_crowd_toward_both_ends() {
    let text = GOOD.replace("count = 3", "count = 5\nbias = 3.0");
    let f = Scene::parse("x", &text).unwrap().frequencies();
    let d = 50.0 * 0.5f64.powf(1.0 / 3.0);
    let want = [100.0, 150.0 - d, 150.0, 150.0 + d, 200.0];
    for (g, w) in f.iter().zip(want) {
        approx::assert_relative_eq!(*g, w, max_relative = 1e-15);
    }
    assert_eq!(f.len(), 5);
    let band = GOOD.replace(
        "count = 3",
        "count = 3\nrefine = [{ f_min = 160.0, f_max = 180.0, count = 5, bias = 3.0 }]",
    );
    let f = Scene::parse("x", &band).unwrap().frequencies();
    // 100, 150, then the band 160, 170 − 10·0.5^{1/3}, 170, …, then 200.
    approx::assert_relative_eq!(
        f[3],
        170.0 - 10.0 * 0.5f64.powf(1.0 / 3.0),
        max_relative = 1e-15
    );
    assert_eq!(
        err(&text.replace("bias = 3.0", "bias = 0.0")).key,
        "sweep.bias"
    );
    assert_eq!(
        err(&band.replace("bias = 3.0", "bias = -1.0")).key,
        "sweep.refine[0].bias"
    );
}

#[test]
fn refine_bands_merge_sorted() {
    let text = GOOD.replace(
        "count = 3",
        "count = 3\nrefine = [{ f_min = 140.0, f_max = 160.0, count = 3 }]",
    );
    let f = Scene::parse("x", &text).unwrap().frequencies();
    assert_eq!(f, vec![100.0, 140.0, 150.0, 160.0, 200.0]);
    let bad = GOOD.replace(
        "count = 3",
        "count = 3\nrefine = [{ f_min = 140.0, f_max = 130.0, count = 3 }]",
    );
    assert_eq!(err(&bad).key, "sweep.refine[0].f_max");
    // One exact frequency: count = 1 with f_max = f_min; count = 1 over a band is an error.
    let one = GOOD.replace(
        "count = 3",
        "count = 3\nrefine = [{ f_min = 123.456789, f_max = 123.456789, count = 1 }]",
    );
    let f = Scene::parse("x", &one).unwrap().frequencies();
    assert_eq!(f, vec![100.0, 123.456789, 150.0, 200.0]);
    let bad = one.replace("f_max = 123.456789", "f_max = 124.0");
    assert_eq!(err(&bad).key, "sweep.refine[0].count");
}

#[test]
fn harmonic_balance_keys_are_validated() {
    let hb = |extra: &str| {
        GOOD.replace(
            "count = 3\n",
            &format!("count = 3\n\n[iteration]\nmode = \"harmonic_balance\"\n{extra}"),
        )
    };
    let s = Scene::parse("x", &hb("harmonics = 7\nsamples = 128\n")).unwrap();
    assert_eq!(s.spec.iteration.mode, Mode::HarmonicBalance);
    assert_eq!(
        (s.spec.iteration.harmonics, s.spec.iteration.samples),
        (Some(7), Some(128))
    );
    // Missing H: named at the table.
    let e = err(&hb(""));
    assert_eq!(e.key, "iteration.harmonics", "{e}");
    assert_eq!(e.line, line_of(&hb(""), "[iteration]"));
    // Out of range H and N, each at its value.
    for (text, key, value) in [
        (
            hb("harmonics = 0\n"),
            "iteration.harmonics",
            "harmonics = 0",
        ),
        (
            hb("harmonics = 65\n"),
            "iteration.harmonics",
            "harmonics = 65",
        ),
        (
            hb("harmonics = 7\nsamples = 15\n"),
            "iteration.samples",
            "samples = 15",
        ),
    ] {
        let e = err(&text);
        assert_eq!(e.key, key, "{e}");
        assert_eq!(e.line, line_of(&text, value), "{e}");
    }
    // Harmonics without the mode.
    let text = GOOD.replace("count = 3\n", "count = 3\n\n[iteration]\nharmonics = 3\n");
    let e = err(&text);
    assert_eq!(e.key, "iteration.harmonics");
    assert!(e.message.contains("harmonic_balance"), "{e}");
    // Effects the balance cannot switch off.
    let text = hb("harmonics = 3\n\n[effects]\ncontact_damping = false\n");
    let e = err(&text);
    assert_eq!(e.key, "effects.contact_damping", "{e}");
    assert_eq!(e.line, line_of(&text, "contact_damping = false"));
}

#[test]
fn cubic_spring_keys_are_validated() {
    let path = format!(
        "{}/../scenes/duffing-point.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let good = std::fs::read_to_string(path).unwrap();
    assert!(Scene::parse("duffing-point.toml", &good).is_ok());
    // A preload on the body of a cubic spring: its linearization about x = 0 would be
    // wrong; the error points at the cubic key.
    let text = format!(
        "{good}\n[[preload]]\nkind = \"force\"\nbody = \"mass\"\nforce = [1.0, 0.0, 0.0]\n"
    );
    let e = Scene::parse("d.toml", &text).unwrap_err();
    assert_eq!(e.key, "springs[0].cubic");
    assert_eq!(e.line, line_of(&text, "cubic = 40.0"));
    assert!(e.message.contains("no preload along"), "{}", e.message);
    // A preload across the spring (a contact's normal load) is allowed.
    let across = text.replace("force = [1.0, 0.0, 0.0]", "force = [0.0, 0.0, -1.0]");
    assert!(Scene::parse("d.toml", &across).is_ok());
    // The harmonic-balance mode has no cubic springs.
    let text = good.replace("mode = \"fast\"", "mode = \"harmonic_balance\"");
    let e = Scene::parse("d.toml", &text).unwrap_err();
    assert_eq!(e.key, "springs[0].cubic");
    // Unknown sweep direction: a type error naming the key's line.
    let text = good.replace("count = 1\n", "count = 1\ndirection = \"sideways\"\n");
    let e = Scene::parse("d.toml", &text).unwrap_err();
    assert_eq!(e.line, line_of(&text, "sideways"));
}

#[test]
fn area_samples_are_validated() {
    let with = |v: &str| {
        GOOD.replace(
            "normal_stiffness_per_area = 1e5\n",
            &format!("normal_stiffness_per_area = 1e5\narea_samples = {v}\n"),
        )
    };
    let s = Scene::parse("x", &with("4")).unwrap();
    assert_eq!(s.spec.interfaces[0].area_samples, Some(4));
    for bad in ["0", "33"] {
        let text = with(bad);
        let e = err(&text);
        assert_eq!(e.key, "interfaces[0].area_samples", "{e}");
        assert_eq!(e.line, line_of(&text, &format!("area_samples = {bad}")));
    }
    // Only the fast mode samples the area.
    let thesis = with("4").replace(
        "count = 3\n",
        "count = 3\n\n[iteration]\nmode = \"thesis\"\n",
    );
    let e = err(&thesis);
    assert_eq!(e.key, "interfaces[0].area_samples", "{e}");
    assert!(e.message.contains("fast"), "{e}");
}

#[test]
fn matrices_tables_are_validated() {
    let text = |extra: &str, name: &str| {
        format!(
            "[units]\nlength = \"mm\"\nforce = \"N\"\ntime = \"s\"\nmass = \"t\"\n\
             [[matrices]]\nname = \"{name}\"\nmass = \"M.mtx\"\nstiffness = \"K.mtx\"\ndofs = [\"tip,x\", \"modal,1\"]\n{extra}\
             [[joints]]\nname = \"j\"\nbetween = [\"{name}.tip\", \"ground\"]\ndirection = [1.0, 0.0, 0.0]\n\
             law = \"jenkins\"\nmu = 1.0\nnormal_force = 1.0\nk_t0 = 1.0\n\
             [[excitation]]\nkind = \"point\"\nbody = \"{name}.tip\"\ndirection = [1.0, 0.0, 0.0]\namplitude = 1.0\n\
             [sweep]\nf_min = 1.0\nf_max = 2.0\ncount = 3\n\
             [[outputs]]\nname = \"tip\"\nbody = \"{name}.tip\"\ndirection = [1.0, 0.0, 0.0]\n"
        )
    };
    // Points `<name>.<point>` stand where mass bodies do; no [[bodies]] needed.
    let s = Scene::parse("m.toml", &text("", "beam")).unwrap();
    assert_eq!(
        s.spec.matrices[0].dofs,
        DofsSpec::Inline(vec!["tip,x".into(), "modal,1".into()])
    );
    let e = err(&text("", "ground"));
    assert_eq!(e.key, "matrices[0].name", "{}", e.message);
    let e = err(&text("", "be.am"));
    assert_eq!(e.key, "matrices[0].name", "{}", e.message);
    let other =
        text("", "beam").replace("[\"beam.tip\", \"ground\"]", "[\"other.tip\", \"ground\"]");
    let e = err(&other);
    assert_eq!(e.key, "joints[0].between[0]", "{}", e.message);
    // A matrix model joins lumped parts only.
    let boxed = text(
        "[materials.steel]\nE = 2e5\nnu = 0.3\nrho = 7.85e-9\n[[bodies]]\nname = \"b\"\nkind = \"box\"\n\
         origin = [0.0, 0.0, 0.0]\nsize = [1.0, 1.0, 1.0]\ndivisions = [1, 1, 1]\nmaterial = \"steel\"\n",
        "beam",
    );
    let e = err(&boxed);
    assert_eq!(e.key, "matrices[0]", "{}", e.message);
}

#[test]
fn lumped_elements_beside_fe_bodies_are_refused_at_the_first() {
    let mass =
        "\n[[bodies]]\nname = \"m\"\nkind = \"mass\"\nposition = [0.0, 0.0, 5.0]\nmass = 1.0\n";
    let joint = "\n[[joints]]\nname = \"j\"\nbetween = [\"ground\", \"m\"]\ndirection = [1.0, 0.0, 0.0]\nlaw = \"jenkins\"\nrule = \"masing\"\nmu = 1.0\nnormal_force = 0.1\nk_t0 = 2.0\n";
    let text = format!("{GOOD}{mass}{joint}");
    let e = err(&text);
    assert_eq!(e.key, "joints[0]", "{e}");
    assert_eq!(e.line, line_of(&text, "[[joints]]"));
    assert!(e.message.contains("make a lumped system"), "{e}");
    let spring = "\n[[springs]]\nbetween = [\"ground\", \"m\"]\ndirection = [1.0, 0.0, 0.0]\nstiffness = 1.0\n";
    let text = format!("{GOOD}{mass}{spring}");
    let e = err(&text);
    assert_eq!(e.key, "springs[0].between", "{e}");
    assert!(e.message.contains("make a lumped system"), "{e}");
}
