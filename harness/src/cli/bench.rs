//! `jointlin bench`: cost of the nonlinear sweep relative to the linear one.

use std::process::ExitCode;

use jointlin_harness::bench::{column, contact_table, table};

// The command's help is the doc comment of `Command::Bench`.
#[derive(clap::Args)]
pub struct Args {
    /// Approximate DOF counts.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1_000usize, 10_000, 100_000])]
    dofs: Vec<usize>,
    /// Frequencies per sweep.
    #[arg(long, default_value_t = 20)]
    freqs: usize,
    /// Skip thesis mode above this DOF count (it costs passes × frequencies
    /// factorizations).
    #[arg(long, default_value_t = 20_000)]
    thesis_max_dofs: usize,
    /// Instead: cost against the number of contact points at about the first DOF
    /// count (1, 2, 4 elements per mm of thickness), fast mode only.
    #[arg(long)]
    contact_scan: bool,
    /// Instead: the first-order sweep of a box column of about the first DOF count
    /// (two boxes, one 289-point joint) by the modal route, and by the direct route at
    /// every `--direct-stride`-th of its frequencies (time and difference).
    #[arg(long, conflicts_with = "contact_scan")]
    modal_box: bool,
    /// With --modal-box: the direct route runs every this many frequencies.
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u64).range(1..))]
    direct_stride: u64,
}

pub fn main(a: Args) -> ExitCode {
    let out = &mut std::io::stdout();
    let r = if a.modal_box {
        column::modal_table(a.dofs[0], a.freqs, a.direct_stride as usize, out)
    } else if a.contact_scan {
        contact_table(a.dofs[0], a.freqs, out)
    } else {
        table(&a.dofs, a.freqs, a.thesis_max_dofs, out)
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
