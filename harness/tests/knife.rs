//! The ultrasonic knife (thesis chapter 5) on the coarse scene: geometry and preload as
//! stated, the thesis's trends as computed numbers (§5.4.2), the contact maps read back
//! from their `.vtu` files. Each power is the joint loss at resonance with the end face
//! at a set amplitude (`jointlin_harness::loss`). Units: N, mm, s; power in N·mm/s.
//!
//! The trends are taken at 3 µm end-face amplitude, where every closed point of the
//! coarse model is in microslip at μ = 0.2 (the thesis's trend figures are at 15 µm,
//! where its model was still all microslip; this simplified model's edge points slide
//! there, see docs/thesis-cases.md "Ultrasonic knife").

use std::path::Path;

use jointlin_harness::input::scene::{RegionSpec, Scene};
use jointlin_harness::loss::{self, mesh, Sample};
use jointlin_harness::report::contact_map as maps;

/// Trend amplitude (mm): 3 µm.
const A: f64 = 0.003;

fn coarse() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
    Scene::load(&path).unwrap()
}

fn power(scene: &Scene, torque: f64) -> Sample {
    loss::power_at(scene, torque, A).unwrap().0
}

fn with(scene: &Scene, edit: impl Fn(&mut jointlin_harness::input::scene::InterfaceSpec)) -> Scene {
    let mut s = scene.clone();
    s.spec.interfaces.iter_mut().for_each(edit);
    s
}

#[test]
fn geometry_slot_gap_and_screw_preload_are_as_stated() {
    let s = coarse();
    let b = |n: &str| s.spec.bodies.iter().find(|b| b.name == n).unwrap().clone();
    let (rear, blade_in, blade_out) = (b("bar_rear_low"), b("blade_in"), b("blade_out"));
    let tip = blade_out.origin.unwrap()[0] + blade_out.size.unwrap()[0];
    approx::assert_relative_eq!(tip - rear.origin.unwrap()[0], 90.0, max_relative = 1e-12);
    let gap: f64 = s.spec.interfaces.iter().map(|i| i.initial_gap).sum();
    approx::assert_relative_eq!(blade_in.size.unwrap()[2], 0.585, max_relative = 1e-12);
    approx::assert_relative_eq!(blade_in.size.unwrap()[2] + gap, 0.6, max_relative = 1e-12);

    // VDI 2230 by hand: 3000 / (0.16·0.5 + 0.58·2.675·0.12 + 4.7/2·0.17), half of it
    // in the half model; the contact carries it less what closing the 0.015 mm play takes.
    let (sample, op) = loss::power_at(&s, 3000.0, A).unwrap();
    let f = 3000.0 / (0.16 * 0.5 + 0.58 * 2.675 * 0.12 + 2.35 * 0.17);
    let screw = &op.problem.screws[0];
    approx::assert_relative_eq!(screw.preload, f, max_relative = 1e-12);
    approx::assert_relative_eq!(screw.applied, 0.5 * f, max_relative = 1e-12);
    let per_face = |k: usize| -> f64 {
        op.problem
            .contacts
            .iter()
            .zip(&op.stat.pressure)
            .filter(|(c, _)| c.interface == k)
            .map(|(c, p)| c.area * p)
            .sum()
    };
    for k in 0..2 {
        let carried = per_face(k);
        assert!(
            carried < 0.5 * f && carried > 0.5 * 0.5 * f,
            "face {k}: {carried} N of {}",
            0.5 * f
        );
    }
    // Both faces carry the same force (the model is symmetric about the blade's
    // mid-plane), to the Newton tolerance.
    approx::assert_relative_eq!(per_face(0), per_face(1), max_relative = 1e-6);
    assert!((sample.amplitude / A - 1.0).abs() <= loss::LEVEL_TOL * 1.01);
}

#[test]
fn lower_friction_coefficient_dissipates_more_in_microslip() {
    let s = coarse();
    let p: Vec<Sample> = [0.2, 0.3, 0.4]
        .iter()
        .map(|&mu| power(&with(&s, |i| i.mu = mu), 3000.0))
        .collect();
    for x in &p {
        assert!(x.max_ratio() < 1.0, "not all microslip: {}", x.max_ratio());
    }
    assert!(
        p[0].power > p[1].power && p[1].power > p[2].power,
        "{} {} {}",
        p[0].power,
        p[1].power,
        p[2].power
    );
}

#[test]
fn lower_stick_stiffness_dissipates_more() {
    // Thesis §5.4.2: k_T0,2 = 1.5 k_T0,1 and k_T0,3 = 4/3 k_T0,2.
    let s = coarse();
    let k1 = s.spec.interfaces[0].k_t0_per_area;
    let p: Vec<f64> = [k1, 1.5 * k1, 2.0 * k1]
        .iter()
        .map(|&k| power(&with(&s, |i| i.k_t0_per_area = k), 3000.0).power)
        .collect();
    assert!(p[0] > p[1] && p[1] > p[2], "{p:?}");
}

#[test]
fn smaller_l_shaped_contact_face_dissipates_more() {
    // Relieve the sonotrode's faces in one corner so that an L stays in contact, both
    // corners in turn. Where matters: cutting the corner at the screw (x > 72, y < 1.5),
    // where the pressure is highest, leaves the tangential load to lower-pressure points
    // and the loss rises (the thesis's finding). Cutting the far corner (x < 72,
    // y > 1.5) also removes low-pressure edge points, which dissipate most: there the
    // two effects nearly cancel. Measured at 3 µm on the coarse scene: full 9.414 W,
    // screw corner cut 21.98 W (+133 %), far corner cut 8.608 W (−8.6 %).
    let s = coarse();
    let cut =
        |min: [f64; 3], max: [f64; 3]| with(&s, |i| i.exclude = vec![RegionSpec { min, max }]);
    let full = power(&s, 3000.0).power;
    let at_screw = power(&cut([72.1, -1.0, -10.0], [80.0, 1.4, 10.0]), 3000.0).power;
    let far = power(&cut([60.0, 1.6, -10.0], [71.9, 10.0, 10.0]), 3000.0).power;
    assert!(at_screw > 2.0 * full, "{at_screw} vs {full}");
    assert!((far / full - 1.0).abs() < 0.15, "{far} vs {full}");
}

/// The thesis's torque trend (Fig. 5.41–5.45: lower torque, more loss) at all four
/// torques and at 4, 8, 12 and 14 µm on scenes/knife-fast.toml (knife.toml's model — the
/// screw on its bearing ring and thread, its hole out of the contact faces, the contact
/// law area-sampled — on a modest uniform mesh; knife.toml's graded mesh shows the same
/// order in the README table and in the ignored test below, at about seven times the
/// CPU time): strictly decreasing with the torque at each amplitude. knife-coarse cannot
/// show it: its 30 points do not resolve the patch the spread screw closes (its loss
/// then rises with the torque), so it keeps the point forces for the other trends.
///
/// The same runs give the model at the four reference points of §5.5 (its k_T0 = 7.282e3
/// N/mm³ calibrated at 3 N·m, 12 µm): the README's row for knife-fast.toml, +0.1, −11.4,
/// −16.7, +0.1 % from the measured levels, asserted at its printed digit, and the loss
/// at 1.5 N·m 2.975 × that at 3 N·m (12 µm). This is the CI stand-in of the graded
/// knife's predictions (ignored test below).
#[test]
fn lower_torque_dissipates_more_at_every_torque_and_amplitude() {
    let (s, curves) = losses("knife-fast.toml");
    assert_falls_with_the_torque(&curves);
    assert_references(&s, &curves, [0.1, -11.4, -16.7, 0.1]);
    assert_ratio(&curves, 2.975, 5e-4);
}

/// The same trend on the graded mesh, where the calibration and the README table are
/// made, and its predictions: +0.1 % at the calibration point, then −2.1, −9.2 and
/// −1.4 %, each within the thesis's own deviation there (19.4, 13.1, 11.6 %)
/// (`cargo test --release -p jointlin-harness --test knife -- --ignored graded_knife`).
#[test]
#[ignore = "knife.toml's 30k DOFs at four torques: about 15 CPU-minutes"]
fn the_graded_knife_dissipates_more_at_every_lower_torque() {
    let (s, curves) = losses("knife.toml");
    assert_falls_with_the_torque(&curves);
    assert_ratio(&curves, 2.93, 5e-3);
    let deviations = assert_references(&s, &curves, [0.1, -2.1, -9.2, -1.4]);
    let st = s.spec.loss_study.as_ref().unwrap();
    for (d, r) in deviations.iter().zip(&st.reference).skip(1) {
        let own = r.source_deviation_percent.unwrap();
        assert!(
            d.abs() < own,
            "{} N·mm: {d:+.1} % beyond the thesis's {own} %",
            r.torque
        );
    }
}

/// The loss at 1.5 N·m over that at 3 N·m, at 12 µm, within `tol` of the README's `printed`.
fn assert_ratio(curves: &[Vec<Sample>], printed: f64, tol: f64) {
    let r = curves[0][2].power / curves[3][2].power;
    assert!(
        (r - printed).abs() < tol,
        "P(1.5 N·m)/P(3 N·m) = {r:.4}, printed {printed}"
    );
}

const TORQUES: [f64; 4] = [1500.0, 2000.0, 2500.0, 3000.0];
/// End-face amplitudes (mm): 12 and 14 µm are where §5.5 gives its reference levels.
const AMPLITUDES: [f64; 4] = [0.004, 0.008, 0.012, 0.014];

/// The loss samples of scenes/`scene` per torque of [`TORQUES`] at [`AMPLITUDES`], each
/// at its resonance.
fn losses(scene: &str) -> (Scene, Vec<Vec<Sample>>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(scene);
    let s = Scene::load(&path).unwrap();
    let curves = TORQUES
        .iter()
        .map(|&t| loss::powers_at(&s, t, &AMPLITUDES).unwrap().0)
        .collect();
    (s, curves)
}

/// The loss strictly decreasing with the torque at each amplitude.
fn assert_falls_with_the_torque(curves: &[Vec<Sample>]) {
    for (k, a) in AMPLITUDES.iter().enumerate() {
        for (pair, t) in curves.windows(2).zip(TORQUES.windows(2)) {
            assert!(
                pair[0][k].power > pair[1][k].power,
                "at {a} mm: {} N·mm/s at {} N·mm, {} at {}",
                pair[0][k].power,
                t[0],
                pair[1][k].power,
                t[1]
            );
        }
    }
}

/// The model's deviation (percent) from each of the scene's `[loss_study] reference`
/// points, asserted within 0.05 of `printed` (the README's digit); each reference level
/// is the thesis's difference over its deviation, as its note says (0.08 W / 6.9 % =
/// 1.159 W), to the scene's digits.
fn assert_references(s: &Scene, curves: &[Vec<Sample>], printed: [f64; 4]) -> Vec<f64> {
    let st = s.spec.loss_study.as_ref().unwrap();
    assert_eq!(st.reference.len(), 4);
    let mut out = Vec::new();
    for (r, want) in st.reference.iter().zip(printed) {
        // "thesis §5.5: 0.08 W at 6.9 %": level = difference / deviation.
        let words: Vec<&str> = r.note.split_whitespace().collect();
        let difference: f64 = words[2].parse().unwrap();
        let deviation = r.source_deviation_percent.unwrap();
        assert_eq!(words[5].parse::<f64>().unwrap(), deviation, "{}", r.note);
        let level = difference / (deviation / 100.0);
        assert!(
            (level - r.power).abs() < 5e-4,
            "{}: {level} W, the scene says {}",
            r.note,
            r.power
        );
        let t = TORQUES.iter().position(|&t| t == r.torque).unwrap();
        let a = AMPLITUDES.iter().position(|&a| a == r.amplitude).unwrap();
        let ours = curves[t][a].power * st.power_factor;
        let d = 100.0 * (ours / r.power - 1.0);
        eprintln!(
            "{} N·mm at {} mm: {ours:.4} W, {d:+.2} % (printed {want:+.1} %)",
            r.torque, r.amplitude
        );
        out.push(d);
    }
    for (d, want) in out.iter().zip(printed) {
        assert!((d - want).abs() < 0.05, "{out:.2?} printed {printed:?}");
    }
    out
}

#[test]
fn edge_points_slip_more_than_interior_points() {
    // Among the closed points, those on the outline of the closed region (a grid
    // neighbour open, or on the face's border) have the lower pressure and the larger
    // A/δ*.
    let (sample, op) = loss::power_at(&coarse(), 3000.0, A).unwrap();
    let p = &op.problem;
    let closed: Vec<usize> = (0..p.contacts.len())
        .filter(|&i| op.stat.closed[i])
        .collect();
    let h = 12.0 / 4.0; // coarse x spacing on the jaws
    let hy = 3.0 / 2.0;
    let near = |a: f64, b: f64| (a - b).abs() < 1e-6;
    let is_edge = |i: usize| {
        let c = &p.contacts[i];
        let n: Vec<usize> = (0..p.contacts.len())
            .filter(|&j| {
                let d = &p.contacts[j];
                let (dx, dy) = (
                    (d.position[0] - c.position[0]).abs(),
                    (d.position[1] - c.position[1]).abs(),
                );
                d.interface == c.interface
                    && ((near(dx, h) && near(dy, 0.0)) || (near(dx, 0.0) && near(dy, hy)))
            })
            .collect();
        n.len() < 4 || n.iter().any(|&j| !op.stat.closed[j])
    };
    let ratio = |i: usize| sample.points[i].ratio[0].max(sample.points[i].ratio[1]);
    let (edge, inner): (Vec<usize>, Vec<usize>) = closed.iter().partition(|&&i| is_edge(i));
    assert!(!edge.is_empty() && !inner.is_empty(), "{edge:?} {inner:?}");
    let mean = |v: &[usize], f: &dyn Fn(usize) -> f64| {
        v.iter().map(|&i| f(i)).sum::<f64>() / v.len() as f64
    };
    let pr = |i: usize| op.stat.pressure[i];
    assert!(mean(&edge, &ratio) > mean(&inner, &ratio));
    assert!(mean(&edge, &pr) < mean(&inner, &pr));
}

/// The thesis's "a finer mesh changes the loss by less than 2 %" (§5.4.2), on the graded
/// scene (knife-graded.toml) with the contact law averaged over area samples: each part
/// of the discretization doubled on its own (x of the jaws and the blade in the slot, x
/// of the bar, y of every box, z of every box), area-sampled power at 3 N·m, 3 and
/// 12 µm, each against the scene itself. Measured 2026-11-22 one row at a time
/// (`jointlin loss scenes/knife-graded.toml --mesh-study 2 --refine R --sampled-only`;
/// the scene 0.011172 / 0.76543 W): x in the slot +0.27 % / +0.45 %, bar x −1.1 % /
/// −1.0 %, z +1.7 % / +1.8 %, y −0.20 % / −0.41 %. On the uniform meshes of
/// knife-coarse the loss does not settle at all (docs/thesis-cases.md "Ultrasonic knife": the patch
/// edge falls inside one element). Ignored because it takes about two hours on this
/// machine's two cores (the y row alone ~1.5 h); run it with
/// `cargo test --release -p jointlin-harness --test knife -- --ignored`.
#[test]
#[ignore = "five meshes of 37k–71k DOFs: about two hours on two cores"]
fn refining_the_mesh_changes_the_loss_by_less_than_two_percent() {
    refining_changes_the_loss_by_less_than("knife-graded.toml", [0.02, 0.02]);
}

/// The same for the screw spread over its ring and thread (knife.toml, graded toward the
/// patch edges of every torque, k_T0 calibrated there; README block `knife_graded_mesh`,
/// 6924 s): at the calibration point (3 N·m, 12 µm) each refinement changes the loss by
/// less than 2 % (measured +0.1 % x in the slot, −1.4 % x of the bar, −1.3 % y, +0.6 %
/// z); at a quarter of the amplitude (0.016 W) x in the slot changes it by +2.4 % (the
/// others +1.5, +0.3, +0.4 %), so 3 % there.
#[test]
#[ignore = "five meshes of 30k–58k DOFs: about two hours on two cores"]
fn the_spread_screw_model_changes_by_less_than_two_percent_at_the_calibration_point() {
    refining_changes_the_loss_by_less_than("knife.toml", [0.03, 0.02]);
}

/// Each of x in the slot, x of the bar, y and z doubled on its own changes the
/// area-sampled loss at a quarter of the scene's first reference amplitude and at it by
/// less than `tol` (relative, in that order).
fn refining_changes_the_loss_by_less_than(scene: &str, tol: [f64; 2]) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(scene);
    let s = Scene::load(&path).unwrap();
    let refinements: Vec<mesh::Refinement> = ["x:jaw_,blade_in", "x:bar_", "y", "z"]
        .iter()
        .map(|r| mesh::Refinement::parse(r).unwrap())
        .collect();
    let rows = mesh::study(&s, &[1, 2], &refinements, false, &|_| {}).unwrap();
    let base = &rows[0];
    for r in &rows[1..] {
        for (k, tol) in tol.iter().enumerate() {
            let rel = (r.sampled[k] - base.sampled[k]).abs() / base.sampled[k];
            assert!(
                rel < *tol,
                "{} at {} mm: {} -> {} W ({rel:.3})",
                r.refined,
                r.amplitudes[k],
                base.sampled[k],
                r.sampled[k],
            );
        }
    }
}

/// The mesh study's first row is the scene itself: its node-based powers are (bitwise)
/// `power_at`'s at the reference torque (3 N·m) and amplitudes (3 µm, 12 µm); the area-sampled
/// ones differ (the patch edge moves into the elements) but stay positive; the shares
/// are fractions; without the node-based law the area-sampled half is the same.
#[test]
fn mesh_study_row_one_is_the_scene_itself() {
    let s = coarse();
    let everything = [mesh::Refinement::everything()];
    let rows = mesh::study(&s, &[1], &everything, true, &|_| {}).unwrap();
    let r = &rows[0];
    let node = r.node.expect("the node-based law was asked for");
    let st = s.spec.loss_study.as_ref().unwrap();
    let at = |a: f64| loss::power_at(&s, 3000.0, a).unwrap().0.power * st.power_factor;
    approx::assert_relative_eq!(node.power[0], at(0.003), max_relative = 1e-12);
    approx::assert_relative_eq!(node.power[1], at(0.012), max_relative = 1e-12);
    assert_eq!(r.amplitudes, [0.003, 0.012]);
    assert!(r.sampled.iter().all(|&p| p > 0.0));
    assert!(node
        .low_pressure_share
        .iter()
        .all(|&x| (0.0..=1.0).contains(&x)));
    // Without the node-based law: the same area-sampled row, no node-based half.
    let sampled_only = mesh::study(&s, &[1], &everything, false, &|_| {}).unwrap();
    assert!(sampled_only[0].node.is_none());
    assert_eq!(sampled_only[0].sampled, r.sampled);
    assert_eq!(sampled_only[0].freq, r.freq);
    assert_eq!(mesh::refined(&s, 3).divisions()[0], Some([18, 6, 6]));
}

/// The graded scene (knife-graded.toml, for the mesh study) meshes the same part: its
/// slab interfaces cover each 12 × 3 mm contact face of the half model exactly once
/// (areas summed over the slabs, round-off 1e-12), like knife-coarse's, the screw's
/// loads are centred at x = 72 on both, and its finest elements (0.05 mm) sit in the
/// bands across the
/// patch edges at 3 N·m, which the coarse scene's pressure puts between 69.3–69.9 and
/// 76.1–76.8 mm.
#[test]
fn graded_scene_meshes_the_same_contact_faces() {
    use jointlin_harness::model::build;
    let graded = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-graded.toml");
    let graded = Scene::load(&graded).unwrap();
    for s in [coarse(), graded.clone()] {
        faces_and_screw_are(&s, 36.0, 1e-12);
    }
    let p = build(&graded).unwrap();
    let xs: Vec<f64> = {
        let mut v: Vec<f64> = p.contacts.iter().map(|c| c.position[0]).collect();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        v
    };
    let finest = xs.windows(2).map(|w| w[1] - w[0]).fold(f64::MAX, f64::min);
    approx::assert_relative_eq!(finest, 0.05, max_relative = 1e-9);
    for band in [(69.3, 69.9), (76.1, 76.8)] {
        let inside = xs
            .iter()
            .filter(|&&x| x >= band.0 - 1e-9 && x <= band.1 + 1e-9);
        assert!(inside.count() >= 13, "band {band:?}");
    }
}

/// knife.toml (graded) and knife-fast.toml (uniform) mesh the same model: per contact
/// face 12 × 3 mm less the screw's hole (3 × 2 mm of faces) = 30 mm² of contact, summed
/// over the slabs; the screw's head ring and thread loads centred on its axis (x = 72,
/// to the sampling's resolution) on both, with the preload's resultant; knife.toml's
/// finest elements (0.070 and 0.071 mm) fill the two bands 69.1–70.5 and 76.4–77.4 mm
/// that hold the patch's edges at every torque.
#[test]
fn graded_knife_meshes_the_fast_knifes_model() {
    use jointlin_harness::model::build;
    let scene = |f: &str| {
        Scene::load(
            &Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../scenes")
                .join(f),
        )
        .unwrap()
    };
    let (graded, fast) = (scene("knife.toml"), scene("knife-fast.toml"));
    for s in [&graded, &fast] {
        // Midpoint sampling of the ring and the cylinder on the elements: centred to well
        // below a micrometre (0.4 µm on the graded mesh).
        faces_and_screw_are(s, 30.0, 1e-3);
    }
    let p = build(&graded).unwrap();
    let mut xs: Vec<f64> = p.model.nodes.iter().map(|x| x[0]).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    for band in [(69.1, 70.5), (76.4, 77.4)] {
        let inside: Vec<f64> = xs
            .iter()
            .copied()
            .filter(|&x| x >= band.0 - 1e-9 && x <= band.1 + 1e-9)
            .collect();
        let h = inside[1] - inside[0];
        assert!(h < 0.072, "{h} mm in {band:?}");
        for w in inside.windows(2) {
            approx::assert_relative_eq!(w[1] - w[0], h, max_relative = 1e-9);
        }
        approx::assert_relative_eq!(inside[0], band.0, max_relative = 1e-12);
        approx::assert_relative_eq!(*inside.last().unwrap(), band.1, max_relative = 1e-12);
    }
}

/// Each contact face (the interfaces named face1…, face2…) has `area` (mm², to 1e-12),
/// and each end of the screw carries shares summing to 1 centred at x = 72 mm (within
/// `dx` mm).
fn faces_and_screw_are(s: &Scene, area: f64, dx: f64) {
    let p = jointlin_harness::model::build(s).unwrap();
    for face in ["face1", "face2"] {
        let a: f64 = p
            .contacts
            .iter()
            .filter(|c| p.interfaces[c.interface].name.starts_with(face))
            .map(|c| c.area)
            .sum();
        approx::assert_relative_eq!(a, area, max_relative = 1e-12);
    }
    let screw = &p.screws[0];
    for end in [&screw.head, &screw.nut] {
        let x: f64 = end.iter().map(|&(n, w)| w * p.model.nodes[n][0]).sum();
        assert!((x - 72.0).abs() <= dx, "{x}");
        approx::assert_relative_eq!(
            end.iter().map(|e| e.1).sum::<f64>(),
            1.0,
            max_relative = 1e-12
        );
    }
}

/// The numbers of a `<DataArray Name="name">` of a `.vtu` text.
fn data_array(text: &str, name: &str) -> Vec<f64> {
    let key = format!("Name=\"{name}\"");
    let start = text.find(&key).unwrap_or_else(|| panic!("no {name}"));
    let open = start + text[start..].find('>').unwrap() + 1;
    let close = open + text[open..].find("</DataArray>").unwrap();
    text[open..close]
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

fn attr(text: &str, name: &str) -> usize {
    let key = format!("{name}=\"");
    let i = text.find(&key).unwrap() + key.len();
    text[i..i + text[i..].find('"').unwrap()].parse().unwrap()
}

#[test]
fn contact_maps_read_back_from_vtu() {
    let (sample, op) = loss::power_at(&coarse(), 3000.0, A).unwrap();
    let vals = maps::values(&op.problem, &op.stat.pressure, &sample.points);
    let dir = std::env::temp_dir().join(format!("jointlin-knife-vtu-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (k, itf) in op.problem.interfaces.iter().enumerate() {
        let path = dir.join(format!("{}.vtu", itf.name));
        std::fs::write(&path, maps::vtu(&op.problem, k, &vals)).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("<VTKFile type=\"UnstructuredGrid\""));
        // Coarse jaws: 4 × 2 element faces, 5 × 3 nodes per contact face.
        let ids: Vec<usize> = (0..op.problem.contacts.len())
            .filter(|&i| op.problem.contacts[i].interface == k)
            .collect();
        assert_eq!(attr(&text, "NumberOfPoints"), 15);
        assert_eq!(attr(&text, "NumberOfCells"), 8);
        let pos = data_array(&text, "position");
        let conn = data_array(&text, "connectivity");
        let types = data_array(&text, "types");
        assert_eq!(pos.len(), 3 * 15);
        assert_eq!(conn.len(), 4 * 8);
        assert!(types.iter().all(|&t| t == 9.0));
        assert!(conn.iter().all(|c| (0.0..15.0).contains(c)));
        for (name, f) in [
            (
                "pressure",
                &(|v: &maps::PointValues| v.pressure) as &dyn Fn(&maps::PointValues) -> f64,
            ),
            ("amplitude_ratio", &|v: &maps::PointValues| v.ratio),
            ("energy_density", &|v: &maps::PointValues| v.energy_density),
        ] {
            let read = data_array(&text, name);
            assert_eq!(read.len(), 15);
            for (r, &i) in read.iter().zip(&ids) {
                let want = f(&vals[i]);
                assert!(
                    (r - want).abs() <= 1e-8 * want.abs().max(1e-300),
                    "{name}: {r} vs {want}"
                );
            }
        }
        // Positions are the contact points' (the lower face's nodes).
        for (j, &i) in ids.iter().enumerate() {
            for a in 0..3 {
                assert!((pos[3 * j + a] - op.problem.contacts[i].position[a]).abs() < 1e-8);
            }
        }
        // The map's energy is the sample's power: Σ E/A·A·f / share.
        let e: f64 = ids
            .iter()
            .map(|&i| vals[i].energy_density * op.problem.contacts[i].area)
            .sum();
        assert!(e > 0.0);
    }
    let total: f64 = vals
        .iter()
        .zip(&op.problem.contacts)
        .map(|(v, c)| v.energy_density * c.area)
        .sum();
    approx::assert_relative_eq!(total * sample.freq / 0.5, sample.power, max_relative = 1e-9);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_knife_scenes_name_file_line_and_key() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife-coarse.toml");
    let text = std::fs::read_to_string(path).unwrap();
    for (from, to, key) in [
        (
            "output = \"end_face\"\n@",
            "output = \"nope\"\n@",
            "loss_study.output",
        ),
        (
            "initial_gap = 0.0075",
            "initial_gap = -0.0075",
            "interfaces[0].initial_gap",
        ),
        (
            "mu_thread = 0.12",
            "mu_thread = -0.12",
            "screws[0].mu_thread",
        ),
        (
            "between = [\"blade_in\", \"blade_out\"]",
            "between = [\"blade_in\", \"blade\"]",
            "ties[9].between[1]",
        ),
        (
            "head = { body = \"jaw_high\", at = [72.0, 0.0, 4.3875] }",
            "head = { body = \"jaw_high\", at = [72.0, 0.0, 4.3875], bearing = [6.0, 3.4] }",
            "screws[0].head.bearing",
        ),
        (
            "[loss_study]\n",
            "[loss_study]\ncalibration = { parameters = [\"k_t0\", \"mu\"], points = [0] }\n",
            "loss_study.calibration.points",
        ),
    ] {
        // `@` marks the first occurrence after the [loss_study] header.
        let bad = if from.ends_with('@') {
            let at = text.find("[loss_study]").unwrap();
            let (head, tail) = text.split_at(at);
            format!(
                "{head}{}",
                tail.replacen(from.trim_end_matches('@'), to.trim_end_matches('@'), 1)
            )
        } else {
            text.replacen(from, to, 1)
        };
        assert_ne!(bad, text, "{from}");
        let e = Scene::parse("knife-coarse.toml", &bad)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("knife-coarse.toml:") && e.contains(key),
            "{e}"
        );
    }
}

/// `jointlin loss` with amplitudes 3 and 4 µm at 2500 N·mm: the 3 µm level started from
/// 0.9 × the 4 µm scale, and the secant cycled between three scales where the amplitude
/// (iterated to the scene's tolerance 1e-3) jumps by 9.5e-4 ("amplitude level did not
/// converge at 31819.9 Hz"). Now bracketed and bisected: each level within the scene's
/// iteration tolerance.
#[test]
fn loss_levels_at_three_and_four_microns_converge_at_2500_nmm() {
    let mut s = coarse();
    let st = s.spec.loss_study.as_mut().unwrap();
    st.amplitudes = vec![0.003, 0.004];
    st.torques = vec![2500.0];
    let r = loss::run_study(&s, &|_| {}).unwrap();
    let tol = s.spec.iteration.tolerance;
    for (sample, a) in r.curves[0].1.iter().zip([0.003, 0.004]) {
        let e = (sample.amplitude / a).ln().abs();
        assert!(e <= tol, "{a} mm: |ln(a/target)| = {e}");
    }
}

/// `jointlin loss --calibrate` with two parameters on two reference points: reference
/// powers made by the model itself with k_T0 × 1.3 and μ × 0.8 (at 3000 N·mm and 3 µm,
/// all microslip, and at 1500 N·mm and 12 µm, where the coarse scene's edge slides, so
/// the two parameters act differently; at 8 µm on both, k_T0 hardly acted at all and the
/// fit found another pair) are fitted back from the scene's own values: both factors to
/// 2 %, both powers to the calibration's 0.2 %.
#[test]
fn a_two_parameter_calibration_recovers_the_factors_that_made_its_references() {
    use jointlin_harness::input::scene::{CalibratedParameter as P, CalibrationSpec};
    use jointlin_harness::loss::calibrate::{calibrate, scaled};
    let truth = [(P::KT0, 1.3), (P::Mu, 0.8)];
    let made = scaled(&coarse(), &truth);
    let mut s = coarse();
    let st = s.spec.loss_study.as_mut().unwrap();
    st.reference.truncate(2);
    for (r, (torque, amplitude)) in st
        .reference
        .iter_mut()
        .zip([(3000.0, 0.003), (1500.0, 0.012)])
    {
        r.torque = torque;
        r.amplitude = amplitude;
        r.power = loss::power_at(&made, torque, amplitude).unwrap().0.power * st.power_factor;
    }
    st.calibration = Some(CalibrationSpec {
        parameters: vec![P::KT0, P::Mu],
        points: vec![0, 1],
    });
    let cal = calibrate(&s, &|_| {}).unwrap();
    for (&(p, got), (q, want)) in cal.factors.iter().zip(truth) {
        assert_eq!(p, q);
        approx::assert_relative_eq!(got, want, max_relative = 0.02);
    }
    let st = s.spec.loss_study.as_ref().unwrap();
    for (p, r) in cal.powers.iter().zip(&st.reference) {
        approx::assert_relative_eq!(*p, r.power, max_relative = 2.5e-3);
    }
}

#[test]
fn contact_maps_draw_each_face_whole() {
    // knife.toml splits each contact face into six x-slabs (interfaces face1_s1 …
    // face1_s6 in one plane): the maps draw a face as one panel, not six.
    use jointlin_harness::report::contact_map::{svg, MapKind, PointValues};
    let s =
        Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife.toml")).unwrap();
    let p = jointlin_harness::model::build(&s).unwrap();
    let vals: Vec<PointValues> = p
        .contacts
        .iter()
        .enumerate()
        .map(|(i, c)| PointValues {
            pressure: 1.0,
            amplitude: 1e-4 * c.position[0],
            ratio: (i % 3) as f64 * 0.6,
            energy_density: c.position[0],
        })
        .collect();
    let dir = std::env::temp_dir().join(format!("jointlin-maps-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ratio.svg");
    svg(&file, "knife", &s.spec.units, &p, &vals, MapKind::Ratio).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    for face in ["face1", "face2"] {
        let caption = format!("{face}_s1 … {face}_s6 (6 interfaces in one plane)");
        assert_eq!(text.matches(&caption).count(), 1, "{face}");
    }
    assert!(!text.contains("face1_s2:"), "a slab drawn on its own");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The README's facts of knife.toml: 30 108 free DOFs and 500 contact points (`jointlin
/// check`); with stuck joints its working mode, longitudinal, at 31.67 kHz between
/// neighbours at 25.5 and 34.9 kHz (`jointlin modes`, Lanczos on the 30k DOFs).
#[test]
fn the_graded_knife_has_the_size_and_modes_the_readme_states() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/knife.toml");
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_jointlin"))
            .args(args)
            .arg(&scene)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let check = run(&["check"]);
    assert!(
        check.contains("model: 30108 free DOFs, 500 contact points"),
        "{check}"
    );
    let modes = run(&["modes", "--count", "9"]);
    let row = |mode: usize| -> Vec<String> {
        modes
            .lines()
            .find(|l| l.starts_with(&format!("| {mode} |")))
            .unwrap_or_else(|| panic!("mode {mode} in {modes}"))
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    let khz = |mode: usize| row(mode)[2].parse::<f64>().unwrap() / 1e3;
    assert!((khz(8) - 31.67).abs() < 0.005, "{modes}");
    assert_eq!(row(8)[3], "longitudinal_x", "{modes}");
    assert!(
        (khz(7) - 25.5).abs() < 0.05 && (khz(9) - 34.9).abs() < 0.05,
        "{modes}"
    );
}
