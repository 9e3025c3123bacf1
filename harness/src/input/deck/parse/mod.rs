//! Cards → [`Deck`]: one handler per keyword, parts replayed per instance.
//!
//! `mod.rs` holds the reader's state, the instance replay and the dispatch of each card
//! to its handler; the handlers live by subject: `mesh` (nodes, elements, sets,
//! surfaces), `model_data` (materials, interactions, contact pairs and ties,
//! boundaries), `steps` (procedures and output requests); `fields` reads the numbers,
//! DOFs and labels of data lines.

mod fields;
mod mesh;
mod model_data;
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
            "MATERIAL" => {
                let name = Scope::default().name(card.required("NAME")?);
                let m = MaterialDef {
                    name: name.clone(),
                    origin: card.origin.clone(),
                    ..Default::default()
                };
                if self.deck.materials.insert(name.clone(), m).is_some() {
                    return Err(card.error(K::Duplicate, format!("material {name} defined twice")));
                }
                self.material = Some(name);
            }
            "ELASTIC" | "DENSITY" | "DAMPING" => self.material_data(card)?,
            "SOLID SECTION" => {
                let section = Section {
                    element_set: scope.name(card.required("ELSET")?),
                    material: Scope::default().name(card.required("MATERIAL")?),
                    origin: card.origin.clone(),
                };
                match self.deck.element_sets.get(&section.element_set) {
                    None => {
                        return Err(card.error(
                            K::Undefined,
                            format!("element set {} is not defined", section.element_set),
                        ))
                    }
                    Some(set) if set.is_empty() => {
                        return Err(card.error(
                            K::BadValue,
                            format!("element set {} is empty", section.element_set),
                        ))
                    }
                    Some(_) => {}
                }
                self.deck.sections.push(section);
            }
            "SURFACE INTERACTION" => self.interaction(card)?,
            "CONTACT PAIR" => {
                let interaction = scope.name(card.required("INTERACTION")?);
                if let Some(t) = card
                    .param("TYPE")
                    .filter(|t| !t.eq_ignore_ascii_case("NODE TO SURFACE"))
                {
                    return Err(card.error(
                        K::Unsupported,
                        format!("TYPE={t}: a run pairs node to surface (UINTER per slave node)"),
                    ));
                }
                for l in lines(card) {
                    let [slave, master] = self.surface_pair(card, l, scope)?;
                    let earlier = (self.deck.contact_pairs.iter())
                        .map(|c| (&c.slave, &c.master, c.origin.line));
                    if let Some(w) = repeated(card, l, [&slave, &master], earlier) {
                        self.warnings.push(w);
                        continue;
                    }
                    self.deck.contact_pairs.push(ContactPair {
                        interaction: interaction.clone(),
                        slave,
                        master,
                        small_sliding: card.flag("SMALL SLIDING"),
                        origin: data_origin(card, l),
                    });
                }
            }
            "TIE" => {
                let name = scope.name(card.required("NAME")?);
                let tol = match card.param("POSITION TOLERANCE") {
                    None => None,
                    Some(_) => Some(param_number(card, "POSITION TOLERANCE", 0.0)?),
                };
                choice(card, "ADJUST", &["YES", "NO"], "YES")?;
                let surface_to_surface = choice(
                    card,
                    "TYPE",
                    &["NODE TO SURFACE", "SURFACE TO SURFACE"],
                    "NODE TO SURFACE",
                )? == "SURFACE TO SURFACE";
                for l in lines(card) {
                    let [slave, master] = self.surface_pair(card, l, scope)?;
                    let earlier =
                        (self.deck.ties.iter()).map(|t| (&t.slave, &t.master, t.origin.line));
                    if let Some(w) = repeated(card, l, [&slave, &master], earlier) {
                        self.warnings.push(w);
                        continue;
                    }
                    self.deck.ties.push(Tie {
                        name: name.clone(),
                        slave,
                        master,
                        position_tolerance: tol,
                        surface_to_surface,
                        origin: data_origin(card, l),
                    });
                }
            }
            "BOUNDARY" => self.boundary(card, scope)?,
            "STEP" => {
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
            }
            "STATIC" | "FREQUENCY" | "STEADY STATE DYNAMICS" => self.procedure(card)?,
            "MODAL DAMPING" => self.modal_damping(card)?,
            "END STEP" => {
                let mut step = self
                    .step
                    .take()
                    .ok_or_else(|| card.error(K::Syntax, "*END STEP without *STEP"))?;
                step.procedure = self.procedure.take().ok_or_else(|| {
                    card.error(K::Syntax, format!("step {} has no procedure (*STATIC, *FREQUENCY, *STEADY STATE DYNAMICS)", step.name))
                })?;
                self.deck.steps.push(step);
            }
            "CLOAD" => {
                let imaginary = load_part(card)?;
                let mut loads = Vec::new();
                for l in lines(card) {
                    let target = self.node_target(card, l, scope)?;
                    let dof = dof(card, l, 1)?;
                    let value = number(card, l, 2, "load")?;
                    loads.push(CLoad {
                        target,
                        dof,
                        value,
                        imaginary,
                        origin: card.origin.clone(),
                    });
                }
                self.step_mut(card)?.cloads.extend(loads);
            }
            "DLOAD" => {
                let imaginary = load_part(card)?;
                let mut loads = Vec::new();
                for l in lines(card) {
                    let elements = self.element_target(card, l, scope)?;
                    let label = l.fields.get(1).map(String::as_str).unwrap_or("");
                    let face = face_label(label, 'P').ok_or_else(|| {
                        card.error_at(
                            l.line,
                            K::Unsupported,
                            format!(
                                "load type {:?}: only P1…P6 (pressure on a face) is supported",
                                truncate(label)
                            ),
                        )
                    })?;
                    for id in self.element_ids(&elements) {
                        self.check_face(card, l.line, id, face)?;
                    }
                    let pressure = number(card, l, 2, "pressure")?;
                    loads.push(DLoad {
                        elements,
                        face,
                        pressure,
                        imaginary,
                        origin: card.origin.clone(),
                    });
                }
                self.step_mut(card)?.dloads.extend(loads);
            }
            "DSLOAD" => {
                let imaginary = load_part(card)?;
                let mut loads = Vec::new();
                for l in lines(card) {
                    let surface = scope.name(&l.fields[0]);
                    if !self.deck.surfaces.contains_key(&surface) {
                        return Err(card.error_at(
                            l.line,
                            K::Undefined,
                            format!("surface {surface} is not defined"),
                        ));
                    }
                    let label = l
                        .fields
                        .get(1)
                        .map(|s| s.trim().to_ascii_uppercase())
                        .unwrap_or_default();
                    if label != "P" {
                        return Err(card.error_at(
                            l.line,
                            K::Unsupported,
                            format!("load type {:?}: only P is supported", truncate(&label)),
                        ));
                    }
                    let pressure = number(card, l, 2, "pressure")?;
                    loads.push(DsLoad {
                        surface,
                        pressure,
                        imaginary,
                        origin: card.origin.clone(),
                    });
                }
                self.step_mut(card)?.dsloads.extend(loads);
            }
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
