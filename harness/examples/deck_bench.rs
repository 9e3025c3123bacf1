//! Prints how long reading Abaqus-format decks and pairing a non-conforming interface
//! take, on this machine, for structured meshes of growing size (best of 3 runs).
//! Run: `cargo run --release -p jointlin-harness --example deck_bench`.

use std::time::Instant;

use jointlin_harness::fe::elements::box_mesh::box_mesh;
use jointlin_harness::fe::elements::face::MeshFace;
use jointlin_harness::fe::elements::ElementKind;
use jointlin_harness::fe::mesh::Material;
use jointlin_harness::fe::pairing::pair;
use jointlin_harness::input::deck;
use jointlin_harness::validate::ccx::frequency_deck;

/// Best wall time of 3 runs of `f`, in ms.
fn best_ms(mut f: impl FnMut()) -> f64 {
    (0..3)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let mat = Material::new(210_000.0, 0.3, 7.85e-9).expect("steel");
    let dir = std::env::temp_dir().join(format!("jointlin-deck-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    println!("| mesh | DOFs | deck size (MB) | read + check (ms) | MB/s |");
    println!("|---|---:|---:|---:|---:|");
    for (kind, cells) in [
        (ElementKind::C3D8, [20, 10, 10]),
        (ElementKind::C3D8, [40, 20, 14]),
        (ElementKind::C3D10, [20, 10, 10]),
        (ElementKind::C3D20, [20, 10, 10]),
        (ElementKind::C3D20, [40, 20, 10]),
    ] {
        let mesh = box_mesh(kind, [100.0, 50.0, 50.0], cells, 0.1, 1);
        let text = frequency_deck(&mesh, &mat, &[0], 10);
        let path = dir.join("bench.inp");
        std::fs::write(&path, &text).expect("write deck");
        let ms = best_ms(|| {
            deck::read(&path).expect("bench deck reads");
        });
        let mb = text.len() as f64 / 1e6;
        println!(
            "| {kind} {}×{}×{} | {} | {mb:.1} | {ms:.0} | {:.0} |",
            cells[0],
            cells[1],
            cells[2],
            3 * mesh.nodes.len(),
            mb / ms * 1e3
        );
    }
    println!();
    println!("| interface (C3D20 faces) | slave nodes | master faces | pairing (ms) |");
    println!("|---|---:|---:|---:|");
    for n in [20, 60] {
        let lower = box_mesh(ElementKind::C3D20, [1.0, 1.0, 0.1], [n, n, 1], 0.0, 1);
        let mut upper = box_mesh(
            ElementKind::C3D20,
            [1.0, 1.0, 0.1],
            [n + 3, n + 1, 1],
            0.0,
            1,
        );
        upper.nodes.iter_mut().for_each(|p| p[2] += 0.1);
        let off = lower.nodes.len();
        let mut coords = lower.nodes.clone();
        coords.extend_from_slice(&upper.nodes);
        let faces =
            |m: &jointlin_harness::fe::elements::box_mesh::SolidMesh, o: usize, s: usize| {
                m.elements
                    .iter()
                    .enumerate()
                    .map(|(e, c)| {
                        let c: Vec<usize> = c.iter().map(|v| v + o).collect();
                        MeshFace::new(m.kind, e, &c, s).expect("face")
                    })
                    .collect::<Vec<_>>()
            };
        let (master, slave) = (faces(&lower, 0, 1), faces(&upper, off, 0));
        let mut paired = 0;
        let ms = best_ms(|| paired = pair(&coords, &slave, &master, 1e-6).nodes.len());
        println!(
            "| {n}×{n} master, {}×{} slave | {paired} | {} | {ms:.1} |",
            n + 3,
            n + 1,
            master.len()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
