//! The keywords the reader implements, each with the parameters it implements: the one
//! list the reader checks every card against (a parameter not listed is an error
//! `file:line: *KEYWORD, PARAMETER=: …`, never skipped) and the keyword table of docs/own-model.md
//! prints (`jointlin check --keywords`).

use super::error::{DeckError, DeckErrorKind};
use super::lexer::Card;

/// How a parameter is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Form {
    /// `NAME` alone (a value is an error).
    Flag,
    /// `NAME=value` (a missing value is an error).
    Value,
}

/// One parameter a keyword implements and what the reader makes of it.
#[derive(Debug, Clone, Copy)]
pub struct Param {
    /// Upper case, single spaces.
    pub name: &'static str,
    pub form: Form,
    /// What it means here (one line for the keyword table).
    pub reading: &'static str,
}

/// One implemented keyword: its parameters and the most fields a data line may have.
#[derive(Debug, Clone, Copy)]
pub struct Keyword {
    /// Upper case, single spaces.
    pub name: &'static str,
    pub params: &'static [Param],
    /// Most non-empty fields of one data line (`None`: any, the handler reads them all).
    pub fields: Option<usize>,
}

const fn flag(name: &'static str, reading: &'static str) -> Param {
    Param {
        name,
        form: Form::Flag,
        reading,
    }
}

const fn value(name: &'static str, reading: &'static str) -> Param {
    Param {
        name,
        form: Form::Value,
        reading,
    }
}

const LOAD_PARAMS: &[Param] = &[
    value("OP", "MOD (the default) only"),
    flag("REAL", "the real part (the default)"),
    flag("IMAGINARY", "the imaginary part of a steady-state load"),
    value(
        "AMPLITUDE",
        "refused: a frequency-dependent load is not read",
    ),
];

/// Every keyword the reader implements.
pub const KEYWORDS: &[Keyword] = &[
    Keyword {
        name: "HEADING",
        params: &[],
        fields: None,
    },
    Keyword {
        name: "NODE",
        params: &[
            value("NSET", "the nodes also form this set"),
            value("SYSTEM", "R (x, y, z), C (r, θ°, z) or S (r, θ°, φ°)"),
            value("INPUT", "the data lines from this file"),
        ],
        fields: Some(4),
    },
    Keyword {
        name: "ELEMENT",
        params: &[
            value("TYPE", "C3D4, C3D10, C3D6, C3D15, C3D8, C3D8I, C3D20, C3D20R"),
            value("ELSET", "the elements also form this set"),
            value("INPUT", "the data lines from this file"),
        ],
        fields: None,
    },
    Keyword {
        name: "NSET",
        params: &[
            value("NSET", "the set's name"),
            value("ELSET", "the nodes of this element set"),
            flag("GENERATE", "data lines first, last, increment"),
            value("INSTANCE", "ids and names of that instance"),
            flag("INTERNAL", "no meaning for a run"),
            flag("UNSORTED", "no meaning for a run (a set)"),
            value("INPUT", "the data lines from this file"),
        ],
        fields: None,
    },
    Keyword {
        name: "ELSET",
        params: &[
            value("ELSET", "the set's name"),
            flag("GENERATE", "data lines first, last, increment"),
            value("INSTANCE", "ids and names of that instance"),
            flag("INTERNAL", "no meaning for a run"),
            flag("UNSORTED", "no meaning for a run (a set)"),
            value("INPUT", "the data lines from this file"),
        ],
        fields: None,
    },
    Keyword {
        name: "SURFACE",
        params: &[
            value("NAME", "the surface's name"),
            value("TYPE", "ELEMENT (faces, the default) or NODE"),
            flag("INTERNAL", "no meaning for a run"),
        ],
        fields: Some(2),
    },
    Keyword {
        name: "MATERIAL",
        params: &[value("NAME", "the material's name")],
        fields: None,
    },
    Keyword {
        name: "ELASTIC",
        params: &[value("TYPE", "ISOTROPIC only")],
        fields: Some(2),
    },
    Keyword {
        name: "DENSITY",
        params: &[],
        fields: Some(1),
    },
    Keyword {
        name: "DAMPING",
        params: &[
            value("ALPHA", "Rayleigh mass factor α (1/time)"),
            value("BETA", "Rayleigh stiffness factor β (time)"),
            value(
                "STRUCTURAL",
                "structural damping s: i·s·K of the material in steady-state steps",
            ),
        ],
        fields: Some(0),
    },
    Keyword {
        name: "SOLID SECTION",
        params: &[
            value("ELSET", "the elements"),
            value("MATERIAL", "their material"),
        ],
        fields: Some(1),
    },
    Keyword {
        name: "SURFACE INTERACTION",
        params: &[
            value("NAME", "the interaction's name"),
            flag("USER", "required: the jointlin law"),
            value("DEPVAR", "state variables per point"),
            value("PROPERTIES", "number of property values"),
        ],
        fields: None,
    },
    Keyword {
        name: "CONTACT PAIR",
        params: &[
            value("INTERACTION", "the USER interaction"),
            value("TYPE", "NODE TO SURFACE only"),
            flag(
                "SMALL SLIDING",
                "how Abaqus tracks; a run's points never slide apart",
            ),
        ],
        fields: Some(2),
    },
    Keyword {
        name: "TIE",
        params: &[
            value("NAME", "the tie's name"),
            value(
                "POSITION TOLERANCE",
                "slave nodes farther from the master surface are an error",
            ),
            value(
                "ADJUST",
                "YES (the default) or NO: slave nodes are not moved; gaps are reported",
            ),
            value(
                "TYPE",
                "NODE TO SURFACE, or SURFACE TO SURFACE where the tie is conforming (the two agree there)",
            ),
        ],
        fields: Some(2),
    },
    Keyword {
        name: "BOUNDARY",
        params: &[
            value("OP", "MOD (the default) only"),
            value("TYPE", "DISPLACEMENT (the default) only"),
        ],
        fields: Some(4),
    },
    Keyword {
        name: "STEP",
        params: &[
            value("NAME", "the step's name"),
            flag("PERTURBATION", "a linear perturbation step"),
            value("NLGEOM", "NO only"),
            value("INC", "no meaning for a linear step"),
        ],
        fields: None,
    },
    Keyword {
        name: "STATIC",
        params: &[flag("DIRECT", "no meaning for a linear step")],
        fields: Some(4),
    },
    Keyword {
        name: "FREQUENCY",
        params: &[
            value("EIGENSOLVER", "LANCZOS, SUBSPACE or AMS: the same modes"),
            value(
                "STORAGE",
                "YES or NO (CalculiX): the modes are kept for a modal steady state either way",
            ),
            value(
                "NORMALIZATION",
                "DISPLACEMENT or MASS (mode shapes are not written)",
            ),
            value("SIM", "no meaning for a run (the same modes)"),
            value("ACOUSTIC COUPLING", "no meaning for a run (no acoustic elements)"),
        ],
        fields: Some(1),
    },
    Keyword {
        name: "STEADY STATE DYNAMICS",
        params: &[
            flag(
                "DIRECT",
                "a direct solve per frequency; without it mode-based on the *FREQUENCY step's modes (the modal route, no residual flexibility, as Abaqus and CalculiX)",
            ),
            value("FREQUENCY SCALE", "LOGARITHMIC (the default) or LINEAR"),
            value(
                "INTERVAL",
                "RANGE (DIRECT's default) or EIGENFREQUENCY (the mode-based default: each range divided at the stuck eigenfrequencies inside it, bias 3)",
            ),
            value("FRICTION DAMPING", "NO (the default) only: friction is jointlin's"),
        ],
        fields: Some(4),
    },
    Keyword {
        name: "MODAL DAMPING",
        params: &[
            flag(
                "RAYLEIGH",
                "data lines first mode, last mode (blank: all), α, β: ζ_r = α/(2ω_r) + βω_r/2",
            ),
            value("DEFINITION", "MODE NUMBERS (the default) only"),
            value(
                "VISCOUS",
                "FRACTION OF CRITICAL DAMPING (the default) only: first mode, last mode, ζ",
            ),
        ],
        fields: Some(4),
    },
    Keyword {
        name: "CLOAD",
        params: LOAD_PARAMS,
        fields: Some(3),
    },
    Keyword {
        name: "DLOAD",
        params: LOAD_PARAMS,
        fields: Some(3),
    },
    Keyword {
        name: "DSLOAD",
        params: LOAD_PARAMS,
        fields: Some(3),
    },
    Keyword {
        name: "NODE PRINT",
        params: &[
            value("NSET", "the nodes printed"),
            value("FREQUENCY", "no meaning for a run"),
            value("SUMMARY", "no meaning for a run"),
            value("TOTALS", "no meaning for a run"),
            value("GLOBAL", "no meaning for a run"),
        ],
        fields: None,
    },
    Keyword {
        name: "NODE OUTPUT",
        params: &[value("NSET", "the nodes written")],
        fields: None,
    },
    Keyword {
        name: "OUTPUT",
        params: &[
            flag("FIELD", "no meaning for a run"),
            flag("HISTORY", "no meaning for a run"),
            value("FREQUENCY", "no meaning for a run"),
            value("NUMBER INTERVAL", "no meaning for a run"),
            value("TIME INTERVAL", "no meaning for a run"),
            value("VARIABLE", "no meaning for a run"),
            value("OP", "no meaning for a run"),
        ],
        fields: Some(0),
    },
    Keyword {
        name: "END STEP",
        params: &[],
        fields: Some(0),
    },
    Keyword {
        name: "PART",
        params: &[value("NAME", "the part's name")],
        fields: Some(0),
    },
    Keyword {
        name: "END PART",
        params: &[],
        fields: Some(0),
    },
    Keyword {
        name: "ASSEMBLY",
        params: &[value("NAME", "no meaning for a run")],
        fields: Some(0),
    },
    Keyword {
        name: "END ASSEMBLY",
        params: &[],
        fields: Some(0),
    },
    Keyword {
        name: "INSTANCE",
        params: &[
            value("NAME", "the instance's name"),
            value("PART", "the part it instantiates"),
        ],
        fields: Some(3),
    },
    Keyword {
        name: "END INSTANCE",
        params: &[],
        fields: Some(0),
    },
    Keyword {
        name: "INCLUDE",
        params: &[value("INPUT", "the file read in its place")],
        fields: Some(0),
    },
];

/// The implemented keyword `name` (upper case), if it is one.
pub fn keyword(name: &str) -> Option<&'static Keyword> {
    KEYWORDS.iter().find(|k| k.name == name)
}

/// Checks `card`'s parameters against its keyword's list: an unlisted parameter, a
/// flag with a value, a value parameter without one, or a parameter given twice is an
/// error at the keyword line naming `*KEYWORD, PARAMETER=`.
pub fn check_params(card: &Card, kw: &Keyword) -> Result<(), DeckError> {
    for (i, (name, v)) in card.params.iter().enumerate() {
        let shown = format!("*{}, {name}=", kw.name);
        let err = |kind, m: String| Err(card.origin.error(kind, &shown, m));
        let Some(p) = kw.params.iter().find(|p| p.name == name) else {
            let known: Vec<&str> = kw.params.iter().map(|p| p.name).collect();
            return err(
                DeckErrorKind::Unsupported,
                format!(
                    "parameter not supported (this reader implements {})",
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ),
            );
        };
        if card.params[..i].iter().any(|(n, _)| n == name) {
            return err(DeckErrorKind::Duplicate, "given twice".into());
        }
        match p.form {
            Form::Flag if !v.is_empty() => {
                return err(
                    DeckErrorKind::Syntax,
                    format!("a flag takes no value (got {v:?})"),
                )
            }
            Form::Value if v.is_empty() => {
                return err(DeckErrorKind::Syntax, "needs a value".into())
            }
            _ => {}
        }
    }
    Ok(())
}

/// Checks that no data line of `card` has more non-empty fields than `kw.fields`.
pub fn check_fields(card: &Card, kw: &Keyword) -> Result<(), DeckError> {
    let Some(max) = kw.fields else {
        return Ok(());
    };
    for l in &card.data {
        let n = l
            .fields
            .iter()
            .rposition(|f| !f.is_empty())
            .map_or(0, |i| i + 1);
        if n > max {
            return Err(card.error_at(
                l.line,
                DeckErrorKind::Unsupported,
                format!(
                    "{n} fields on a data line: this reader implements {max} (field {} and after would not be read)",
                    max + 1
                ),
            ));
        }
    }
    Ok(())
}

/// The keyword table (docs/own-model.md): each keyword with the parameters it implements.
pub fn markdown_table() -> String {
    let mut s = String::from("| keyword | parameters (what a run makes of them) |\n|---|---|\n");
    for k in KEYWORDS {
        let params: Vec<String> = k
            .params
            .iter()
            .map(|p| match p.form {
                Form::Flag => format!("`{}` ({})", p.name, p.reading),
                Form::Value => format!("`{}=` ({})", p.name, p.reading),
            })
            .collect();
        let params = if params.is_empty() {
            "none".to_string()
        } else {
            params.join("; ")
        };
        s.push_str(&format!("| `*{}` | {params} |\n", k.name));
    }
    s
}
