//! Cards → [`Deck`]: one handler per keyword, parts replayed per instance.

use std::collections::HashMap;

use crate::fe::elements::ElementKind;

use super::error::{DeckError, DeckErrorKind as K, DeckWarning, Origin};
use super::lexer::{parse_id, parse_number, truncate, Card, DataLine};
use super::model::*;
use super::sets::{add_to_set, members, InstanceOffsets, Members, Scope};
use super::{IGNORED_KEYWORDS, SUPPORTED_KEYWORDS};

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

fn number(card: &Card, l: &DataLine, i: usize, what: &str) -> Result<f64, DeckError> {
    let f = l.fields.get(i).map(String::as_str).unwrap_or("");
    parse_number(f).ok_or_else(|| {
        card.error_at(
            l.line,
            K::Syntax,
            format!("{what}: {:?} is not a finite number", truncate(f)),
        )
    })
}

fn opt_number(
    card: &Card,
    l: &DataLine,
    i: usize,
    what: &str,
    default: f64,
) -> Result<f64, DeckError> {
    match l.fields.get(i).map(|s| s.trim()) {
        None | Some("") => Ok(default),
        Some(_) => number(card, l, i, what),
    }
}

/// Whether a load card gives the imaginary part of a steady-state load (`IMAGINARY`;
/// `REAL`, the default, the real part). An `AMPLITUDE` is refused: a frequency-dependent
/// load would otherwise be read as constant.
fn load_part(card: &Card) -> Result<bool, DeckError> {
    if let Some(a) = card.param("AMPLITUDE") {
        return Err(card.error(
            K::Unsupported,
            format!("AMPLITUDE={a}: a frequency-dependent load amplitude is not read (the data lines' values would be taken at every frequency)"),
        ));
    }
    let (re, im) = (card.flag("REAL"), card.flag("IMAGINARY"));
    if re && im {
        return Err(card.error(
            K::BadValue,
            "REAL and IMAGINARY together: one card per part",
        ));
    }
    Ok(im)
}

fn param_number(card: &Card, name: &str, default: f64) -> Result<f64, DeckError> {
    match card.param(name) {
        None => Ok(default),
        Some(v) => parse_number(v)
            .ok_or_else(|| card.error(K::Syntax, format!("{name}={v:?} is not a finite number"))),
    }
}

/// Data lines with at least one non-empty field.
fn lines(card: &Card) -> impl Iterator<Item = &DataLine> {
    card.data
        .iter()
        .filter(|l| l.fields.iter().any(|f| !f.is_empty()))
}

/// DOF number 1…6.
fn dof(card: &Card, l: &DataLine, i: usize) -> Result<u8, DeckError> {
    let f = l.fields.get(i).map(String::as_str).unwrap_or("");
    parse_id(f)
        .filter(|&d| d <= 6)
        .map(|d| d as u8)
        .ok_or_else(|| {
            card.error_at(
                l.line,
                K::BadValue,
                format!("DOF {:?} is not 1…6", truncate(f)),
            )
        })
}

/// Face label `S1`…`S6` / `P1`…`P6` → 0-based index.
fn face_label(label: &str, letter: char) -> Option<usize> {
    let u = label.trim().to_ascii_uppercase();
    let n: usize = u.strip_prefix(letter)?.parse().ok()?;
    (1..=6).contains(&n).then_some(n - 1)
}

/// A `*STEADY STATE DYNAMICS` data line as Abaqus reads it: f_low, f_high (zero or
/// blank: the single frequency f_low), points (fewer than 2 or blank: 20), bias
/// (default 1).
fn frequency_range(card: &Card, l: &DataLine) -> Result<FrequencyRange, DeckError> {
    /// Abaqus's number of points when the line gives fewer than 2.
    const DEFAULT_POINTS: f64 = 20.0;
    let f_low = number(card, l, 0, "lower frequency")?;
    let f_high = opt_number(card, l, 1, "upper frequency", 0.0)?;
    if f_high == 0.0 {
        if f_low < 0.0 {
            return Err(card.error_at(l.line, K::BadValue, format!("frequency {f_low} < 0")));
        }
        return Ok(FrequencyRange {
            f_low,
            f_high: f_low,
            points: 1,
            bias: 1.0,
        });
    }
    let mut points = opt_number(card, l, 2, "number of points", DEFAULT_POINTS)?;
    if points < 2.0 {
        points = DEFAULT_POINTS;
    }
    let bias = opt_number(card, l, 3, "bias", 1.0)?;
    if f_low < 0.0 || f_high < f_low || points.fract() != 0.0 || points > 1e7 || bias <= 0.0 {
        return Err(card.error_at(l.line, K::BadValue, format!("need 0 <= f_low <= f_high, a whole number of points and bias > 0; got {f_low}, {f_high}, {points}, {bias}")));
    }
    Ok(FrequencyRange {
        f_low,
        f_high,
        points: points as usize,
        bias,
    })
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
        if !self.deck.node_sets.contains_key(&name) {
            return Err(card.error_at(
                l.line,
                K::Undefined,
                format!("node set {name} is not defined"),
            ));
        }
        Ok(NodeTarget::Set(name))
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
        if !self.deck.element_sets.contains_key(&name) {
            return Err(card.error_at(
                l.line,
                K::Undefined,
                format!("element set {name} is not defined"),
            ));
        }
        Ok(ElementTarget::Set(name))
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
                if !self.deck.element_sets.contains_key(&section.element_set) {
                    return Err(card.error(
                        K::Undefined,
                        format!("element set {} is not defined", section.element_set),
                    ));
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
                    self.deck.contact_pairs.push(ContactPair {
                        interaction: interaction.clone(),
                        slave,
                        master,
                        small_sliding: card.flag("SMALL SLIDING"),
                        origin: card.origin.clone(),
                    });
                }
            }
            "TIE" => {
                let name = scope.name(card.required("NAME")?);
                let tol = match card.param("POSITION TOLERANCE") {
                    None => None,
                    Some(_) => Some(param_number(card, "POSITION TOLERANCE", 0.0)?),
                };
                for l in lines(card) {
                    let [slave, master] = self.surface_pair(card, l, scope)?;
                    self.deck.ties.push(Tie {
                        name: name.clone(),
                        slave,
                        master,
                        position_tolerance: tol,
                        origin: card.origin.clone(),
                    });
                }
            }
            "BOUNDARY" => self.boundary(card, scope)?,
            "STEP" => {
                if self.step.is_some() {
                    return Err(card.error(K::Syntax, "*STEP inside a step (missing *END STEP?)"));
                }
                if card
                    .param("NLGEOM")
                    .is_some_and(|v| v.eq_ignore_ascii_case("YES"))
                {
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
                    origin: card.origin.clone(),
                });
                self.procedure = None;
            }
            "STATIC" | "FREQUENCY" | "STEADY STATE DYNAMICS" => self.procedure(card)?,
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
                self.warnings.push(
                    card.origin
                        .warning(&card.name(), "ignored (output the harness does not need)"),
                );
            }
            _ => {
                debug_assert!(!SUPPORTED_KEYWORDS.contains(&kw), "{kw} has no handler");
                return Err(card.error(
                    K::UnknownKeyword,
                    "keyword not supported (see the supported and ignored keyword lists)",
                ));
            }
        }
        Ok(())
    }

    fn nodes(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let mut ids = Vec::new();
        for l in lines(card) {
            let f = &l.fields[0];
            let id = scope
                .id(f, Members::Nodes, &self.instances)
                .ok_or_else(|| {
                    card.error_at(
                        l.line,
                        K::Syntax,
                        format!("node id {:?} is not a positive integer", truncate(f)),
                    )
                })?;
            let mut x = [0.0; 3];
            for c in 0..3 {
                x[c] = opt_number(card, l, c + 1, "coordinate", 0.0)? + scope.translation[c];
            }
            if self
                .deck
                .node_index
                .insert(id, self.deck.nodes.len())
                .is_some()
            {
                return Err(card.error_at(l.line, K::Duplicate, format!("node {f} defined twice")));
            }
            self.deck.nodes.push(Node { id, x });
            ids.push(id);
        }
        if let Some(set) = card.param("NSET") {
            add_to_set(&mut self.deck.node_sets, scope.name(set), &ids);
        }
        Ok(())
    }

    fn elements(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let ty = card.required("TYPE")?;
        let kind = ElementKind::from_name(ty).ok_or_else(|| {
            let names: Vec<&str> = ElementKind::ALL.iter().map(|k| k.name()).collect();
            let why = if ty.eq_ignore_ascii_case("C3D8R") {
                " (reduced integration needs hourglass control, which this code does not have)"
            } else {
                ""
            };
            card.error(
                K::Unsupported,
                format!("element type {ty}{why}; supported: {}", names.join(", ")),
            )
        })?;
        let need = kind.node_count() + 1;
        let mut ids = Vec::new();
        let mut fields: Vec<String> = Vec::new();
        let mut first_line = 0;
        for l in lines(card) {
            if fields.is_empty() {
                first_line = l.line;
            }
            fields.extend(l.fields.iter().filter(|f| !f.is_empty()).cloned());
            if fields.len() < need {
                continue;
            }
            if fields.len() > need {
                return Err(card.error_at(
                    l.line,
                    K::Syntax,
                    format!(
                        "{kind} needs {} nodes, line has {}",
                        need - 1,
                        fields.len() - 1
                    ),
                ));
            }
            let at = |msg: String| card.error_at(first_line, K::Syntax, msg);
            let id = scope
                .id(&fields[0], Members::Elements, &self.instances)
                .ok_or_else(|| {
                    at(format!(
                        "element id {:?} is not a positive integer",
                        truncate(&fields[0])
                    ))
                })?;
            let mut nodes = Vec::with_capacity(need - 1);
            for f in &fields[1..] {
                let n = scope
                    .id(f, Members::Nodes, &self.instances)
                    .ok_or_else(|| {
                        at(format!(
                            "node id {:?} is not a positive integer",
                            truncate(f)
                        ))
                    })?;
                nodes.push(n);
            }
            if self
                .deck
                .element_index
                .insert(id, self.deck.elements.len())
                .is_some()
            {
                return Err(card.error_at(
                    first_line,
                    K::Duplicate,
                    format!("element {} defined twice", fields[0]),
                ));
            }
            let origin = Origin {
                file: card.origin.file.clone(),
                line: first_line,
            };
            self.deck.elements.push(Element {
                id,
                kind,
                nodes,
                origin,
            });
            ids.push(id);
            fields.clear();
        }
        if !fields.is_empty() {
            return Err(card.error_at(
                first_line,
                K::Syntax,
                format!(
                    "{kind} needs {} nodes, got {} (truncated?)",
                    need - 1,
                    fields.len() - 1
                ),
            ));
        }
        if let Some(set) = card.param("ELSET") {
            add_to_set(&mut self.deck.element_sets, scope.name(set), &ids);
        }
        Ok(())
    }

    fn set(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let (param, kind) = if card.keyword == "NSET" {
            ("NSET", Members::Nodes)
        } else {
            ("ELSET", Members::Elements)
        };
        let name = scope.name(card.required(param)?);
        // INSTANCE=: ids and names of the data lines are that instance's.
        let inner = match card.param("INSTANCE") {
            Some(inst) => {
                let inst = inst.to_ascii_uppercase();
                let &(n, e) = self.instances.get(&inst).ok_or_else(|| {
                    card.error(K::Undefined, format!("instance {inst} is not defined"))
                })?;
                Scope {
                    prefix: format!("{inst}."),
                    node_offset: n,
                    element_offset: e,
                    translation: [0.0; 3],
                }
            }
            None => scope.clone(),
        };
        let data: Vec<DataLine> = lines(card).cloned().collect();
        let ids = members(card, &data, kind, &inner, &self.instances, &self.deck)?;
        let sets = if kind == Members::Nodes {
            &mut self.deck.node_sets
        } else {
            &mut self.deck.element_sets
        };
        add_to_set(sets, name, &ids);
        Ok(())
    }

    fn check_face(
        &self,
        card: &Card,
        line: usize,
        element: u64,
        face: usize,
    ) -> Result<(), DeckError> {
        let e = &self.deck.elements[self.deck.element_index[&element]];
        if face >= e.kind.face_count() {
            return Err(card.error_at(
                line,
                K::BadValue,
                format!(
                    "element {element} is a {} and has no face {}{}",
                    e.kind,
                    if card.keyword == "DLOAD" { "P" } else { "S" },
                    face + 1
                ),
            ));
        }
        Ok(())
    }

    fn surface(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let name = scope.name(card.required("NAME")?);
        let ty = card.param("TYPE").unwrap_or("ELEMENT").to_ascii_uppercase();
        let kind = match ty.as_str() {
            "ELEMENT" => {
                let mut faces = Vec::new();
                for l in lines(card) {
                    let target = self.element_target(card, l, scope)?;
                    let label = l.fields.get(1).map(String::as_str).unwrap_or("");
                    let face = face_label(label, 'S').ok_or_else(|| {
                        card.error_at(
                            l.line,
                            K::BadValue,
                            format!("face label {:?}: expected S1…S6", truncate(label)),
                        )
                    })?;
                    for id in self.element_ids(&target) {
                        self.check_face(card, l.line, id, face)?;
                        faces.push((id, face));
                    }
                }
                SurfaceKind::Element(faces)
            }
            "NODE" => {
                let mut nodes = Vec::new();
                for l in lines(card) {
                    let area = match l.fields.get(1).map(|s| s.trim()) {
                        None | Some("") => None,
                        Some(_) => Some(number(card, l, 1, "area")?),
                    };
                    match self.node_target(card, l, scope)? {
                        NodeTarget::Node(id) => nodes.push((id, area)),
                        NodeTarget::Set(s) => {
                            nodes.extend(self.deck.node_sets[&s].iter().map(|&id| (id, area)))
                        }
                    }
                }
                SurfaceKind::Node(nodes)
            }
            other => {
                return Err(card.error(
                    K::Unsupported,
                    format!("TYPE={other}: only ELEMENT and NODE surfaces"),
                ))
            }
        };
        let empty = match &kind {
            SurfaceKind::Element(f) => f.is_empty(),
            SurfaceKind::Node(n) => n.is_empty(),
        };
        if empty {
            return Err(card.error(K::BadValue, format!("surface {name} is empty")));
        }
        let s = Surface {
            name: name.clone(),
            kind,
            origin: card.origin.clone(),
        };
        if self.deck.surfaces.insert(name.clone(), s).is_some() {
            return Err(card.error(K::Duplicate, format!("surface {name} defined twice")));
        }
        Ok(())
    }

    fn material_data(&mut self, card: &Card) -> Result<(), DeckError> {
        let name = self
            .material
            .clone()
            .ok_or_else(|| card.error(K::Syntax, "must follow a *MATERIAL"))?;
        let first = lines(card).next().cloned();
        let need = |what: &str| card.error(K::Syntax, format!("needs a data line ({what})"));
        let m = self
            .deck
            .materials
            .get_mut(&name)
            .ok_or_else(|| card.error(K::Undefined, "material"))?;
        match card.keyword.as_str() {
            "ELASTIC" => {
                if let Some(t) = card
                    .param("TYPE")
                    .filter(|t| !t.eq_ignore_ascii_case("ISOTROPIC"))
                {
                    return Err(card.error(
                        K::Unsupported,
                        format!("TYPE={t}: only isotropic elasticity"),
                    ));
                }
                let l = first.ok_or_else(|| need("E, nu"))?;
                let (e, nu) = (number(card, &l, 0, "E")?, number(card, &l, 1, "nu")?);
                if e <= 0.0 || nu <= -1.0 || nu >= 0.5 {
                    return Err(card.error_at(
                        l.line,
                        K::BadValue,
                        format!("E = {e} must be > 0 and -1 < nu = {nu} < 0.5"),
                    ));
                }
                m.elastic = Some((e, nu));
            }
            "DENSITY" => {
                let l = first.ok_or_else(|| need("density"))?;
                let rho = number(card, &l, 0, "density")?;
                if rho < 0.0 {
                    return Err(card.error_at(l.line, K::BadValue, format!("density {rho} < 0")));
                }
                m.density = Some(rho);
            }
            _ => {
                let (a, b) = (
                    param_number(card, "ALPHA", 0.0)?,
                    param_number(card, "BETA", 0.0)?,
                );
                if a < 0.0 || b < 0.0 {
                    return Err(
                        card.error(K::BadValue, format!("ALPHA = {a}, BETA = {b} must be >= 0"))
                    );
                }
                m.damping = Some((a, b));
            }
        }
        Ok(())
    }

    fn interaction(&mut self, card: &Card) -> Result<(), DeckError> {
        let name = Scope::default().name(card.required("NAME")?);
        let user = card.flag("USER");
        let count = |p: &str| -> Result<usize, DeckError> {
            match card.param(p) {
                None => Ok(0),
                Some(v) => parse_id(v)
                    .map(|v| v as usize)
                    .or((v.trim() == "0").then_some(0))
                    .ok_or_else(|| card.error(K::Syntax, format!("{p}={v:?} is not a count"))),
            }
        };
        let (nprops, depvar) = (count("PROPERTIES")?, count("DEPVAR")?);
        if !user {
            return Err(card.error(K::Unsupported, "only USER surface interactions (the jointlin law, fortran-shim/README.md) are supported"));
        }
        let mut data = card.data.iter();
        // First data line: the out-of-plane thickness as Abaqus/CAE writes it, or blank.
        let thickness = match data.next() {
            Some(l) if l.fields.iter().any(|f| !f.is_empty()) => {
                Some(number(card, l, 0, "thickness")?)
            }
            _ => None,
        };
        let mut properties = Vec::new();
        for l in data {
            for (i, f) in l.fields.iter().enumerate() {
                if f.is_empty() && i + 1 == l.fields.len() {
                    continue;
                }
                properties.push(number(card, l, i, "property")?);
            }
        }
        if properties.len() != nprops {
            return Err(card.error(
                K::BadValue,
                format!("PROPERTIES={nprops} but {} values given", properties.len()),
            ));
        }
        let it = Interaction {
            name: name.clone(),
            user,
            depvar,
            properties,
            thickness,
            origin: card.origin.clone(),
        };
        if self.deck.interactions.insert(name.clone(), it).is_some() {
            return Err(card.error(K::Duplicate, format!("interaction {name} defined twice")));
        }
        Ok(())
    }

    fn surface_pair(
        &self,
        card: &Card,
        l: &DataLine,
        scope: &Scope,
    ) -> Result<[String; 2], DeckError> {
        if l.fields.len() < 2 {
            return Err(card.error_at(l.line, K::Syntax, "needs slave surface, master surface"));
        }
        let mut out = [String::new(), String::new()];
        for (i, o) in out.iter_mut().enumerate() {
            *o = scope.name(&l.fields[i]);
            if !self.deck.surfaces.contains_key(o.as_str()) {
                return Err(card.error_at(
                    l.line,
                    K::Undefined,
                    format!("surface {o} is not defined"),
                ));
            }
        }
        Ok(out)
    }

    fn boundary(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let mut out = Vec::new();
        for l in lines(card) {
            let target = self.node_target(card, l, scope)?;
            let second = l
                .fields
                .get(1)
                .map(|s| s.trim().to_ascii_uppercase())
                .unwrap_or_default();
            let named: Option<&[(u8, u8)]> = match second.as_str() {
                "ENCASTRE" => Some(&[(1, 6)]),
                "PINNED" => Some(&[(1, 3)]),
                "XSYMM" => Some(&[(1, 1), (5, 6)]),
                "YSYMM" => Some(&[(2, 2), (4, 4), (6, 6)]),
                "ZSYMM" => Some(&[(3, 3), (4, 5)]),
                _ => None,
            };
            if let Some(ranges) = named {
                for &(first, last) in ranges {
                    out.push(Boundary {
                        target: target.clone(),
                        first,
                        last,
                        value: 0.0,
                        origin: card.origin.clone(),
                    });
                }
                continue;
            }
            let first = dof(card, l, 1)?;
            let last = match l.fields.get(2).map(|s| s.trim()) {
                None | Some("") => first,
                Some(_) => dof(card, l, 2)?,
            };
            if last < first {
                return Err(card.error_at(
                    l.line,
                    K::BadValue,
                    format!("last DOF {last} < first DOF {first}"),
                ));
            }
            let value = opt_number(card, l, 3, "displacement", 0.0)?;
            out.push(Boundary {
                target,
                first,
                last,
                value,
                origin: card.origin.clone(),
            });
        }
        match self.step.as_mut() {
            Some(s) => s.boundaries.extend(out),
            None => self.deck.boundaries.extend(out),
        }
        Ok(())
    }

    fn procedure(&mut self, card: &Card) -> Result<(), DeckError> {
        let first = lines(card).next().cloned();
        let procedure = match card.keyword.as_str() {
            "STATIC" => Procedure::Static,
            "FREQUENCY" => {
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
                let ranges = lines(card)
                    .map(|l| frequency_range(card, l))
                    .collect::<Result<Vec<_>, _>>()?;
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

    fn output(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let Some(set) = card.param("NSET") else {
            self.warnings.push(card.origin.warning(
                &card.name(),
                "no NSET=: ignored (only node-set output is written)",
            ));
            return Ok(());
        };
        let node_set = scope.name(set);
        if !self.deck.node_sets.contains_key(&node_set) {
            return Err(card.error(K::Undefined, format!("node set {node_set} is not defined")));
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
