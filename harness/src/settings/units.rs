//! The scene's `[units]` and their names for column headers, table headings and axis
//! labels. Column names append the unit with `_` (products) and `_per_` (quotients),
//! e.g. `dissipated_power_N_mm_per_s`; labels write it as text, e.g. `N·mm/s`.

use serde::{Deserialize, Serialize};

/// The scene's unit system, stated (names only; the numbers must be consistent with
/// them: mass = force·time²/length).
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Units {
    pub length: String,
    pub force: String,
    pub time: String,
    pub mass: String,
    /// How outputs show frequencies: `"Hz"` (time in s) or `"1/<time>"`, cycles per time
    /// unit (the default), or `"rad/<time>"`, angular frequency ω = 2πf. Display only:
    /// `[sweep]` and `[[refine]]` frequencies stay in cycles per time unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency: Option<String>,
}

/// How outputs show frequencies (`[units] frequency`).
#[derive(Debug, Clone, PartialEq)]
pub struct FrequencyUnit {
    /// Column name, e.g. `frequency_Hz`, `frequency_per_ms`, `angular_frequency_rad_per_s`.
    pub column: String,
    /// Text for labels and headings, e.g. `Hz`, `1/ms`, `rad/s`.
    pub text: String,
    /// Shown value per frequency in cycles per time unit: 1, or 2π for angular.
    pub factor: f64,
}

impl FrequencyUnit {
    /// A frequency f (cycles per time unit) as shown.
    pub fn show(&self, f: f64) -> f64 {
        f * self.factor
    }

    /// The unit part of the column name for file and field names: `Hz`, `per_ms`,
    /// `rad_per_s`.
    pub fn suffix(&self) -> &str {
        self.column
            .rsplit("frequency_")
            .next()
            .unwrap_or(&self.column)
    }
}

/// The frequency unit outputs use: cycles per time unit (`Hz` for seconds), or angular
/// (`rad/<time>`) when `[units] frequency` says so.
pub fn frequency_unit(units: &Units) -> FrequencyUnit {
    let t = column_word(&units.time);
    if units.frequency.as_deref() == Some(&angular_text(units)) {
        FrequencyUnit {
            column: format!("angular_frequency_rad_per_{t}"),
            text: angular_text(units),
            factor: 2.0 * std::f64::consts::PI,
        }
    } else if units.time == "s" {
        FrequencyUnit {
            column: "frequency_Hz".into(),
            text: "Hz".into(),
            factor: 1.0,
        }
    } else {
        FrequencyUnit {
            column: format!("frequency_per_{t}"),
            text: format!("1/{}", units.time),
            factor: 1.0,
        }
    }
}

/// The accepted spellings of `[units] frequency` for these units: the cycles unit
/// (`Hz` for seconds, always `1/<time>`) and the angular one (`rad/<time>`).
pub fn frequency_spellings(units: &Units) -> Vec<String> {
    let mut v = vec![format!("1/{}", units.time), angular_text(units)];
    if units.time == "s" {
        v.insert(0, "Hz".into());
    }
    v
}

fn angular_text(units: &Units) -> String {
    format!("rad/{}", units.time)
}

/// A unit name as part of a column name: white space becomes `-` (a deck without a
/// units comment has "deck length": `tip_amp_deck-length`).
fn column_word(unit: &str) -> String {
    unit.split_whitespace().collect::<Vec<_>>().join("-")
}

/// The frequency column's name (`frequency_Hz` or `frequency_per_<time>`).
pub fn frequency_column(units: &Units) -> String {
    frequency_unit(units).column
}

/// Column suffixes of the derived quantities of a run's tables.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ColumnUnits {
    /// Length, e.g. `mm`.
    pub length: String,
    /// Pressure force/length², e.g. `N_per_mm2`.
    pub pressure: String,
    /// Energy force·length, e.g. `N_mm`.
    pub energy: String,
    /// Power force·length/time, e.g. `N_mm_per_s`.
    pub power: String,
    /// Stiffness per area force/length³, e.g. `N_per_mm3`.
    pub stiffness_per_area: String,
    /// Damping per area force·time/length³, e.g. `N_s_per_mm3`.
    pub damping_per_area: String,
}

impl ColumnUnits {
    /// The suffixes of `units`.
    pub fn new(units: &Units) -> Self {
        let (l, f, t) = (
            column_word(&units.length),
            column_word(&units.force),
            column_word(&units.time),
        );
        ColumnUnits {
            length: l.clone(),
            pressure: format!("{f}_per_{l}2"),
            energy: format!("{f}_{l}"),
            power: format!("{f}_{l}_per_{t}"),
            stiffness_per_area: format!("{f}_per_{l}3"),
            damping_per_area: format!("{f}_{t}_per_{l}3"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn units(length: &str, force: &str, time: &str) -> Units {
        Units {
            length: length.into(),
            force: force.into(),
            time: time.into(),
            mass: "t".into(),
            frequency: None,
        }
    }

    #[test]
    fn frequency_follows_the_time_unit() {
        let (hz, per_ms) = (
            frequency_unit(&units("mm", "N", "s")),
            frequency_unit(&units("mm", "N", "ms")),
        );
        assert_eq!(
            (hz.column.as_str(), hz.text.as_str()),
            ("frequency_Hz", "Hz")
        );
        assert_eq!(
            (per_ms.column.as_str(), per_ms.text.as_str()),
            ("frequency_per_ms", "1/ms")
        );
        assert_eq!((hz.factor, hz.suffix()), (1.0, "Hz"));
        assert_eq!(per_ms.suffix(), "per_ms");
    }

    #[test]
    fn a_declared_angular_unit_shows_two_pi_f() {
        let mut u = units("mm", "N", "ms");
        u.frequency = Some("rad/ms".into());
        let w = frequency_unit(&u);
        assert_eq!(w.column, "angular_frequency_rad_per_ms");
        assert_eq!((w.text.as_str(), w.suffix()), ("rad/ms", "rad_per_ms"));
        assert_eq!(w.show(1.0), 2.0 * std::f64::consts::PI);
        assert_eq!(frequency_spellings(&u), ["1/ms", "rad/ms"]);
        // Cycles spelled out keep the default.
        u.frequency = Some("1/ms".into());
        assert_eq!(frequency_unit(&u).factor, 1.0);
    }

    #[test]
    fn unit_names_with_spaces_make_one_column_word() {
        let c = ColumnUnits::new(&units("deck length", "deck force", "deck time"));
        assert_eq!(c.power, "deck-force_deck-length_per_deck-time");
        assert_eq!(
            frequency_column(&units("m", "N", "deck time")),
            "frequency_per_deck-time"
        );
    }

    #[test]
    fn derived_columns_follow_every_unit() {
        let c = ColumnUnits::new(&units("m", "kN", "ms"));
        assert_eq!(c.length, "m");
        assert_eq!(c.pressure, "kN_per_m2");
        assert_eq!(c.energy, "kN_m");
        assert_eq!(c.power, "kN_m_per_ms");
        assert_eq!(c.stiffness_per_area, "kN_per_m3");
        assert_eq!(c.damping_per_area, "kN_ms_per_m3");
    }
}
