//! Turns Gmsh's Abaqus export into a mesh file a deck can `*INCLUDE`: physical surfaces
//! (written by Gmsh as CPS3/CPS6 facets) become `*SURFACE, TYPE=ELEMENT` surfaces of the
//! solid elements they bound (jointlin_harness::input::deck::gmsh).
//! Run: `cargo run --release -p jointlin-harness --example gmsh_deck_mesh -- GMSH.inp OUT.inp`
//! (exit 2 on a bad argument or export, with `file:line: *KEYWORD: message`).

use std::path::Path;

use jointlin_harness::input::deck::gmsh::deck_mesh_from_gmsh;
use jointlin_harness::util::atomic::write_text;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [input, output] = args.as_slice() else {
        eprintln!("usage: gmsh_deck_mesh GMSH_EXPORT.inp OUT.inp");
        std::process::exit(2);
    };
    let text = match deck_mesh_from_gmsh(Path::new(input)) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    if let Err(e) = write_text(Path::new(output), &text) {
        eprintln!("{e}");
        std::process::exit(2);
    }
    let surfaces = text.matches("*SURFACE").count();
    eprintln!("{output}: written ({surfaces} surfaces)");
}
