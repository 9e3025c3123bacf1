//! What a run takes from a deck, checked: the stated units, the one static (preload)
//! step, the one `*FREQUENCY` step, the one steady-state step with its frequencies, the
//! node outputs. Whatever a run cannot honour is a `file:line: *KEYWORD: message` error
//! here, before anything is built (the contact pairs' property tables are checked where
//! they become interfaces, `model::deck`).

use super::error::{DeckError, DeckErrorKind as K, DeckWarning};
use super::model::{Deck, FrequencyScale, NodeTarget, Procedure, Step};
use super::props::user_law;
use crate::names::ContactLaw;
use crate::settings::{
    BandSpec, Interval, ModalDampingSpec, OutputSpec, Spacing, SweepMethod, SweepSpec, Units,
};

/// The comment line that states a deck's units (decks carry none):
/// `** jointlin units: length=mm force=N time=s mass=t`.
pub const UNITS_COMMENT: &str = "jointlin units:";

/// A deck read and checked for a run.
#[derive(Debug, Clone, PartialEq)]
pub struct DeckJob {
    /// File name as given (for messages).
    pub file: String,
    pub deck: Deck,
    /// The reader's warnings and the run's own (outputs it does not write).
    pub warnings: Vec<DeckWarning>,
    /// Stated by [`UNITS_COMMENT`], else "deck length", "deck force", … .
    pub units: Units,
    /// Index into `deck.steps` of the `*STATIC` step (the preload), if any.
    pub preload: Option<usize>,
    /// Index of the `*FREQUENCY` step, if any.
    pub frequency: Option<usize>,
    /// Index of the `*STEADY STATE DYNAMICS` step, if any.
    pub dynamics: Option<usize>,
    /// The contact law of each contact pair (in `deck.contact_pairs` order).
    pub laws: Vec<ContactLaw>,
}

impl DeckJob {
    /// Reads deck `path` and checks it for a run.
    pub fn load(path: &std::path::Path) -> Result<DeckJob, DeckError> {
        let (deck, warnings) = super::read(path)?;
        let file = path.display().to_string();
        let text = std::fs::read_to_string(path).unwrap_or_default();
        DeckJob::new(file, &text, deck, warnings)
    }

    /// Checks a read deck (`text`: the main file's text, for the units comment).
    pub fn new(
        file: String,
        text: &str,
        deck: Deck,
        mut warnings: Vec<DeckWarning>,
    ) -> Result<DeckJob, DeckError> {
        super::size::check(&file, &deck)?;
        let units = stated_units(&file, text)?.unwrap_or_else(|| Units {
            length: "deck length".into(),
            force: "deck force".into(),
            time: "deck time".into(),
            mass: "deck mass".into(),
            frequency: None,
        });
        let StepRoles {
            preload,
            frequency,
            dynamics,
        } = step_roles(&deck)?;
        check_boundaries(&deck)?;
        note_outputs(&deck, &mut warnings);
        let laws = deck
            .contact_pairs
            .iter()
            .map(|c| user_law(c, &deck.interactions[&c.interaction]))
            .collect::<Result<Vec<_>, _>>()?;
        for s in &deck.sections {
            let m = &deck.materials[&s.material];
            if m.density.is_none() {
                return Err(m.origin.error(
                    K::BadValue,
                    "*MATERIAL",
                    format!("material {} has no *DENSITY: a run needs the mass", m.name),
                ));
            }
        }
        if deck.elements.is_empty() {
            return Err(DeckError {
                kind: K::Undefined,
                file,
                line: 0,
                keyword: "*ELEMENT".into(),
                message: "the deck has no elements: a run needs a mesh".into(),
            });
        }
        Ok(DeckJob {
            file,
            deck,
            warnings,
            units,
            preload,
            frequency,
            dynamics,
            laws,
        })
    }

    /// The steady-state step's frequencies as a scene sweep (1/time), if it has one: its
    /// first data line is the sweep's range, every further line a band of its own
    /// (`refine`; checked by [`check_step`] to be linearly spaced or of at most two
    /// points, which a band reproduces).
    pub fn sweep(&self) -> Option<SweepSpec> {
        let st = &self.deck.steps[self.dynamics?];
        let Procedure::SteadyState {
            ranges,
            scale,
            direct,
            eigen_intervals,
        } = &st.procedure
        else {
            return None;
        };
        let (first, more) = ranges.split_first()?;
        Some(SweepSpec {
            f_min: first.f_low,
            f_max: first.f_high,
            count: first.points,
            spacing: match scale {
                FrequencyScale::Linear => Spacing::Linear,
                FrequencyScale::Logarithmic => Spacing::Log,
            },
            bias: first.bias,
            refine: more
                .iter()
                .map(|r| BandSpec {
                    f_min: r.f_low,
                    f_max: r.f_high,
                    count: r.points,
                    bias: r.bias,
                })
                .collect(),
            direction: Default::default(),
            // Mode-based: the *FREQUENCY step's modes, without residual flexibility
            // (what Abaqus and CalculiX compute from the same deck).
            method: if *direct {
                SweepMethod::Direct
            } else {
                SweepMethod::Modal
            },
            modes: (!*direct).then(|| self.frequency_modes()).flatten(),
            residual: (!*direct).then_some(false),
            interval: if *eigen_intervals {
                Interval::Eigenfrequency
            } else {
                Interval::Range
            },
            modal_damping: st
                .modal_damping
                .iter()
                .map(|(d, _)| ModalDampingSpec {
                    first_mode: d.first,
                    last_mode: d.last,
                    ratio: d.ratio,
                    alpha: d.alpha,
                    beta: d.beta,
                })
                .collect(),
        })
    }

    /// Modes asked for by the `*FREQUENCY` step, if it exists.
    pub fn frequency_modes(&self) -> Option<usize> {
        match self.deck.steps[self.frequency?].procedure {
            Procedure::Frequency { modes } => Some(modes),
            _ => None,
        }
    }

    /// The node outputs of every step as named outputs, one per node of each U set and
    /// component: `<SET>_<node id>_u<1|2|3>` (the set names the body: the output is
    /// that node, along that axis).
    pub fn outputs(&self) -> Vec<OutputSpec> {
        let mut out: Vec<OutputSpec> = Vec::new();
        for st in &self.deck.steps {
            for o in &st.outputs {
                for id in &self.deck.node_sets[&o.node_set] {
                    // CSV column names: instance sets' dots become dashes.
                    let set = o.node_set.replace(
                        |ch: char| !(ch.is_ascii_alphanumeric() || ch == '_' || ch == '-'),
                        "-",
                    );
                    for c in 0..3 {
                        let name = format!("{set}_{id}_u{}", c + 1);
                        if out.iter().any(|x| x.name == name) {
                            continue;
                        }
                        let mut direction = [0.0; 3];
                        direction[c] = 1.0;
                        out.push(OutputSpec {
                            name,
                            body: o.node_set.clone(),
                            at: self.deck.node(*id),
                            direction,
                        });
                    }
                }
            }
        }
        out
    }

    /// The deck's nodes named by a target (a node id or a node set), as node ids.
    pub fn target_nodes(&self, t: &NodeTarget) -> Vec<u64> {
        match t {
            NodeTarget::Node(id) => vec![*id],
            NodeTarget::Set(s) => self.deck.node_sets[s].clone(),
        }
    }
}

/// A step's content that a run cannot honour: loads in a `*FREQUENCY` step, imaginary
/// loads in a `*STATIC` step, rotational load DOFs, logarithmic spacing on data lines
/// after the first.
fn check_step(st: &Step) -> Result<(), DeckError> {
    match st.procedure {
        Procedure::Static => {
            let imaginary = (st.cloads.iter().filter(|l| l.imaginary).map(|l| &l.origin))
                .chain(st.dloads.iter().filter(|l| l.imaginary).map(|l| &l.origin))
                .chain(st.dsloads.iter().filter(|l| l.imaginary).map(|l| &l.origin))
                .next();
            if let Some(o) = imaginary {
                return Err(o.error(
                    K::Unsupported,
                    "*STATIC",
                    "an IMAGINARY load in a static step: only steady-state loads have a phase",
                ));
            }
        }
        Procedure::Frequency { .. } => {
            let load = st
                .cloads
                .first()
                .map(|l| &l.origin)
                .or(st.dloads.first().map(|l| &l.origin))
                .or(st.dsloads.first().map(|l| &l.origin));
            if let Some(o) = load {
                return Err(o.error(
                    K::Unsupported,
                    "*FREQUENCY",
                    "loads in a frequency step: modes take none",
                ));
            }
        }
        Procedure::SteadyState {
            ref ranges, scale, ..
        } => {
            let err = |m: String| Err(st.origin.error(K::Unsupported, "*STEADY STATE DYNAMICS", m));
            let log = scale == FrequencyScale::Logarithmic;
            if let Some((i, r)) = ranges
                .iter()
                .enumerate()
                .skip(1)
                .find(|(_, r)| log && r.points > 2)
            {
                return err(format!(
                    "data line {}: {} logarithmically spaced points from {} to {}: a run spaces the lines after the first linearly (FREQUENCY SCALE=LINEAR, or single frequencies)",
                    i + 1,
                    r.points,
                    r.f_low,
                    r.f_high
                ));
            }
        }
    }
    for l in &st.cloads {
        if !(1..=3).contains(&l.dof) {
            return Err(l.origin.error(
                K::Unsupported,
                "*CLOAD",
                format!("DOF {}: solid nodes carry forces in DOFs 1–3 only", l.dof),
            ));
        }
    }
    Ok(())
}

/// The units of a `** jointlin units: length=mm force=N time=s mass=t` line of `text`,
/// if there is one; a malformed one is an error at its line.
pub fn stated_units(file: &str, text: &str) -> Result<Option<Units>, DeckError> {
    for (i, line) in text.lines().enumerate() {
        let Some(rest) = line.trim().strip_prefix("**") else {
            continue;
        };
        let Some(list) = rest.trim().strip_prefix(UNITS_COMMENT) else {
            continue;
        };
        let err = |m: String| DeckError {
            kind: K::Syntax,
            file: file.to_string(),
            line: i + 1,
            keyword: "**".into(),
            message: m,
        };
        let mut u = [None, None, None, None];
        for item in list.split_whitespace() {
            let Some((k, v)) = item.split_once('=') else {
                return Err(err(format!(
                    "`{item}`: units are key=value (length=mm force=N time=s mass=t)"
                )));
            };
            let slot = match k.to_ascii_lowercase().as_str() {
                "length" => 0,
                "force" => 1,
                "time" => 2,
                "mass" => 3,
                _ => {
                    return Err(err(format!(
                        "unknown unit `{k}` (length, force, time, mass)"
                    )))
                }
            };
            if v.is_empty() {
                return Err(err(format!("`{item}`: the unit of {k} is empty")));
            }
            u[slot] = Some(v.to_string());
        }
        let [Some(length), Some(force), Some(time), Some(mass)] = u else {
            return Err(err("units need length, force, time and mass".into()));
        };
        let units = Units {
            length,
            force,
            time,
            mass,
            frequency: None,
        };
        if let Some((k, m)) = crate::settings::unit_names::problems(&units)
            .into_iter()
            .next()
        {
            return Err(err(format!("{k}=: {m}")));
        }
        return Ok(Some(units));
    }
    Ok(None)
}

/// Which of a deck's steps is the preload, the frequency and the steady-state step.
struct StepRoles {
    preload: Option<usize>,
    frequency: Option<usize>,
    dynamics: Option<usize>,
}

/// The indices of the deck's preload (*STATIC), *FREQUENCY and steady-state steps, each
/// at most once and in an order a run can follow; each step checked ([`check_step`]),
/// *MODAL DAMPING only where a mode-based steady state uses it.
fn step_roles(deck: &Deck) -> Result<StepRoles, DeckError> {
    let (mut preload, mut frequency, mut dynamics) = (None, None, None);
    for (i, st) in deck.steps.iter().enumerate() {
        let (slot, what) = match st.procedure {
            Procedure::Static => (&mut preload, "*STATIC"),
            Procedure::Frequency { .. } => (&mut frequency, "*FREQUENCY"),
            Procedure::SteadyState { .. } => (&mut dynamics, "*STEADY STATE DYNAMICS"),
        };
        if slot.is_some() {
            return Err(st.origin.error(
                K::Unsupported,
                "*STEP",
                format!("a second {what} step: a run has one preload, one frequency and one steady-state step"),
            ));
        }
        *slot = Some(i);
        check_step(st)?;
    }
    if let Some(d) = dynamics {
        let st = &deck.steps[d];
        let direct = matches!(st.procedure, Procedure::SteadyState { direct: true, .. });
        if !direct && frequency.is_none_or(|f| f >= d) {
            return Err(st.origin.error(
                K::Unsupported,
                "*STEADY STATE DYNAMICS",
                "mode-based (no DIRECT) needs a preceding *FREQUENCY step: its modes are the basis (or give DIRECT)",
            ));
        }
        if let (true, Some((_, o))) = (direct, st.modal_damping.first()) {
            return Err(o.error(
                K::Unsupported,
                "*MODAL DAMPING",
                "in a DIRECT steady state: modal damping damps the modes of a mode-based step (give the step without DIRECT, or material damping)",
            ));
        }
    }
    for st in &deck.steps {
        if let (false, Some((_, o))) = (
            matches!(st.procedure, Procedure::SteadyState { .. }),
            st.modal_damping.first(),
        ) {
            return Err(o.error(
                K::Unsupported,
                "*MODAL DAMPING",
                "outside a steady-state step: it damps a mode-based steady state",
            ));
        }
    }
    if let (Some(p), Some(d)) = (preload, dynamics) {
        if p > d {
            return Err(deck.steps[p].origin.error(
                K::Unsupported,
                "*STATIC",
                "the static step must come before the steady-state step it preloads",
            ));
        }
    }
    Ok(StepRoles {
        preload,
        frequency,
        dynamics,
    })
}

/// Every *BOUNDARY of the model and the steps holds its DOFs at zero.
fn check_boundaries(deck: &Deck) -> Result<(), DeckError> {
    for b in deck
        .boundaries
        .iter()
        .chain(deck.steps.iter().flat_map(|s| &s.boundaries))
    {
        if b.value != 0.0 {
            return Err(b.origin.error(
                K::Unsupported,
                "*BOUNDARY",
                format!(
                    "prescribed displacement {} on DOFs {}–{}: a run holds boundary DOFs at zero only",
                    b.value, b.first, b.last
                ),
            ));
        }
    }
    Ok(())
}

/// A warning per *NODE OUTPUT variable besides U (only U is written, as results.csv
/// columns).
fn note_outputs(deck: &Deck, warnings: &mut Vec<DeckWarning>) {
    for st in &deck.steps {
        for o in &st.outputs {
            let other: Vec<&str> = o
                .variables
                .iter()
                .map(String::as_str)
                .filter(|v| *v != "U")
                .collect();
            if !other.is_empty() {
                warnings.push(o.origin.warning(
                    "*NODE OUTPUT",
                    format!("{other:?} not written (only U, as results.csv columns)"),
                ));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_from_the_comment_line_or_none() {
        let text = "*HEADING\nx\n** jointlin units: length=mm force=N time=s mass=t\n*NODE\n";
        let u = stated_units("a.inp", text).unwrap().unwrap();
        assert_eq!([u.length, u.force, u.time, u.mass], ["mm", "N", "s", "t"]);
        assert_eq!(stated_units("a.inp", "*HEADING\n** other\n").unwrap(), None);
        let e =
            stated_units("a.inp", "*HEADING\n** jointlin units: length=mm force=N\n").unwrap_err();
        assert_eq!(
            (e.line, e.message.as_str()),
            (2, "units need length, force, time and mass")
        );
        let e = stated_units("a.inp", "** jointlin units: size=mm\n").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("a.inp:1: **: unknown unit `size`"),
            "{e}"
        );
    }
}
