//! `jointlin matrices import-ccx JOB --out DIR`: CalculiX's matrix storage files
//! (JOB.sti, JOB.mas, JOB.dof) as the Matrix Market files and DOF list of a
//! `[[matrices]]` model.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::formats::ccx;
use jointlin_harness::util::atomic;

// The command's help is the doc comment of `Command::Matrices`.
#[derive(clap::Subcommand)]
pub enum Args {
    /// Converts JOB.sti, JOB.mas and JOB.dof, written by a CalculiX step
    /// `*FREQUENCY, SOLVER=MATRIXSTORAGE`, into DIR/K.mtx, DIR/M.mtx (coordinate real
    /// symmetric) and DIR/dofs.csv (`node,direction`: the point is the node number).
    ImportCcx {
        /// The job name (path without extension).
        job: PathBuf,
        /// Output directory (created if missing).
        #[arg(long)]
        out: PathBuf,
    },
}

pub fn main(a: Args) -> ExitCode {
    let Args::ImportCcx { job, out } = a;
    let m = match ccx::import(&job) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("error: {}: {e}", out.display());
        return ExitCode::from(1);
    }
    for (name, text) in [
        ("K.mtx", &m.stiffness),
        ("M.mtx", &m.mass),
        ("dofs.csv", &m.dofs),
    ] {
        let p = out.join(name);
        if let Err(e) = atomic::write_text(&p, text) {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
        eprintln!("wrote {}", p.display());
    }
    eprintln!("{} DOFs", m.n);
    ExitCode::SUCCESS
}
