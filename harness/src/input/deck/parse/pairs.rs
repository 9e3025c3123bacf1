//! `*CONTACT PAIR` and `*TIE`: surface pairs, one per data line.

use super::*;

impl Reader {
    /// `*CONTACT PAIR, INTERACTION=`: node-to-surface pairs, one per data line (a
    /// repeated pair is a warning).
    pub(super) fn contact_pair(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
            let earlier =
                (self.deck.contact_pairs.iter()).map(|c| (&c.slave, &c.master, c.origin.line));
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
        Ok(())
    }

    /// `*TIE, NAME=`: tied surface pairs, one per data line (a repeated pair is a warning).
    pub(super) fn tie(&mut self, card: &Card, scope: &Scope) -> Result<(), DeckError> {
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
            let earlier = (self.deck.ties.iter()).map(|t| (&t.slave, &t.master, t.origin.line));
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
        Ok(())
    }
}
