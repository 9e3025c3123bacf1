//! The procedures of a step (`*STATIC`, `*FREQUENCY`, `*STEADY STATE DYNAMICS`) and its
//! output requests.

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
                if !card.flag("DIRECT") {
                    return Err(card.error(
                        K::Unsupported,
                        "only DIRECT steady-state dynamics (not modal)",
                    ));
                }
                choice(card, "INTERVAL", &["RANGE"], "RANGE")?;
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
                    let r = frequency_range(card, l, log)?;
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
                Procedure::SteadyState { ranges, scale }
            }
        };
        let name = self.step_mut(card)?.name.clone();
        if self.procedure.is_some() {
            return Err(card.error(K::Syntax, format!("step {name} already has a procedure")));
        }
        self.procedure = Some(procedure);
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
