//! `jointlin deck from-gmsh GMSH.inp --out MESH.inp`: Gmsh's Abaqus export as a mesh
//! file a deck can `*INCLUDE`: physical surfaces (written by Gmsh as CPS3/CPS6 facets,
//! which a 3D deck cannot hold) become `*SURFACE, TYPE=ELEMENT` surfaces of the solid
//! elements they bound ([`jointlin_harness::input::deck::gmsh`]).

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::input::deck::gmsh::deck_mesh_from_gmsh;
use jointlin_harness::util::atomic;

// The command's help is the doc comment of `Command::Deck`.
#[derive(clap::Subcommand)]
pub enum Args {
    /// Converts a Gmsh export (`gmsh -3 -format inp -o GMSH.inp MODEL.geo`) into a mesh
    /// file for a deck's `*INCLUDE`: nodes, solid elements, their element sets and every
    /// node set as Gmsh wrote them; each physical surface (CPS3/CPS6/CPS4/CPS8 facets)
    /// as `*SURFACE, TYPE=ELEMENT` of the solid element faces it covers (S1…S6); curve
    /// elements dropped. A facet that is no solid element's face, an element type the
    /// deck reader does not know or a malformed line is an error naming file:line and
    /// keyword (exit 2, nothing written).
    FromGmsh {
        /// Gmsh's Abaqus export (.inp).
        export: PathBuf,
        /// The mesh file written (atomically; an existing file is replaced).
        #[arg(long)]
        out: PathBuf,
    },
}

pub fn main(a: Args) -> ExitCode {
    let Args::FromGmsh { export, out } = a;
    let text = match deck_mesh_from_gmsh(&export) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if let Err(e) = atomic::write_text(&out, &text) {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    let surfaces = text.matches("\n*SURFACE").count();
    let elsets = text.matches("\n*ELEMENT").count();
    eprintln!(
        "wrote {} ({} element blocks, {} surfaces)",
        out.display(),
        elsets,
        surfaces
    );
    ExitCode::SUCCESS
}
