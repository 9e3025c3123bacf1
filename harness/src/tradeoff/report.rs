//! The study's files: tradeoff.csv, tradeoff.md (headings in the scene's units) and
//! tradeoff.svg, each written atomically.

use super::*;
use crate::util::number::exact;

/// tradeoff.csv.
pub fn csv(t: &Tradeoff) -> String {
    let u = ColumnUnits::new(&t.units);
    let mut table = CsvTable::new([
        "family".to_string(),
        "label".into(),
        "frequency_domain".into(),
        "wall_time_s".into(),
        format!("amplitude_{}", u.length),
        "amplitude_error".into(),
        format!("energy_per_cycle_{}", u.energy),
        "energy_error".into(),
        "converged".into(),
    ]);
    for r in &t.rungs {
        table.row([
            r.family.to_string(),
            r.label.clone(),
            r.frequency_domain.to_string(),
            exact(r.seconds),
            exact(r.amplitude),
            exact(r.amplitude_error),
            exact(r.energy),
            exact(r.energy_error),
            r.converged.to_string(),
        ]);
    }
    table.finish()
}

/// tradeoff.md.
pub fn markdown(t: &Tradeoff) -> String {
    let fu = frequency_unit(&t.units);
    let (length, energy) = (
        &t.units.length,
        format!("{}·{}", t.units.force, t.units.length),
    );
    let mut s = format!(
        "`{}` at {:.6} {}. Errors are relative to the reference time-domain run (last row): **amplitude** = first-harmonic amplitude of `{}`, **energy** = total joint energy dissipated per cycle.\n\n",
        t.scene,
        fu.show(t.freq),
        fu.text,
        t.output
    );
    let _ = writeln!(
        s,
        "| rung | wall time [s] | amplitude [{length}] | amplitude error | energy per cycle [{energy}] | energy error | converged |\n|---|---:|---:|---:|---:|---:|---|"
    );
    for r in &t.rungs {
        let _ = writeln!(
            s,
            "| {} | {:.3e} | {:.5e} | {:.2e} | {:.5e} | {:.2e} | {} |",
            r.label,
            r.seconds,
            r.amplitude,
            r.amplitude_error,
            r.energy,
            r.energy_error,
            if r.converged { "yes" } else { "no" }
        );
    }
    s.push('\n');
    for l in &t.summary {
        let _ = writeln!(s, "- {l}");
    }
    s
}

/// Writes tradeoff.csv, tradeoff.md and tradeoff.svg into `dir`, each atomically (a file
/// is complete or absent).
pub fn write(dir: &Path, t: &Tradeoff) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    let a = dir.join("tradeoff.csv");
    let b = dir.join("tradeoff.md");
    let c = dir.join("tradeoff.svg");
    atomic::write_text(&a, &csv(t))?;
    atomic::write_text(&b, &markdown(t))?;
    atomic::with_temp(&c, |tmp| plot::pareto(tmp, t))?;
    Ok(vec![a, b, c])
}

/// " with coupled_slip and normal_load_variation" (the effects that are on), or nothing:
/// the rung labels' note of the point model.
pub(super) fn effects_label(coupled_slip: bool, normal_load_variation: bool) -> String {
    let on: Vec<&str> = [
        (coupled_slip, "coupled_slip"),
        (normal_load_variation, "normal_load_variation"),
    ]
    .iter()
    .filter_map(|&(on, name)| on.then_some(name))
    .collect();
    if on.is_empty() {
        String::new()
    } else {
        format!(" with {}", on.join(" and "))
    }
}
