//! The UEXTERNALDB configuration file beside a deck, `jointlin.cfg`
//! (fortran-shim/README.md, "Where the store lives"): the file an Abaqus job run in the
//! deck's directory iterates with. A run of the deck (`jointlin run DECK.inp`) takes its
//! iteration settings from the same file, so that the harness and the Abaqus job iterate
//! alike: `initial_amplitude` (length), `rtol` (the relative tolerance), `scheme`,
//! `max_passes`. The other keys are the Abaqus job's (`atol`, `sweep_step`,
//! `kinc_numbering`, `restart_file`, `action_file`, `agree_timeout`): read, checked as
//! keys, not used (a run derives its absolute tolerance from the stuck response's
//! scale, `solve::sweep::ATOL_REL`). The syntax is the shim's: one `key = value` per
//! line, `#` or `!` starts a comment, keys and word values case-insensitive; an unknown
//! key is an error, as it is for the shim.

use std::path::{Path, PathBuf};

use super::error::{DeckError, DeckErrorKind as K, Origin};
use crate::names::SchemeName;
use crate::settings::IterationSpec;
use crate::util::provenance::SourceFile;

/// The file name the shim looks for in the job directory.
pub const CONFIG_FILE: &str = "jointlin.cfg";

/// What errors name in place of a deck keyword.
const KEYWORD: &str = "UEXTERNALDB configuration";

/// Keys of the shim that a run reads but does not use.
const JOB_KEYS: &[&str] = &[
    "atol",
    "sweep_step",
    "kinc_numbering",
    "restart_file",
    "action_file",
    "agree_timeout",
];

/// The settings a run takes from the file (unset: the scene's defaults).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ShimConfig {
    /// Where it was read.
    pub path: PathBuf,
    /// The file as read (run.json's `inputs`); absent for text not read from a file.
    pub source: Option<SourceFile>,
    /// Amplitude estimate of the first increment (length).
    pub initial_amplitude: Option<f64>,
    /// Relative tolerance |a − a*| ≤ rtol·max(a, a*) + atol.
    pub rtol: Option<f64>,
    pub scheme: Option<SchemeName>,
    pub max_passes: Option<usize>,
}

impl ShimConfig {
    /// The configuration beside deck `deck` (in its directory), if there is one.
    pub fn beside(deck: &Path) -> Result<Option<ShimConfig>, DeckError> {
        let path = deck.parent().unwrap_or(Path::new("")).join(CONFIG_FILE);
        if !path.is_file() {
            return Ok(None);
        }
        let text = std::fs::read_to_string(&path).map_err(|e| {
            origin(&path, 0).error(
                K::Io,
                KEYWORD,
                format!("cannot read {}: {e}", path.display()),
            )
        })?;
        let mut c = ShimConfig::parse(&path, &text)?;
        c.source = Some(SourceFile::of(&path.display().to_string(), text.as_bytes()));
        Ok(Some(c))
    }

    /// Parses the text of configuration file `path`.
    pub fn parse(path: &Path, text: &str) -> Result<ShimConfig, DeckError> {
        let mut c = ShimConfig {
            path: path.to_path_buf(),
            ..Default::default()
        };
        for (i, raw) in text.lines().enumerate() {
            let line = raw.split(['#', '!']).next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let err = |m: String| origin(path, i + 1).error(K::Syntax, KEYWORD, m);
            let Some((key, value)) = line.split_once('=') else {
                return Err(err(format!("`{line}`: expected key = value")));
            };
            let (key, value) = (key.trim().to_ascii_lowercase(), value.trim());
            let number = || -> Result<f64, DeckError> {
                value
                    .replace(['d', 'D'], "e")
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite() && *v >= 0.0)
                    .ok_or_else(|| err(format!("{key} = {value}: not a number >= 0")))
            };
            match key.as_str() {
                "initial_amplitude" => c.initial_amplitude = Some(number()?),
                "rtol" => c.rtol = Some(number()?),
                "max_passes" => {
                    c.max_passes =
                        Some(value.parse().map_err(|_| {
                            err(format!("max_passes = {value}: not a whole number"))
                        })?)
                }
                "scheme" => {
                    c.scheme = Some(match value.to_ascii_lowercase().as_str() {
                        "direct" => SchemeName::Direct,
                        "relaxation" => SchemeName::Relaxation,
                        "secant" => SchemeName::Secant,
                        _ => {
                            return Err(err(format!(
                                "scheme = {value}: direct, relaxation or secant"
                            )))
                        }
                    })
                }
                k if JOB_KEYS.contains(&k) => {}
                _ => return Err(err(format!("unknown key \"{key}\""))),
            }
        }
        Ok(c)
    }

    /// Sets the iteration settings the file gives.
    pub fn apply(&self, it: &mut IterationSpec) {
        if let Some(a) = self.initial_amplitude {
            it.initial_amplitude = a;
        }
        if let Some(r) = self.rtol {
            it.tolerance = r;
        }
        if let Some(s) = self.scheme {
            it.scheme = s;
        }
        if let Some(m) = self.max_passes {
            it.max_passes = m;
        }
    }
}

fn origin(path: &Path, line: usize) -> Origin {
    Origin {
        file: path.display().to_string(),
        line,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shim_s_keys_set_the_iteration_and_unknown_keys_are_errors() {
        let text = "# comment\ninitial_amplitude = 1d-6 ! estimate\nRTOL = 1e-4\nscheme = Relaxation\nmax_passes = 7\nsweep_step = 2\nrestart_file = jointlin.restart\n";
        let c = ShimConfig::parse(Path::new("d/jointlin.cfg"), text).unwrap();
        let mut it = IterationSpec::default();
        c.apply(&mut it);
        assert_eq!(
            (it.initial_amplitude, it.tolerance, it.scheme, it.max_passes),
            (1e-6, 1e-4, SchemeName::Relaxation, 7)
        );
        let e = ShimConfig::parse(Path::new("d/jointlin.cfg"), "rtol = 1e-3\nmode = fast\n")
            .unwrap_err();
        assert_eq!((e.line, e.message.as_str()), (2, "unknown key \"mode\""));
        let e = ShimConfig::parse(Path::new("c.cfg"), "rtol = -1\n").unwrap_err();
        assert!(e.message.contains("not a number"), "{e}");
    }
}
