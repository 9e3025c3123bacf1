//! `*MATERIAL` with `*ELASTIC`, `*DENSITY`, `*DAMPING`; `*SOLID SECTION`,
//! `*SURFACE INTERACTION`, `*BOUNDARY`.

use super::*;

impl Reader {
    pub(super) fn material_data(&mut self, card: &Card) -> Result<(), DeckError> {
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
                if m.damping.is_some() || m.structural.is_some() {
                    return Err(card.error(
                        K::Duplicate,
                        format!("material {name} has a *DAMPING already (one card gives ALPHA, BETA and STRUCTURAL)"),
                    ));
                }
                let (a, b, s) = (
                    param_number(card, "ALPHA", 0.0)?,
                    param_number(card, "BETA", 0.0)?,
                    param_number(card, "STRUCTURAL", 0.0)?,
                );
                if a < 0.0 || b < 0.0 || s < 0.0 {
                    return Err(card.error(
                        K::BadValue,
                        format!("ALPHA = {a}, BETA = {b}, STRUCTURAL = {s} must be >= 0"),
                    ));
                }
                m.damping = Some((a, b));
                m.structural = card.param("STRUCTURAL").map(|_| s);
            }
        }
        Ok(())
    }

    pub(super) fn interaction(&mut self, card: &Card) -> Result<(), DeckError> {
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

    pub(super) fn surface_pair(
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
        if out[0] == out[1] {
            return Err(card.error_at(
                l.line,
                K::BadValue,
                format!("slave and master are the same surface {}", out[0]),
            ));
        }
        Ok(out)
    }

    pub(super) fn boundary(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
        choice(card, "OP", &["MOD"], "MOD")?;
        choice(card, "TYPE", &["DISPLACEMENT"], "DISPLACEMENT")?;
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
}

impl Reader {
    /// `*MATERIAL, NAME=`: a new material, the one the following material cards fill.
    pub(super) fn material(&mut self, card: &Card) -> Result<(), DeckError> {
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
        Ok(())
    }

    /// `*SOLID SECTION, ELSET=, MATERIAL=`: a non-empty element set defined before.
    pub(super) fn solid_section(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
        Ok(())
    }
}
