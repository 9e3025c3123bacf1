//! `*CLOAD`, `*DLOAD`, `*DSLOAD`: the open step's loads, each with its real or imaginary part.

use super::*;

impl Reader {
    /// `*CLOAD`: concentrated loads of the open step (real or imaginary part).
    pub(super) fn cload(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
        Ok(())
    }

    /// `*DLOAD`: face pressures P1…P6 of the open step.
    pub(super) fn dload(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
        Ok(())
    }

    /// `*DSLOAD`: surface pressures P of the open step.
    pub(super) fn dsload(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
        Ok(())
    }
}
