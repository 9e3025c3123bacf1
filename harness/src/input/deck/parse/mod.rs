//! Cards → [`Deck`]: one handler per keyword, parts replayed per instance.
//!
//! `mod.rs` holds the reader's state, the instance replay and the dispatch of each card
//! to its handler; the handlers live by subject: `mesh` (nodes, elements, sets,
//! surfaces), `model_data` (materials, sections, interactions, boundaries), `pairs`
//! (contact pairs and ties), `steps` (steps, procedures and output requests), `loads`
//! (the steps' loads); `fields` reads the numbers, DOFs and labels of data lines.

mod fields;
mod loads;
mod mesh;
mod model_data;
mod pairs;
mod steps;

use std::collections::HashMap;

use crate::fe::elements::ElementKind;
use crate::names::MAX_FREQUENCY;

use super::error::{DeckError, DeckErrorKind as K, DeckWarning, Origin};
use super::keywords::{check_fields, check_params, keyword};
use super::lexer::{parse_id, parse_number, truncate, Card, DataLine};
use super::model::*;
use super::sets::{add_to_set, members, InstanceOffsets, Members, Scope};
use super::IGNORED_KEYWORDS;
use fields::{
    choice, dof, face_label, frequency_range, lines, load_part, number, opt_number, param_number,
};

/// Reader state between cards.
#[derive(Default)]
struct Reader {
    deck: Deck,
    warnings: Vec<DeckWarning>,
    parts: HashMap<String, Vec<Card>>,
    instances: InstanceOffsets,
    material: Option<String>,
    step: Option<Step>,
    /// The procedure card of the open step, once read.
    procedure: Option<Procedure>,
}

/// Builds the deck from its cards (see [`super::read`]).
pub fn build(cards: Vec<Card>) -> Result<(Deck, Vec<DeckWarning>), DeckError> {
    for card in &cards {
        check_card(card)?;
    }
    let mut r = Reader::default();
    let flat = Scope::default();
    let mut it = cards.into_iter();
    while let Some(card) = it.next() {
        match card.keyword.as_str() {
            "PART" => {
                let name = flat.name(card.required("NAME")?);
                let mut body = Vec::new();
                loop {
                    match it.next() {
                        Some(c) if c.keyword == "END PART" => break,
                        Some(c) => body.push(c),
                        None => {
                            return Err(
                                card.error(K::Syntax, format!("part {name} has no *END PART"))
                            )
                        }
                    }
                }
                if r.parts.insert(name.clone(), body).is_some() {
                    return Err(card.error(K::Duplicate, format!("part {name} defined twice")));
                }
            }
            "INSTANCE" => {
                let mut inner = Vec::new();
                loop {
                    match it.next() {
                        Some(c) if c.keyword == "END INSTANCE" => break,
                        Some(c) => inner.push(c),
                        None => return Err(card.error(K::Syntax, "no *END INSTANCE")),
                    }
                }
                if let Some(c) = inner.first() {
                    return Err(c.error(
                        K::Unsupported,
                        "cards inside *INSTANCE (define the mesh in a *PART)",
                    ));
                }
                r.instance(&card)?;
            }
            _ => r.card(&card, &flat)?,
        }
    }
    if let Some(step) = &r.step {
        return Err(step.origin.error(K::Syntax, "*STEP", "no *END STEP"));
    }
    super::check::check(&r.deck)?;
    Ok((r.deck, r.warnings))
}

/// Where data line `l` of `card` is (its file, its line).
fn data_origin(card: &Card, l: &DataLine) -> Origin {
    Origin {
        file: card
            .data_file
            .clone()
            .unwrap_or_else(|| card.origin.file.clone()),
        line: l.line,
    }
}

/// A warning when the pair `[slave, master]` of data line `l` repeats one of `earlier`
/// (slave, master, line): the repeat then counts once.
fn repeated<'a>(
    card: &Card,
    l: &DataLine,
    [slave, master]: [&String; 2],
    mut earlier: impl Iterator<Item = (&'a String, &'a String, usize)>,
) -> Option<DeckWarning> {
    let (_, _, line) = earlier.find(|(s, m, _)| *s == slave && *m == master)?;
    Some(card.origin.warning(
        &card.name(),
        format!(
            "line {}: {slave}, {master} is given already (line {line}): counted once",
            l.line
        ),
    ))
}

/// Checks a card against the implemented keywords: an unknown keyword, a parameter
/// its keyword does not implement or a data line with more fields than it reads is an
/// error (output keywords the run ignores are not checked further).
fn check_card(card: &Card) -> Result<(), DeckError> {
    if IGNORED_KEYWORDS.contains(&card.keyword.as_str()) {
        return Ok(());
    }
    let kw = keyword(&card.keyword).ok_or_else(|| {
        card.error(
            K::UnknownKeyword,
            "keyword not supported (see the supported and ignored keyword lists)",
        )
    })?;
    check_params(card, kw)?;
    check_fields(card, kw)
}

impl Reader {
    fn node_target(
        &self,
        card: &Card,
        l: &DataLine,
        scope: &Scope,
    ) -> Result<NodeTarget, DeckError> {
        let f = l.fields.first().map(String::as_str).unwrap_or("");
        if let Some(id) = scope.id(f, Members::Nodes, &self.instances) {
            if !self.deck.node_index.contains_key(&id) {
                return Err(card.error_at(
                    l.line,
                    K::Undefined,
                    format!("node {f} is not defined"),
                ));
            }
            return Ok(NodeTarget::Node(id));
        }
        let name = scope.name(f);
        match self.deck.node_sets.get(&name) {
            None => Err(card.error_at(
                l.line,
                K::Undefined,
                format!("node set {name} is not defined"),
            )),
            Some(set) if set.is_empty() => Err(card.error_at(
                l.line,
                K::BadValue,
                format!(
                    "node set {name} is empty: {} would act on nothing",
                    card.name()
                ),
            )),
            Some(_) => Ok(NodeTarget::Set(name)),
        }
    }

    fn element_target(
        &self,
        card: &Card,
        l: &DataLine,
        scope: &Scope,
    ) -> Result<ElementTarget, DeckError> {
        let f = l.fields.first().map(String::as_str).unwrap_or("");
        if let Some(id) = scope.id(f, Members::Elements, &self.instances) {
            if !self.deck.element_index.contains_key(&id) {
                return Err(card.error_at(
                    l.line,
                    K::Undefined,
                    format!("element {f} is not defined"),
                ));
            }
            return Ok(ElementTarget::Element(id));
        }
        let name = scope.name(f);
        match self.deck.element_sets.get(&name) {
            None => Err(card.error_at(
                l.line,
                K::Undefined,
                format!("element set {name} is not defined"),
            )),
            Some(set) if set.is_empty() => Err(card.error_at(
                l.line,
                K::BadValue,
                format!(
                    "element set {name} is empty: {} would act on nothing",
                    card.name()
                ),
            )),
            Some(_) => Ok(ElementTarget::Set(name)),
        }
    }

    fn element_ids(&self, t: &ElementTarget) -> Vec<u64> {
        match t {
            ElementTarget::Element(id) => vec![*id],
            ElementTarget::Set(s) => self.deck.element_sets.get(s).cloned().unwrap_or_default(),
        }
    }

    fn step_mut(&mut self, card: &Card) -> Result<&mut Step, DeckError> {
        self.step
            .as_mut()
            .ok_or_else(|| card.error(K::Syntax, "only allowed inside *STEP … *END STEP"))
    }

    fn instance(&mut self, card: &Card) -> Result<(), DeckError> {
        let name = card.required("NAME")?.to_ascii_uppercase();
        let part = card.required("PART")?.to_ascii_uppercase();
        let body = self
            .parts
            .get(&part)
            .cloned()
            .ok_or_else(|| card.error(K::Undefined, format!("part {part} is not defined")))?;
        let mut translation = [0.0; 3];
        let data: Vec<&DataLine> = lines(card).collect();
        if let Some(l) = data.first() {
            for (c, t) in translation.iter_mut().enumerate() {
                *t = opt_number(card, l, c, "translation", 0.0)?;
            }
        }
        if data.len() > 1 {
            return Err(card.error_at(
                data[1].line,
                K::Unsupported,
                "instance rotation is not supported (translate only)",
            ));
        }
        // Offsets past every id so far, rounded up to a power of ten for readable ids.
        let round = |m: u64| 10u64.pow((m as f64 + 1.0).log10().ceil().max(1.0) as u32);
        let max_node = self.deck.nodes.iter().map(|n| n.id).max().unwrap_or(0);
        let max_el = self.deck.elements.iter().map(|e| e.id).max().unwrap_or(0);
        let scope = Scope {
            prefix: format!("{name}."),
            node_offset: if max_node == 0 { 0 } else { round(max_node) },
            element_offset: if max_el == 0 { 0 } else { round(max_el) },
            translation,
        };
        if self
            .instances
            .insert(name.clone(), (scope.node_offset, scope.element_offset))
            .is_some()
        {
            return Err(card.error(K::Duplicate, format!("instance {name} defined twice")));
        }
        for c in &body {
            self.card(c, &scope)?;
        }
        Ok(())
    }

    fn card(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let kw = card.keyword.as_str();
        match kw {
            "HEADING" => {
                // The first heading is the model's (an included mesh file may bring its own).
                if self.deck.heading.is_empty() {
                    let text: Vec<String> = card.data.iter().map(|l| l.fields.join(", ")).collect();
                    self.deck.heading = text.join("\n");
                }
            }
            "ASSEMBLY" | "END ASSEMBLY" | "OUTPUT" => {}
            "NODE" => self.nodes(card, scope)?,
            "ELEMENT" => self.elements(card, scope)?,
            "NSET" | "ELSET" => self.set(card, scope)?,
            "SURFACE" => self.surface(card, scope)?,
            "MATERIAL" => self.material(card)?,
            "ELASTIC" | "DENSITY" | "DAMPING" => self.material_data(card)?,
            "SOLID SECTION" => self.solid_section(card, scope)?,
            "SURFACE INTERACTION" => self.interaction(card)?,
            "CONTACT PAIR" => self.contact_pair(card, scope)?,
            "TIE" => self.tie(card, scope)?,
            "BOUNDARY" => self.boundary(card, scope)?,
            "STEP" => self.step_start(card)?,
            "STATIC" | "FREQUENCY" | "STEADY STATE DYNAMICS" => self.procedure(card)?,
            "MODAL DAMPING" => self.modal_damping(card)?,
            "END STEP" => self.step_end(card)?,
            "CLOAD" => self.cload(card, scope)?,
            "DLOAD" => self.dload(card, scope)?,
            "DSLOAD" => self.dsload(card, scope)?,
            "NODE PRINT" | "NODE OUTPUT" => self.output(card, scope)?,
            _ if IGNORED_KEYWORDS.contains(&kw) => {
                self.warnings.push(card.origin.note(
                    &card.name(),
                    "a request for Abaqus's own output, skipped: jointlin writes its results as CSV, VTU and run.json",
                ));
            }
            _ => {
                return Err(card.error(
                    K::Unsupported,
                    "listed as implemented but has no handler (a reader defect)",
                ))
            }
        }
        Ok(())
    }
}
