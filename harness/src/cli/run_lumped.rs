//! `jointlin run` of a lumped scene (mass bodies, `[[matrices]]`, springs, joints): the
//! thesis's first-order method per frequency (`mhb::first_order`: every joint's k*, d*
//! from `jointlin_linearize` consistent with its amplitude, (3.8), (3.14)), each
//! frequency started from the previous one's amplitudes; results.csv, frf.svg and
//! run.json.

use std::path::Path;
use std::process::ExitCode;

use nalgebra::Complex;
use serde_json::json;

use jointlin_harness::input::scene::units::{frequency_unit, ColumnUnits};
use jointlin_harness::input::scene::Scene;
use jointlin_harness::mhb::first_order;
use jointlin_harness::model::lumped;
use jointlin_harness::report::svg::{frf_curves, FrfCurve};
use jointlin_harness::util::atomic;
use jointlin_harness::util::csv_table::CsvTable;

/// Runs the sweep and writes results.csv (frequency, per output amplitude and phase,
/// per element its relative amplitude, status), with `plots` frf.svg (the outputs'
/// amplitudes), and run.json into `out`.
pub fn main(s: &Scene, out: &Path, plots: bool) -> ExitCode {
    let l = match lumped::build(s) {
        Ok(l) => l,
        Err(e) => {
            eprintln!("error: {}: {e}", s.file);
            return ExitCode::from(2);
        }
    };
    let units = &s.spec.units;
    let len = ColumnUnits::new(units).length;
    let fu = frequency_unit(units);
    let mut header = vec![fu.column.clone()];
    for (name, _) in &l.outputs {
        header.push(format!("{name}_amp_{len}"));
        header.push(format!("{name}_phase_deg"));
    }
    for name in &l.elements {
        header.push(format!("{name}_amplitude_{len}"));
    }
    header.push("status".into());
    let mut csv = CsvTable::new(&header);
    let mut a0 = vec![0.0; l.system.elements.len()];
    let freqs = s.frequencies();
    let mut failed = Vec::new();
    let mut curve = FrfCurve {
        label: String::new(),
        points: Vec::new(),
    };
    for &f in &freqs {
        let omega = 2.0 * std::f64::consts::PI * f;
        let mut row = vec![format!("{:e}", fu.show(f))];
        match first_order::solve(&l.system, omega, &a0) {
            Ok(x) => {
                a0 = first_order::element_amplitudes(&l.system, &x);
                let mut amps = Vec::new();
                for (_, w) in &l.outputs {
                    let v: Complex<f64> = w.iter().zip(&x).map(|(w, x)| x * *w).sum();
                    row.push(format!("{:e}", v.norm()));
                    row.push(format!("{:e}", v.arg().to_degrees()));
                    amps.push(v.norm());
                }
                curve.points.push((f, amps));
                row.extend(a0.iter().map(|a| format!("{a:e}")));
                row.push("converged".into());
            }
            Err(e) => {
                eprintln!("warning: {f:e}: {e}");
                failed.push(f);
                row.resize(header.len() - 1, String::new());
                row.push("failed".into());
            }
        }
        csv.row(&row);
    }
    let results = out.join("results.csv");
    if let Err(e) = atomic::write_text(&results, &csv.finish()) {
        eprintln!("error: {e}");
        return ExitCode::from(1);
    }
    let mut written = vec![results];
    if plots && !curve.points.is_empty() && !l.outputs.is_empty() {
        let names: Vec<String> = l.outputs.iter().map(|(n, _)| n.clone()).collect();
        let p = out.join("frf.svg");
        let title = format!("{}: first order", s.spec.title);
        match atomic::with_temp(&p, |t| frf_curves(t, &title, units, &names, &[curve])) {
            Ok(()) => written.push(p),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(1);
            }
        }
    }
    let run = json!({
        "command": "run",
        "scene": {"file": s.file, "spec": s.spec, "text": s.text},
        "units": units,
        "method": "first order (jointlin_linearize), lumped system",
        "dofs": l.dofs,
        "frequencies": freqs.len(),
        "failed_frequencies": failed,
    });
    let text = serde_json::to_string_pretty(&run).expect("json");
    match atomic::write_marker(out, &text) {
        Ok(p) => {
            eprintln!(
                "{}: lumped system, {} DOFs, {} elements; {} of {} frequencies converged",
                s.file,
                l.dofs.len(),
                l.elements.len(),
                freqs.len() - failed.len(),
                freqs.len(),
            );
            for w in written.iter().chain([&p]) {
                eprintln!("wrote {}", w.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
