//! Labels of the modes of a steel cantilever 100 × 4 × 6 mm (x along it, thin in y),
//! clamped at x = 0, against beam theory's order: bending in x-y (the thin direction)
//! first, then x-z, torsion, and the first longitudinal mode at c/4L.

use super::{Kind, ModeGeometry};
use crate::fe::assembly::assemble;
use crate::fe::mesh::{BoxSpec, Face, Material, Model};
use crate::solve::modal::ModalOptions;
use crate::solve::modal_band::modes_below;

/// Units N, mm, s, t: E in MPa, ρ in t/mm³.
const E: f64 = 210_000.0;
const RHO: f64 = 7.85e-9;
const L: f64 = 100.0;

fn cantilever() -> Model {
    let mut model = Model::new(vec![Material::new(E, 0.3, RHO).unwrap()]);
    model
        .add_box(BoxSpec {
            origin: [0.0; 3],
            size: [L, 4.0, 6.0],
            divisions: [25, 2, 3],
            material: 0,
        })
        .unwrap();
    let clamp = model.bodies[0].face_nodes(Face::XMin);
    model.fix(&clamp, [true; 3]).unwrap();
    model
}

/// Labels, shares and frequencies of the cantilever's modes up to 1.1 × the first
/// longitudinal one.
fn labelled(model: &Model) -> (Vec<f64>, Vec<super::Character>) {
    let sys = assemble(model, &[]).unwrap();
    let f_long = (E / RHO).sqrt() / (4.0 * L);
    let band = modes_below(
        &sys.k,
        &sys.m,
        1.1 * f_long,
        6,
        100,
        &ModalOptions::default(),
    )
    .unwrap();
    assert!(band.complete);
    let geo = ModeGeometry::new(&model.nodes, &sys.dofs, &sys.m);
    let chars = band
        .modes
        .shapes
        .iter()
        .map(|phi| geo.character(&sys.m, phi))
        .collect();
    (band.modes.frequencies_hz(), chars)
}

#[test]
fn a_perturbed_mesh_keeps_the_labels_of_the_box_mesh() {
    // Every node off the clamp moved at random by up to 30 % of the element length
    // along the beam and 10 % across it: no two nodes share an axial plane, so the
    // sections are slabs. The labels, their order and the torsion mode's inertia stay;
    // the shares add up to one (a plane-by-plane split gave 102.9 % on such meshes and
    // called the torsion mode bending).
    let (f_box, box_chars) = labelled(&cantilever());
    let mut model = cantilever();
    let mut rng = crate::util::rng::Rng::new(7);
    for x in model.nodes.iter_mut().filter(|x| x[0] > 0.0) {
        x[0] += rng.uniform(-0.3, 0.3) * L / 25.0;
        x[1] += rng.uniform(-0.1, 0.1) * 4.0 / 2.0;
        x[2] += rng.uniform(-0.1, 0.1) * 6.0 / 3.0;
    }
    let (f, chars) = labelled(&model);
    let labels: Vec<String> = chars.iter().map(|c| c.label()).collect();
    let box_labels: Vec<String> = box_chars.iter().map(|c| c.label()).collect();
    eprintln!("box {box_labels:?}\nperturbed {labels:?}");
    assert_eq!(labels, box_labels);
    // The distorted hexahedra stiffen (incompatible modes lose their bending accuracy
    // off the parallelepiped): up to 10 % here, the same modes.
    for (a, b) in f.iter().zip(&f_box) {
        assert!((a / b - 1.0).abs() < 0.15, "{a} vs {b} Hz");
    }
    let t = chars.iter().position(|c| c.kind == Kind::Torsion).unwrap();
    let c = &chars[t];
    assert!(c.kind_share[2] > 0.8, "{:?}", c.kind_share);
    assert!(c.effective_inertia[0] > 10.0 * c.effective_inertia[1].max(c.effective_inertia[2]));
    for c in &chars {
        approx::assert_relative_eq!(c.kind_share.iter().sum::<f64>(), 1.0, epsilon = 1e-9);
        assert!(c.kind_share.iter().all(|&v| v >= 0.0));
    }
}

#[test]
fn cantilever_modes_are_labelled_as_beam_theory_orders_them() {
    let model = cantilever();
    let (f, chars) = labelled(&model);
    let f_long = (E / RHO).sqrt() / (4.0 * L);
    for (fi, c) in f.iter().zip(&chars) {
        eprintln!(
            "{fi:10.1} Hz {:16} dominant {} shares L/B/T/S {:.3?} m_eff {:?}",
            c.label(),
            c.dominant_name(),
            c.kind_share,
            c.effective_mass
        );
    }
    // Bending of the first two in the planes beam theory orders: the thin direction y
    // (I = 6·4³/12) before z (I = 4·6³/12).
    assert_eq!(chars[0].label(), "bending_xy");
    assert_eq!(chars[0].dominant_name(), 'y');
    assert_eq!(chars[1].label(), "bending_xz");
    assert_eq!(chars[1].dominant_name(), 'z');
    for c in &chars[..2] {
        assert!(c.kind_share[1] > 0.95, "{:?}", c.kind_share);
    }
    // One longitudinal mode in the band, within 3 % of the rod's c/4L, moving along x
    // and carrying most of the x effective mass (8/π² ≈ 81 % of the free mass for a rod).
    let long: Vec<usize> = (0..chars.len())
        .filter(|&i| chars[i].kind == Kind::Longitudinal)
        .collect();
    assert_eq!(
        long.len(),
        1,
        "{:?}",
        chars.iter().map(|c| c.label()).collect::<Vec<_>>()
    );
    let i = long[0];
    assert_eq!(chars[i].label(), "longitudinal_x");
    assert_eq!(chars[i].dominant_name(), 'x');
    assert!(
        (f[i] - f_long).abs() < 0.03 * f_long,
        "{} vs {f_long}",
        f[i]
    );
    // The mass on free DOFs: the clamped nodes hold half an element layer.
    let free_mass = RHO * 24.0 * (L - 0.5 * L / 25.0);
    let share = chars[i].effective_mass[0] / free_mass;
    assert!(
        (share - 8.0 / std::f64::consts::PI.powi(2)).abs() < 0.03,
        "{share}"
    );
    // One torsion mode below it, with its effective inertia about x the largest of its
    // three and no effective mass to speak of.
    let t: Vec<usize> = (0..chars.len())
        .filter(|&i| chars[i].kind == Kind::Torsion)
        .collect();
    assert_eq!(t.len(), 1);
    let c = &chars[t[0]];
    assert_eq!(c.label(), "torsion_x");
    assert!(c.effective_inertia[0] > 10.0 * c.effective_inertia[1].max(c.effective_inertia[2]));
    assert!(c.effective_mass.iter().all(|&m| m < 1e-6 * free_mass));
    // Every mode's shares add up to one.
    for c in &chars {
        approx::assert_relative_eq!(c.kind_share.iter().sum::<f64>(), 1.0, epsilon = 1e-9);
        approx::assert_relative_eq!(c.direction_share.iter().sum::<f64>(), 1.0, epsilon = 1e-9);
    }
}

#[test]
fn a_lone_mass_is_a_translation() {
    let mut model = Model::new(vec![Material::new(E, 0.3, RHO).unwrap()]);
    model
        .add_box(BoxSpec {
            origin: [0.0; 3],
            size: [1.0, 1.0, 1.0],
            divisions: [1, 1, 1],
            material: 0,
        })
        .unwrap();
    // Hold all but node 6's z: one free DOF, one cross-section.
    let all: Vec<usize> = (0..8).collect();
    model.fix(&all, [true; 3]).unwrap();
    model.fixed[3 * 6 + 2] = false;
    let sys = assemble(&model, &[]).unwrap();
    let geo = ModeGeometry::new(&model.nodes, &sys.dofs, &sys.m);
    let c = geo.character(&sys.m, &[1.0]);
    assert_eq!(c.kind, Kind::Translation);
    assert_eq!(c.label(), "translation_z");
}
