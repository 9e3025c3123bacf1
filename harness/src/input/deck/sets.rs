//! Names, ids and set members as the cards write them, resolved in a scope (the flat
//! model, or one instance of a part: names prefixed `INSTANCE.`, ids offset).

use super::error::{DeckError, DeckErrorKind};
use super::lexer::{parse_id, Card, DataLine};
use super::model::Deck;

/// Where a card is read: the flat model or one part instance.
#[derive(Debug, Clone, Default)]
pub struct Scope {
    /// Instance name with a dot (`"BOLT-1."`), or "" for the flat model and assembly.
    pub prefix: String,
    /// Added to every node / element id of the part.
    pub node_offset: u64,
    pub element_offset: u64,
    /// Added to every node coordinate of the part (length).
    pub translation: [f64; 3],
}

/// Node or element members.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Members {
    Nodes,
    Elements,
}

impl Members {
    fn what(self) -> &'static str {
        match self {
            Members::Nodes => "node",
            Members::Elements => "element",
        }
    }
}

impl Scope {
    /// The full upper-case name of `raw` in this scope.
    pub fn name(&self, raw: &str) -> String {
        format!("{}{}", self.prefix, raw.trim().trim_matches('"')).to_ascii_uppercase()
    }

    /// The id of `raw` in this scope (`5`, or `INSTANCE.5` from the assembly), if it is
    /// an id.
    pub fn id(&self, raw: &str, members: Members, instances: &InstanceOffsets) -> Option<u64> {
        if let Some(id) = parse_id(raw) {
            let off = match members {
                Members::Nodes => self.node_offset,
                Members::Elements => self.element_offset,
            };
            return id.checked_add(off);
        }
        let (inst, local) = raw.trim().rsplit_once('.')?;
        let id = parse_id(local)?;
        let &(n, e) = instances.get(&inst.to_ascii_uppercase())?;
        id.checked_add(if members == Members::Nodes { n } else { e })
    }
}

/// Instance name → (node offset, element offset).
pub type InstanceOffsets = std::collections::HashMap<String, (u64, u64)>;

/// The members listed by the data lines of a `*NSET`/`*ELSET` card (ids, set names, or
/// `GENERATE` triples first, last, increment), every id checked to exist.
pub fn members(
    card: &Card,
    lines: &[DataLine],
    kind: Members,
    scope: &Scope,
    instances: &InstanceOffsets,
    deck: &Deck,
) -> Result<Vec<u64>, DeckError> {
    let mut out = Vec::new();
    let exists = |id: u64| match kind {
        Members::Nodes => deck.node_index.contains_key(&id),
        Members::Elements => deck.element_index.contains_key(&id),
    };
    for l in lines {
        let fields: Vec<&str> = l
            .fields
            .iter()
            .map(String::as_str)
            .filter(|f| !f.is_empty())
            .collect();
        if fields.is_empty() {
            continue;
        }
        if card.flag("GENERATE") {
            let v: Vec<u64> = fields.iter().filter_map(|f| parse_id(f)).collect();
            if v.len() != fields.len() || !(2..=3).contains(&v.len()) {
                return Err(card.error_at(
                    l.line,
                    DeckErrorKind::Syntax,
                    "GENERATE needs first, last[, increment] (positive integers)",
                ));
            }
            let (first, last, inc) = (v[0], v[1], v.get(2).copied().unwrap_or(1));
            if last < first {
                return Err(card.error_at(
                    l.line,
                    DeckErrorKind::BadValue,
                    format!("GENERATE last {last} < first {first}"),
                ));
            }
            let mut id = first;
            while id <= last {
                let full = scope
                    .id(&id.to_string(), kind, instances)
                    .unwrap_or(u64::MAX);
                if !exists(full) {
                    return Err(card.error_at(
                        l.line,
                        DeckErrorKind::Undefined,
                        format!("{} {id} is not defined", kind.what()),
                    ));
                }
                out.push(full);
                id += inc;
            }
            continue;
        }
        for f in fields {
            if let Some(id) = scope.id(f, kind, instances) {
                if !exists(id) {
                    return Err(card.error_at(
                        l.line,
                        DeckErrorKind::Undefined,
                        format!("{} {f} is not defined", kind.what()),
                    ));
                }
                out.push(id);
            } else {
                let name = scope.name(f);
                let set = match kind {
                    Members::Nodes => deck.node_sets.get(&name),
                    Members::Elements => deck.element_sets.get(&name),
                };
                match set {
                    Some(ids) => out.extend_from_slice(ids),
                    None => {
                        return Err(card.error_at(
                            l.line,
                            DeckErrorKind::Undefined,
                            format!("{} set {name} is not defined", kind.what()),
                        ))
                    }
                }
            }
        }
    }
    Ok(out)
}

/// Appends `ids` to set `name` of `sets`, keeping the first occurrence of each id.
pub fn add_to_set(
    sets: &mut std::collections::BTreeMap<String, Vec<u64>>,
    name: String,
    ids: &[u64],
) {
    let set = sets.entry(name).or_default();
    let mut seen: std::collections::HashSet<u64> = set.iter().copied().collect();
    set.extend(ids.iter().copied().filter(|id| seen.insert(*id)));
}
