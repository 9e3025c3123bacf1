//! `jointlin modes SCENE`: the modes with every closed joint stuck, labelled, in the
//! scene's units; with `--out`, modes.csv and modes.vtu.

use std::path::PathBuf;
use std::process::ExitCode;

use jointlin_harness::input::scene::Reading;
use jointlin_harness::model::{self, Kind};
use jointlin_harness::report::modes::ModeTable;
use jointlin_harness::settings::units::frequency_unit;
use jointlin_harness::solve::modal_stuck::{stuck_modes, ModeCount};
use jointlin_harness::util::atomic;
use jointlin_harness::util::csv_table::CsvTable;
use jointlin_harness::util::number::exact;
use jointlin_harness::util::number::sig;
use jointlin_harness::util::progress::progress_bar;

use super::{load_scene_for, print_findings, SceneOverrides};

// The command's help is the doc comment of `Command::Modes`.
#[derive(clap::Args)]
pub struct Args {
    /// Scene file (TOML) or Abaqus-format deck (.inp); [sweep], [[excitation]] and
    /// [[outputs]] may be left out.
    scene: PathBuf,
    #[command(flatten)]
    overrides: SceneOverrides,
    /// Number of modes (default: every mode below 1.5 × the sweep's highest frequency,
    /// at least 6, at most 200).
    #[arg(long)]
    count: Option<usize>,
    /// Directory for modes.csv and modes.vtu (created if missing).
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress (the stage and elapsed time, on stderr).
    #[arg(long)]
    quiet: bool,
}

pub fn main(a: Args) -> ExitCode {
    if a.count == Some(0) {
        eprintln!("error: --count must be at least 1");
        return ExitCode::from(2);
    }
    let s = match load_scene_for(&a.scene, &a.overrides.set, Reading::Free) {
        Ok(s) => s,
        Err(code) => return code,
    };
    if model::kind(&s) == Kind::Lumped {
        return lumped_modes(&a, &s);
    }
    // A deck's *FREQUENCY step says how many modes, unless --count does.
    let deck_modes = s.deck.as_ref().and_then(|d| d.frequency_modes());
    let count = a
        .count
        .or(deck_modes)
        .map_or(ModeCount::DEFAULT, ModeCount::Exactly);
    let mut pb = progress_bar(a.quiet);
    pb.set_message("stuck modes: building the model, static step, shift-invert Lanczos");
    let modes = stuck_modes(&s, count);
    pb.finish_and_clear();
    let modes = match modes {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    print_findings(&modes.problem);
    let units = &s.spec.units;
    let unit = frequency_unit(units);
    let fu = &unit.text;
    let f = modes.band.modes.frequencies_hz();
    let top = f.last().copied().unwrap_or(0.0);
    match (modes.limit, modes.band.complete) {
        (Some(limit), true) => eprintln!(
            "{} mode(s): every one below {} {fu} (1.5 × the sweep's highest frequency), at least 6 (or every DOF)",
            f.len(),
            sig(unit.show(limit))
        ),
        (Some(limit), false) => eprintln!(
            "warning: the {} lowest modes end at {} {fu}, below the limit {} {fu}: pass --count for more",
            f.len(),
            sig(unit.show(top)),
            sig(unit.show(limit))
        ),
        (None, _) => eprintln!("{} mode(s), as asked (or every DOF)", f.len()),
    }
    if !modes.band.modes.converged {
        let worst = modes
            .band
            .modes
            .residuals
            .iter()
            .copied()
            .fold(0.0, f64::max);
        eprintln!(
            "warning: not every mode is an eigenpair to working accuracy: largest backward error {worst:.1e} (modes.csv lists each)"
        );
    }
    let table = ModeTable::new(&modes, units);
    print!("{}", table.markdown());
    if let Some(dir) = &a.out {
        // Each file complete or absent (util::atomic).
        let written = std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: {e}", dir.display()))
            .and_then(|_| atomic::write_text(&dir.join("modes.csv"), &table.csv()))
            .and_then(|_| atomic::write_text(&dir.join("modes.vtu"), &table.vtu()));
        if let Err(e) = written {
            eprintln!("error: cannot write: {e}");
            return ExitCode::from(1);
        }
        eprintln!("wrote {0}/modes.csv and {0}/modes.vtu", dir.display());
    }
    ExitCode::SUCCESS
}

/// The modes of a lumped scene (mass bodies, `[[matrices]]`, springs, joints) with every
/// joint stuck: frequencies only (no mesh for labels, effective masses or modes.vtu).
fn lumped_modes(a: &Args, s: &jointlin_harness::input::scene::Scene) -> ExitCode {
    let f = match model::lumped::build(s).and_then(|l| l.stuck_frequencies()) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(2);
        }
    };
    let unit = frequency_unit(&s.spec.units);
    let (column, fu) = (&unit.column, &unit.text);
    let limit = 1.5 * s.frequencies().last().copied().unwrap_or(0.0);
    let n = match a.count {
        Some(n) => n.min(f.len()),
        None => f.iter().filter(|&&x| x < limit).count().max(6).min(f.len()),
    };
    eprintln!(
        "{n} of {} mode(s) of the lumped system, every joint stuck (k_T0){}",
        f.len(),
        if a.count.is_none() {
            format!(
                ": every one below {} {fu}, at least 6",
                sig(unit.show(limit))
            )
        } else {
            String::new()
        }
    );
    let mut md = format!("| mode | frequency ({fu}) |\n|---:|---:|\n");
    let mut csv = CsvTable::new(["mode", column]);
    for (i, x) in f.iter().take(n).enumerate() {
        md.push_str(&format!("| {} | {} |\n", i + 1, sig(unit.show(*x))));
        csv.row([(i + 1).to_string(), exact(unit.show(*x))]);
    }
    print!("{md}");
    if let Some(dir) = &a.out {
        let written = std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: {e}", dir.display()))
            .and_then(|_| atomic::write_text(&dir.join("modes.csv"), &csv.finish()));
        if let Err(e) = written {
            eprintln!("error: cannot write: {e}");
            return ExitCode::from(1);
        }
        eprintln!(
            "wrote {}/modes.csv (a lumped system has no mesh: no modes.vtu)",
            dir.display()
        );
    }
    ExitCode::SUCCESS
}
