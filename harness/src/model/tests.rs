//! Scene → problem: counts, load resultants, damping, lumped masses.

use super::*;
use crate::input::scene::Scene;

fn good() -> Scene {
    Scene::parse("good.toml", crate::input::scene::tests::GOOD).unwrap()
}

#[test]
fn two_plates_build() {
    let p = build(&good()).unwrap();
    // 5×2 interface nodes; only the lower plate is clamped, so every pair can move.
    assert_eq!(p.contacts.len(), 10);
    let area: f64 = p.contacts.iter().map(|c| c.area).sum();
    approx::assert_relative_eq!(area, 100.0, max_relative = 1e-14);
    // Relative normal displacement row: +1 on the upper node's z, −1 on the lower's.
    let c = p.contacts.last().unwrap(); // at x = 20: both nodes free
    let mut u = vec![0.0; p.sys.dofs.n_free()];
    u[p.sys.dofs.free(3 * c.nodes[1] + 2).unwrap()] = 2.0;
    u[p.sys.dofs.free(3 * c.nodes[0] + 2).unwrap()] = 0.5;
    assert_eq!(c.relative(0, &u), 1.5);
    assert_eq!(c.relative(1, &u), 0.0);
    // Unit point force along z; no damping given.
    let total: Complex<f64> = p.excitation.iter().sum();
    assert_eq!(total, Complex::new(1.0, 0.0));
    assert!(p.damping.is_none());
    assert_eq!(p.outputs[0].dofs.len(), 1);
}

#[test]
fn pressure_resultant_and_rayleigh() {
    let text = crate::input::scene::tests::GOOD
        .replace("rho = 7.85e-9", "rho = 7.85e-9\nrayleigh_alpha = 3.0\nrayleigh_beta = 2e-6")
        + "\n[[preload]]\nkind = \"pressure\"\nbody = \"upper\"\nface = \"z_max\"\npressure = 2.0\n";
    let p = build(&Scene::parse("x", &text).unwrap()).unwrap();
    // Resultant of 2 N/mm² on 20×5 mm² in −z.
    let fz: f64 = (0..p.sys.dofs.n_free())
        .filter(|&f| p.sys.dofs.full(f) % 3 == 2)
        .map(|f| p.preload[f])
        .sum();
    // Upper body is not clamped: the whole −200 N arrives.
    approx::assert_relative_eq!(fz, -200.0, max_relative = 1e-13);
    // One material: per-element Rayleigh equals αM + βK of the assembled system.
    let d = p.damping.unwrap();
    let r = p.sys.rayleigh(3.0, 2e-6);
    let scale = r.values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for (a, b) in d.values.iter().zip(&r.values) {
        assert!((a - b).abs() <= 1e-13 * scale);
    }
}

pub(crate) const BLOCK: &str = r#"
[units]
length = "mm"
force = "N"
time = "s"
mass = "t"
[[bodies]]
name = "block"
kind = "mass"
position = [0.0, 0.0, 0.0]
mass = 0.002
[[interfaces]]
name = "plane"
between = ["ground", "block"]
law = "mindlin"
mu = 0.3
k_t0_per_area = 1282.7
normal_law = "linear"
normal_stiffness_per_area = 1e5
area = 1.0
[[preload]]
kind = "force"
body = "block"
force = [0.0, 0.0, -2.0]
[[excitation]]
kind = "point"
body = "block"
direction = [1.0, 0.0, 0.0]
amplitude = 0.5
[sweep]
f_min = 0.2069
f_max = 0.2069
count = 1
[[outputs]]
name = "x"
body = "block"
direction = [1.0, 0.0, 0.0]
"#;

#[test]
fn lumped_mass_on_ground() {
    let p = build(&Scene::parse("block.toml", BLOCK).unwrap()).unwrap();
    assert_eq!(p.sys.dofs.n_free(), 3);
    assert_eq!(p.contacts.len(), 1);
    let m = p.sys.m.to_dense();
    assert_eq!(m, nalgebra::DMatrix::identity(3, 3) * 0.002);
    assert_eq!(p.preload, vec![0.0, 0.0, -2.0]);
    // δ = u_block − u_ground: the tangent-1 row picks u_x with weight +1.
    assert_eq!(p.contacts[0].rows[1], vec![(0, 1.0)]);
}

#[test]
fn an_input_builds_the_model_of_its_kind() {
    let fe = good();
    assert_eq!(kind(&fe), Kind::Fe);
    let a = build(&fe).unwrap();
    let Ok(Built::Fe(b)) = model(&fe) else {
        panic!("an FE scene builds an FE problem")
    };
    assert_eq!(a.sys.dofs, b.sys.dofs);
    assert_eq!(a.excitation, b.excitation);
    assert_eq!(a.contacts.len(), b.contacts.len());
}

fn scene_file(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name);
    Scene::load(&path).unwrap()
}

#[test]
fn a_lumped_scene_builds_its_lumped_system_and_no_fe_problem() {
    let s = scene_file("jenkins-chain.toml");
    assert_eq!(kind(&s), Kind::Lumped);
    let Ok(Built::Lumped(l)) = model(&s) else {
        panic!("a chain of masses with joints builds a lumped system")
    };
    assert_eq!(l.dofs, lumped::build(&s).unwrap().dofs);
    assert_eq!(l.dofs.len(), 3);
    let e = build(&s).unwrap_err().to_string();
    assert!(e.contains("has no FE model"), "{e}");
}

#[test]
fn a_masses_only_scene_builds_both_and_runs_as_fe() {
    let s = scene_file("duffing.toml");
    assert_eq!(kind(&s), Kind::MassesOnly);
    let Ok(Built::Fe(p)) = model(&s) else {
        panic!("a masses-only scene runs as the FE problem")
    };
    assert_eq!(p.sys.dofs.n_free(), 1);
    assert_eq!(lumped::build(&s).unwrap().dofs.len(), 1);
}
