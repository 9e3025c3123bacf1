//! `*NODE`, `*ELEMENT`, `*NSET`/`*ELSET`, `*SURFACE`.

use super::*;
use crate::input::deck::check::MAX_MAGNITUDE;

impl Reader {
    pub(super) fn nodes(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        let system = choice(card, "SYSTEM", &["R", "C", "S"], "R")?;
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
            let mut given = [0.0; 3];
            for (c, v) in given.iter_mut().enumerate() {
                *v = opt_number(card, l, c + 1, "coordinate", 0.0)?;
            }
            let mut x = cartesian(&system, given);
            for (x, t) in x.iter_mut().zip(scope.translation) {
                *x += t;
            }
            if x.iter().any(|v| v.abs() > MAX_MAGNITUDE) {
                return Err(card.error_at(
                    l.line,
                    K::BadValue,
                    format!("node {f} at {x:?}: a coordinate beyond {MAX_MAGNITUDE:e} (the model's size would overflow)"),
                ));
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

    pub(super) fn elements(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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

    /// `*NSET, NSET=name, ELSET=set`: the nodes of the elements of `set` (no data lines).
    fn nodes_of_elements(&self, card: &Card, scope: &Scope) -> Result<Vec<u64>, DeckError> {
        if card.flag("GENERATE") || lines(card).next().is_some() {
            return Err(card.error(
                K::Syntax,
                "ELSET= gives the members: no GENERATE and no data lines",
            ));
        }
        let set = scope.name(card.required("ELSET")?);
        let elements =
            self.deck.element_sets.get(&set).ok_or_else(|| {
                card.error(K::Undefined, format!("element set {set} is not defined"))
            })?;
        let mut ids = Vec::new();
        for id in elements {
            let e = &self.deck.elements[self.deck.element_index[id]];
            ids.extend_from_slice(&e.nodes);
        }
        Ok(ids)
    }

    pub(super) fn set(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
        let ids = if kind == Members::Nodes && card.param("ELSET").is_some() {
            self.nodes_of_elements(card, &inner)?
        } else {
            let data: Vec<DataLine> = lines(card).cloned().collect();
            members(card, &data, kind, &inner, &self.instances, &self.deck)?
        };
        let sets = if kind == Members::Nodes {
            &mut self.deck.node_sets
        } else {
            &mut self.deck.element_sets
        };
        add_to_set(sets, name, &ids);
        Ok(())
    }

    pub(super) fn check_face(
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

    pub(super) fn surface(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
                let n = faces.len();
                let mut seen = std::collections::HashSet::new();
                faces.retain(|f| seen.insert(*f));
                if faces.len() < n {
                    self.warnings.push(card.origin.warning(
                        &card.name(),
                        format!("surface {name}: {} faces listed more than once, each counted once (a surface is a set)", n - faces.len()),
                    ));
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
                let n = nodes.len();
                let mut seen = std::collections::HashSet::new();
                nodes.retain(|(id, _)| seen.insert(*id));
                if nodes.len() < n {
                    self.warnings.push(card.origin.warning(
                        &card.name(),
                        format!("surface {name}: {} nodes listed more than once, each counted once (the first line's area kept)", n - nodes.len()),
                    ));
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
}

/// Global Cartesian coordinates of a node given in `system` (Abaqus's `*NODE, SYSTEM=`):
/// `R` (x, y, z); `C` cylindrical (r, θ, z), θ in degrees about z from x; `S` spherical
/// (r, θ, φ), θ in degrees about z from x, φ in degrees from the x–y plane toward z.
pub(super) fn cartesian(system: &str, v: [f64; 3]) -> [f64; 3] {
    match system {
        "C" => {
            let (s, c) = v[1].to_radians().sin_cos();
            [v[0] * c, v[0] * s, v[2]]
        }
        "S" => {
            let (st, ct) = v[1].to_radians().sin_cos();
            let (sp, cp) = v[2].to_radians().sin_cos();
            [v[0] * cp * ct, v[0] * cp * st, v[0] * sp]
        }
        _ => v,
    }
}
