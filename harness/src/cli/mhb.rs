//! `jointlin mhb`: cost vs H of the multi-harmonic balance, on the 3-DOF Jenkins chain or
//! on FE scenes.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::bench::{mhb_chain, mhb_fe};

use super::load_scene;

// The command's help is the doc comment of `Command::Mhb`.
#[derive(clap::Args)]
pub struct Args {
    /// Harmonics to run (the last row is the reference of the deviation column).
    #[arg(long, value_delimiter = ',', default_values_t = vec![1usize, 3, 7, 15])]
    harmonics: Vec<usize>,
    /// Frequencies per sweep (default 200 for the chain, 5 for scenes).
    #[arg(long)]
    freqs: Option<usize>,
    /// FE scenes to run instead of the chain (e.g. scenes/three-beams-coarse.toml,
    /// scenes/three-beams.toml).
    #[arg(long, value_delimiter = ',')]
    scene: Vec<PathBuf>,
    /// Band f_min,f_max (1/time) for scenes; default each scene's first refine band.
    #[arg(long, value_delimiter = ',', num_args = 2)]
    band: Vec<f64>,
    /// Print the cost of backbones of the chain instead (first order, EPMC H = 1, 3, 7),
    /// and with --scene of the FE scenes' first-order backbones and their reduction.
    #[arg(long)]
    backbones: bool,
    /// Force amplitude on the last mass.
    #[arg(long, default_value_t = 0.05)]
    force: f64,
}

pub fn main(a: Args) -> ExitCode {
    if a.backbones {
        use jointlin_harness::bench::backbone;
        println!("{}", backbone::table());
        if a.scene.is_empty() {
            return ExitCode::SUCCESS;
        }
        let mut t = backbone::FE_HEADER.to_string();
        for path in &a.scene {
            let s = match load_scene(path) {
                Ok(s) => s,
                Err(code) => return code,
            };
            match backbone::fe_row(&s) {
                Ok(r) => t += &r,
                Err(e) => {
                    eprintln!("error: {}: {e}", path.display());
                    return ExitCode::from(1);
                }
            }
        }
        println!("{t}");
        return ExitCode::SUCCESS;
    }
    if a.scene.is_empty() {
        let freqs = a.freqs.unwrap_or(200);
        let rows = mhb_chain::sweep_table(a.force, 0.3, 0.8, freqs, &a.harmonics);
        println!("{}", mhb_chain::markdown(&rows, a.force, 0.3, 0.8, freqs));
        return ExitCode::SUCCESS;
    }
    for path in &a.scene {
        let s = match load_scene(path) {
            Ok(s) => s,
            Err(code) => return code,
        };
        let band = (a.band.len() == 2).then(|| (a.band[0], a.band[1]));
        let log = |l: &str| eprintln!("{}: {l}", path.display());
        match mhb_fe::table(&s, band, a.freqs.unwrap_or(5), &a.harmonics, &log) {
            Ok(t) => println!("{}", mhb_fe::markdown(&t)),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    }
    ExitCode::SUCCESS
}
