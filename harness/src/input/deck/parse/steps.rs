//! Steps (`*STEP` … `*END STEP`), their procedures (`*STATIC`, `*FREQUENCY`,
//! `*STEADY STATE DYNAMICS`) and output requests.

use super::*;
use crate::input::deck::size::MAX_FREQUENCIES;

impl Reader {
    pub(super) fn procedure(&mut self, card: &Card) -> Result<(), DeckError> {
        let first = lines(card).next().cloned();
        let procedure = match card.keyword.as_str() {
            "STATIC" => Procedure::Static,
            "FREQUENCY" => {
                choice(
                    card,
                    "EIGENSOLVER",
                    &["LANCZOS", "SUBSPACE", "AMS"],
                    "LANCZOS",
                )?;
                choice(
                    card,
                    "NORMALIZATION",
                    &["DISPLACEMENT", "MASS"],
                    "DISPLACEMENT",
                )?;
                let l = first
                    .ok_or_else(|| card.error(K::Syntax, "needs a data line (number of modes)"))?;
                let f = l.fields[0].as_str();
                let modes = parse_id(f).ok_or_else(|| {
                    card.error_at(
                        l.line,
                        K::BadValue,
                        format!(
                            "number of modes {:?} is not a positive integer",
                            truncate(f)
                        ),
                    )
                })?;
                Procedure::Frequency {
                    modes: modes as usize,
                }
            }
            _ => {
                let direct = card.flag("DIRECT");
                let interval = choice(
                    card,
                    "INTERVAL",
                    &["RANGE", "EIGENFREQUENCY"],
                    if direct { "RANGE" } else { "EIGENFREQUENCY" },
                )?;
                if direct && interval == "EIGENFREQUENCY" {
                    return Err(card.error(
                        K::Unsupported,
                        "INTERVAL=EIGENFREQUENCY with DIRECT: Abaqus divides direct ranges as given (INTERVAL=RANGE)",
                    ));
                }
                let eigen_intervals = interval == "EIGENFREQUENCY";
                choice(card, "FRICTION DAMPING", &["NO"], "NO")?;
                let scale = match card
                    .param("FREQUENCY SCALE")
                    .map(|s| s.to_ascii_uppercase())
                {
                    None => FrequencyScale::Logarithmic,
                    Some(s) if s == "LINEAR" => FrequencyScale::Linear,
                    Some(s) if s == "LOGARITHMIC" => FrequencyScale::Logarithmic,
                    Some(s) => {
                        return Err(card.error(
                            K::BadValue,
                            format!("FREQUENCY SCALE={s}: LINEAR or LOGARITHMIC"),
                        ))
                    }
                };
                if first.is_none() {
                    return Err(
                        card.error(K::Syntax, "needs a data line (f_low, f_high, points, bias)")
                    );
                }
                let log = scale == FrequencyScale::Logarithmic;
                let mut ranges = Vec::new();
                let mut total = 0usize;
                for l in lines(card) {
                    let r = frequency_range(card, l, log, if eigen_intervals { 3.0 } else { 1.0 })?;
                    total += r.points;
                    if total > MAX_FREQUENCIES {
                        return Err(card.error_at(
                            l.line,
                            K::BadValue,
                            format!("more than {MAX_FREQUENCIES} frequencies in one step (the lines so far list {total})"),
                        ));
                    }
                    ranges.push(r);
                }
                Procedure::SteadyState {
                    ranges,
                    scale,
                    direct,
                    eigen_intervals,
                }
            }
        };
        let name = self.step_mut(card)?.name.clone();
        if self.procedure.is_some() {
            return Err(card.error(K::Syntax, format!("step {name} already has a procedure")));
        }
        self.procedure = Some(procedure);
        Ok(())
    }

    /// `*MODAL DAMPING` (viscous by mode numbers, or RAYLEIGH): first mode, last mode
    /// (blank: all), then ζ, or α and β with RAYLEIGH (CalculiX leaves the modes blank).
    pub(super) fn modal_damping(&mut self, card: &Card) -> Result<(), DeckError> {
        choice(card, "DEFINITION", &["MODE NUMBERS"], "MODE NUMBERS")?;
        choice(
            card,
            "VISCOUS",
            &["FRACTION OF CRITICAL DAMPING"],
            "FRACTION OF CRITICAL DAMPING",
        )?;
        let rayleigh = card.flag("RAYLEIGH");
        let mut out = Vec::new();
        for l in lines(card) {
            let mode = |i: usize, what: &str| -> Result<Option<usize>, DeckError> {
                match l.fields.get(i).map(|f| f.trim()).filter(|f| !f.is_empty()) {
                    None => Ok(None),
                    Some(f) => parse_id(f).map(|v| Some(v as usize)).ok_or_else(|| {
                        card.error_at(
                            l.line,
                            K::BadValue,
                            format!("{what} {:?} is not a positive integer", truncate(f)),
                        )
                    }),
                }
            };
            let (first, last) = (mode(0, "first mode")?, mode(1, "last mode")?);
            let value = |i: usize, what: &str| opt_number(card, l, i, what, 0.0);
            let (ratio, alpha, beta) = if rayleigh {
                (0.0, value(2, "alpha")?, value(3, "beta")?)
            } else {
                if l.fields.len() > 3 {
                    return Err(card.error_at(l.line, K::Unsupported, "a fourth field: viscous modal damping takes first mode, last mode, fraction of critical damping (α, β need RAYLEIGH)"));
                }
                (value(2, "fraction of critical damping")?, 0.0, 0.0)
            };
            if [ratio, alpha, beta]
                .iter()
                .any(|v| !(v.is_finite() && *v >= 0.0))
                || matches!((first, last), (Some(a), Some(b)) if b < a)
            {
                return Err(card.error_at(l.line, K::BadValue, format!("need first mode <= last mode and damping >= 0; got {first:?}, {last:?}, {ratio}, {alpha}, {beta}")));
            }
            out.push((
                ModalDamping {
                    first,
                    last,
                    ratio,
                    alpha,
                    beta,
                },
                data_origin(card, l),
            ));
        }
        if out.is_empty() {
            return Err(card.error(
                K::Syntax,
                "needs a data line (first mode, last mode, damping)",
            ));
        }
        self.step_mut(card)?.modal_damping.extend(out);
        Ok(())
    }

    pub(super) fn output(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let Some(set) = card.param("NSET") else {
            self.warnings.push(card.origin.warning(
                &card.name(),
                "no NSET=: ignored (only node-set output is written)",
            ));
            return Ok(());
        };
        let node_set = scope.name(set);
        match self.deck.node_sets.get(&node_set) {
            None => {
                return Err(card.error(K::Undefined, format!("node set {node_set} is not defined")))
            }
            Some(s) if s.is_empty() => {
                return Err(card.error(
                    K::BadValue,
                    format!("node set {node_set} is empty: no output"),
                ))
            }
            Some(_) => {}
        }
        let variables: Vec<String> = lines(card)
            .flat_map(|l| l.fields.iter())
            .filter(|f| !f.is_empty())
            .map(|f| f.to_ascii_uppercase())
            .collect();
        if !variables.iter().any(|v| v == "U") {
            self.warnings.push(card.origin.warning(
                &card.name(),
                format!("no U among {variables:?}: ignored (only displacements are written)"),
            ));
            return Ok(());
        }
        let out = Output {
            node_set,
            variables,
            origin: card.origin.clone(),
        };
        self.step_mut(card)?.outputs.push(out);
        Ok(())
    }
}

impl Reader {
    /// `*STEP`: opens a step (geometrically linear only).
    pub(super) fn step_start(&mut self, card: &Card) -> Result<(), DeckError> {
        if self.step.is_some() {
            return Err(card.error(K::Syntax, "*STEP inside a step (missing *END STEP?)"));
        }
        if choice(card, "NLGEOM", &["NO", "YES"], "NO")? == "YES" {
            return Err(card.error(
                K::Unsupported,
                "NLGEOM=YES: the model is geometrically linear",
            ));
        }
        let n = self.deck.steps.len() + 1;
        self.step = Some(Step {
            name: card
                .param("NAME")
                .map(|s| s.to_string())
                .unwrap_or_else(|| format!("Step-{n}")),
            perturbation: card.flag("PERTURBATION"),
            procedure: Procedure::Static,
            boundaries: Vec::new(),
            cloads: Vec::new(),
            dloads: Vec::new(),
            dsloads: Vec::new(),
            outputs: Vec::new(),
            modal_damping: Vec::new(),
            origin: card.origin.clone(),
        });
        self.procedure = None;
        Ok(())
    }

    /// `*END STEP`: closes the open step, which must have its procedure.
    pub(super) fn step_end(&mut self, card: &Card) -> Result<(), DeckError> {
        let mut step = self
            .step
            .take()
            .ok_or_else(|| card.error(K::Syntax, "*END STEP without *STEP"))?;
        step.procedure = self.procedure.take().ok_or_else(|| {
            card.error(
                K::Syntax,
                format!(
                    "step {} has no procedure (*STATIC, *FREQUENCY, *STEADY STATE DYNAMICS)",
                    step.name
                ),
            )
        })?;
        self.deck.steps.push(step);
        Ok(())
    }
}
