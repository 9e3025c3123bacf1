//! Prints, per element type, how this crate's eigenfrequencies differ from CalculiX's on
//! the same mesh (validate::ccx::element_case: a clamped 40 × 10 × 10 mm steel
//! cantilever, 8 modes). Run: `cargo run --release -p jointlin-harness --example ccx_elements`.

use jointlin_harness::fe::elements::ElementKind;
use jointlin_harness::validate::ccx::{ccx_missing, element_case};

fn main() {
    if let Some(why) = ccx_missing() {
        eprintln!("{why}");
        std::process::exit(1);
    }
    let dir = std::env::temp_dir().join(format!("jointlin-ccx-elements-{}", std::process::id()));
    println!("| element | f1 ours (Hz) | f1 ccx (Hz) | rel. difference, modes 1–8 (min … max) |");
    println!("|---|---:|---:|---|");
    for kind in ElementKind::ALL {
        match element_case(kind, &dir) {
            Ok((ours, ccx)) => {
                let d: Vec<f64> = ours.iter().zip(&ccx).map(|(a, b)| a / b - 1.0).collect();
                let min = d.iter().copied().fold(f64::INFINITY, f64::min);
                let max = d.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                println!(
                    "| {kind} | {:.2} | {:.2} | {min:+.1e} … {max:+.1e} |",
                    ours[0], ccx[0]
                );
                if std::env::var_os("VERBOSE").is_some() {
                    eprintln!("{ours:?}\n{ccx:?}");
                }
            }
            Err(e) => println!("| {kind} | error: {e} | | |"),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
