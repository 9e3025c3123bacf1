//! The static preload step on small scenes: block preload, initial gaps, pressed plates
//! (linear and Hertz), area-sampled points on a partly closed face.

use super::*;
use crate::input::scene::Scene;
use crate::model::build;

#[test]
fn block_preload_gives_the_normal_force_as_pressure() {
    let p = build(&Scene::parse("b", crate::model::tests::BLOCK).unwrap()).unwrap();
    let s = solve(&p, true).unwrap();
    // 2 N on area 1: p = 2, h = p/k_N = 2e-5 (linear law, exact after the active set).
    approx::assert_relative_eq!(s.pressure[0], 2.0, max_relative = 1e-9);
    approx::assert_relative_eq!(-s.u[2], 2e-5, max_relative = 1e-9);
    assert!(s.closed[0] && s.normal_stiffness[0] == 1e5);
    assert!(s.newton_iterations <= 3, "{}", s.newton_iterations);
}

#[test]
fn an_initial_gap_is_closed_before_the_contact_carries_load() {
    // The block with a 1 µm gap under it: it falls through the gap (held meanwhile
    // only by the open-point stand-in), then the linear law carries the 2 N:
    // −u_z = g₀ + p/k_N exactly, same pressure as without the gap.
    let text = crate::model::tests::BLOCK.replace("area = 1.0", "area = 1.0\ninitial_gap = 1e-3");
    let p = build(&Scene::parse("b", &text).unwrap()).unwrap();
    let s = solve(&p, true).unwrap();
    approx::assert_relative_eq!(s.pressure[0], 2.0, max_relative = 1e-9);
    approx::assert_relative_eq!(-s.u[2], 1e-3 + 2e-5, max_relative = 1e-9);
    assert!(s.closed[0]);
}

#[test]
fn pressed_plates_carry_the_pressure_and_hertz_converges() {
    // Two plates pressed together by 1 N/mm² top and bottom: the interface carries
    // 1 N/mm² on average (total 100 N over 20×5 mm²).
    let base = crate::input::scene::tests::GOOD.to_string()
        + "\n[[preload]]\nkind = \"pressure\"\nbody = \"upper\"\nface = \"z_max\"\npressure = 1.0\n\
           [[preload]]\nkind = \"pressure\"\nbody = \"lower\"\nface = \"z_min\"\npressure = 1.0\n";
    for text in [
        base.clone(),
        base.replace(
            "normal_law = \"linear\"\nnormal_stiffness_per_area = 1e5",
            "normal_law = \"hertz\"\nhertz_radius = 1.0\nhertz_e_star = 115000.0",
        ),
    ] {
        let p = build(&Scene::parse("x", &text).unwrap()).unwrap();
        let s = solve(&p, true).unwrap();
        let total: f64 = p
            .contacts
            .iter()
            .zip(&s.pressure)
            .map(|(c, pr)| c.area * pr)
            .sum();
        // Force balance on the upper plate: the contact carries the whole 100 N
        // (to the Newton tolerance).
        approx::assert_relative_eq!(total, 100.0, max_relative = 1e-6);
        assert!(s.residual <= RESIDUAL_TOL);
    }
}

/// Area samples (`area_samples`) on a face pressed unevenly: the knife's jaw on its
/// blade, closed only where the screw bends it across the 0.015 mm play. The
/// sampled static step converges (coupled normal tangent), each point's pressure is
/// the area average of its samples, and the contact still carries what the screw
/// applies less what the jaws' bending takes (same as node-based within 3 %: only
/// the patch edge differs).
#[test]
fn sampled_points_keep_the_force_balance_on_a_partly_closed_face() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
    let node = Scene::load(&path).unwrap();
    let mut sampled = node.clone();
    for i in &mut sampled.spec.interfaces {
        i.area_samples = Some(3);
    }
    let carried = |scene: &Scene| {
        let p = build(scene).unwrap();
        let s = solve(&p, true).unwrap();
        assert!(s.residual <= RESIDUAL_TOL, "{}", s.residual);
        let total: f64 = p
            .contacts
            .iter()
            .zip(&s.pressure)
            .filter(|(c, _)| c.interface == 0)
            .map(|(c, pr)| c.area * pr)
            .sum();
        (p, s, total)
    };
    let (_, s_node, f_node) = carried(&node);
    let (p, s, f_sampled) = carried(&sampled);
    approx::assert_relative_eq!(f_sampled, f_node, max_relative = 0.03);
    let mut partly = 0;
    let p_max = s.pressure.iter().copied().fold(0.0, f64::max);
    let mut refined = 0;
    for (k, c) in p.contacts.iter().enumerate() {
        // 3 × 3 per quarter face: 9 (corner), 18 (edge) or 36 (interior point).
        assert!(
            [9, 18, 36].contains(&c.samples.len()),
            "{}",
            c.samples.len()
        );
        let list = &s.friction_samples[k];
        assert!(list.len() >= c.samples.len());
        refined += list.len() - c.samples.len();
        let sum: f64 = list.iter().map(|x| x.0).sum();
        approx::assert_relative_eq!(sum, 1.0, max_relative = 1e-12);
        // The refined samples integrate the same pressure field; they differ from
        // the unrefined average only in the cells the patch edge crosses.
        let mean: f64 = list.iter().map(|x| x.0 * x.1).sum();
        assert!(
            (mean - s.pressure[k]).abs() <= 0.01 * p_max,
            "{mean} {}",
            s.pressure[k]
        );
        let open = list.iter().filter(|x| x.1 == 0.0).count();
        if open > 0 && open < list.len() {
            partly += 1;
        }
    }
    assert!(refined > 0);
    // The patch edge runs through elements: points there are partly closed.
    assert!(partly > 0);
    println!(
        "carried: node-based {f_node:.2} N, sampled {f_sampled:.2} N; {partly} points \
         partly closed; Newton iterations {} node-based, {} sampled",
        s_node.newton_iterations, s.newton_iterations
    );
}

/// The knife's screw spread over its head's bearing ring and its engaged thread
/// (`bearing`, `thread`): the static step converges (the open points' stand-in in the
/// Newton matrix once made it converge only linearly, 0.885 per iteration, and stop at
/// 60 iterations), and the screw's force is what the jaws' bending and the contact
/// carry: the blade is held by contact alone, so both faces carry the same force.
#[test]
fn a_screw_spread_over_its_bearing_ring_and_thread_preloads_the_knife() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
    let mut scene = Scene::load(&path).unwrap();
    let sc = &mut scene.spec.screws[0];
    sc.head.bearing = Some([3.4, 6.0]);
    sc.nut.thread = Some(crate::input::scene::ThreadSpec {
        diameter: 2.675,
        length: 4.095,
    });
    let p = build(&scene).unwrap();
    assert!(p.screws[0].head.len() > 1 && p.screws[0].nut.len() > 1);
    let s = solve(&p, true).unwrap();
    assert!(s.residual <= RESIDUAL_TOL, "{}", s.residual);
    assert!(s.newton_iterations < 30, "{}", s.newton_iterations);
    let carried = |iface: usize| -> f64 {
        p.contacts
            .iter()
            .zip(&s.pressure)
            .filter(|(c, _)| c.interface == iface)
            .map(|(c, pr)| c.area * pr)
            .sum()
    };
    let (lower, upper) = (carried(0), carried(1));
    approx::assert_relative_eq!(lower, upper, max_relative = 1e-6);
    // Less than the applied force (the jaws bend across the play), most of it.
    let applied = p.screws[0].applied;
    assert!(
        lower < applied && lower > 0.5 * applied,
        "{lower} of {applied}"
    );
}
