//! `--set KEY=VALUE`: a scene value changed on the command line before the scene is read,
//! so one scene file serves a variant of its model (e.g. the same mesh in harmonic balance)
//! without a copy. KEY is a dotted path of the scene's TOML: table keys, an index into an
//! array of tables (`interfaces.0.mu`) or `*` for every element (`interfaces.*.rule`).
//! VALUE is a TOML value (`0.3`, `[1, 2]`, `"masing"`); a bare word that is not one is
//! taken as a string (`masing`); nothing after `=` removes the key. A value under a table
//! the scene leaves out creates the table (the schema refuses a name it does not know).
//! The changed text is the scene's text (comments kept), so what a run reports is what
//! it ran.

use std::str::FromStr;

use toml_edit::{DocumentMut, Item, Value};

/// One `KEY=VALUE`.
#[derive(Debug, Clone)]
pub struct Override {
    /// As given on the command line.
    text: String,
    path: Vec<String>,
    /// `None`: remove the key.
    value: Option<Value>,
}

impl Override {
    /// The top-level key (table) this override sets a value in.
    pub fn table(&self) -> &str {
        self.path.first().map_or("", String::as_str)
    }

    /// Whether this override set the value at `key` or a table holding it: `key` in
    /// the errors' form (`interfaces[0].mu`), the override's path with `*` for any index.
    pub fn covers(&self, key: &str) -> bool {
        let segments: Vec<String> = key
            .replace('[', ".")
            .replace(']', "")
            .split('.')
            .filter(|s| !s.is_empty())
            .map(str::to_string)
            .collect();
        self.path.len() <= segments.len()
            && self
                .path
                .iter()
                .zip(&segments)
                .all(|(p, s)| p == s || (p == "*" && s.parse::<usize>().is_ok()))
    }

    /// `KEY=VALUE` as given.
    pub fn text(&self) -> &str {
        &self.text
    }
}

impl FromStr for Override {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let (key, value) = s
            .split_once('=')
            .ok_or_else(|| format!("--set {s}: expected KEY=VALUE"))?;
        let path: Vec<String> = key.trim().split('.').map(str::to_string).collect();
        if path.iter().any(String::is_empty) {
            return Err(format!("--set {s}: empty key in {key:?}"));
        }
        let value = value.trim();
        let value = (!value.is_empty()).then(|| {
            Value::from_str(value)
                .unwrap_or_else(|_| Value::from(value))
                .decorated(" ", "")
        });
        Ok(Override {
            text: s.to_string(),
            path,
            value,
        })
    }
}

/// `text` with every override applied in order; an error names the key that does not fit
/// the scene (a missing table, an index past the end, a key under a value).
pub fn apply(text: &str, overrides: &[Override]) -> Result<String, String> {
    if overrides.is_empty() {
        return Ok(text.to_string());
    }
    let mut doc = DocumentMut::from_str(text).map_err(|e| e.to_string())?;
    for o in overrides {
        set(
            doc.as_item_mut(),
            &o.path,
            &o.value,
            &o.path.join("."),
            false,
        )?;
    }
    Ok(doc.to_string())
}

/// Sets `path` under `item` (the remaining segments of the override `key`); `under_all`:
/// below a `*`, where a key to remove may be missing from some elements.
fn set(
    item: &mut Item,
    path: &[String],
    value: &Option<Value>,
    key: &str,
    under_all: bool,
) -> Result<(), String> {
    let (first, rest) = path
        .split_first()
        .ok_or_else(|| format!("--set {key}: no key"))?;
    if let Some(array) = item.as_array_of_tables_mut() {
        let len = array.len();
        let picked: Vec<usize> = if first == "*" {
            (0..len).collect()
        } else {
            match first.parse::<usize>() {
                Ok(i) if i < len => vec![i],
                _ => {
                    return Err(format!(
                        "--set {key}: {first:?} is not an index below {len} or *"
                    ))
                }
            }
        };
        for i in picked {
            let table = array.get_mut(i).expect("index below len");
            set_in_table(table, rest, value, key, under_all || first == "*")?;
        }
        return Ok(());
    }
    let is_table = item.is_table();
    let table = item
        .as_table_like_mut()
        .ok_or_else(|| format!("--set {key}: {first:?} is under a value, not a table"))?;
    // A value set under a table the scene leaves out (a scene over a deck without
    // [iteration]) creates it; the schema then refuses a name it does not know.
    if is_table && !rest.is_empty() && value.is_some() && table.get(first).is_none() {
        let mut t = toml_edit::Table::new();
        t.set_implicit(true);
        table.insert(first, Item::Table(t));
    }
    if rest.is_empty() {
        match value {
            Some(v) => {
                table.insert(first, Item::Value(v.clone()));
            }
            None => {
                if table.remove(first).is_none() && !under_all {
                    return Err(format!("--set {key}: the scene has no {first:?} to remove"));
                }
            }
        }
        return Ok(());
    }
    let next = table
        .get_mut(first)
        .ok_or_else(|| format!("--set {key}: the scene has no table {first:?}"))?;
    set(next, rest, value, key, under_all)
}

fn set_in_table(
    table: &mut toml_edit::Table,
    path: &[String],
    value: &Option<Value>,
    key: &str,
    under_all: bool,
) -> Result<(), String> {
    let mut item = Item::Table(std::mem::take(table));
    let r = set(&mut item, path, value, key, under_all);
    if let Item::Table(t) = item {
        *table = t;
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_override_covers_the_keys_it_set() {
        let o: Override = "interfaces.*.mu=-1".parse().unwrap();
        assert!(o.covers("interfaces[0].mu") && o.covers("interfaces[3].mu"));
        assert!(!o.covers("interfaces[0].rule") && !o.covers("interfaces"));
        let o: Override = "sweep=".parse().unwrap();
        assert!(o.covers("sweep.count") && !o.covers("sweeps"));
        assert_eq!(o.text(), "sweep=");
    }

    #[test]
    fn a_value_under_a_missing_table_creates_it() {
        let text = "title = \"t\"\n[sweep]\ncount = 3\n";
        let out = set_all(text, &["iteration.tolerance=1e-10"]).unwrap();
        let doc: DocumentMut = out.parse().unwrap();
        assert_eq!(doc["iteration"]["tolerance"].as_float(), Some(1e-10));
        assert_eq!(doc["sweep"]["count"].as_integer(), Some(3));
        // Removing under a missing table is still an error.
        let e = set_all(text, &["iteration.tolerance="]).unwrap_err();
        assert!(e.contains("has no table"), "{e}");
    }

    fn set_all(text: &str, overrides: &[&str]) -> Result<String, String> {
        let o: Vec<Override> = overrides
            .iter()
            .map(|s| s.parse())
            .collect::<Result<_, _>>()?;
        apply(text, &o)
    }

    const SCENE: &str = "# a scene\n[iteration]\nmode = \"fast\" # the default\ntolerance = 1e-3\n\n[[interfaces]]\nname = \"a\"\nrule = \"thesis\"\narea_samples = 4\n\n[[interfaces]]\nname = \"b\"\nrule = \"thesis\"\n";

    #[test]
    fn values_tables_and_every_element_of_an_array_of_tables() {
        let t = set_all(
            SCENE,
            &[
                "iteration.mode=harmonic_balance",
                "iteration.harmonics=3",
                "interfaces.*.rule=\"masing\"",
                "interfaces.*.area_samples=",
                "interfaces.1.mu=0.25",
            ],
        )
        .unwrap();
        let v: toml::Table = toml::from_str(&t).unwrap();
        assert_eq!(v["iteration"]["mode"].as_str(), Some("harmonic_balance"));
        assert_eq!(v["iteration"]["harmonics"].as_integer(), Some(3));
        let itf = v["interfaces"].as_array().unwrap();
        for i in itf {
            assert_eq!(i["rule"].as_str(), Some("masing"));
            assert!(i.get("area_samples").is_none());
        }
        assert_eq!(itf[1]["mu"].as_float(), Some(0.25));
        assert!(itf[0].get("mu").is_none());
        assert!(t.starts_with("# a scene\n"), "comments are kept: {t}");
    }

    #[test]
    fn a_key_that_does_not_fit_the_scene_is_named() {
        for (o, says) in [
            ("interfaces.2.rule=masing", "not an index below 2"),
            ("sweep.count=", "no table \"sweep\""),
            ("iteration.mode.x=1", "under a value"),
            ("iteration.missing=", "no \"missing\" to remove"),
            ("iteration..mode=1", "empty key"),
            ("iteration", "KEY=VALUE"),
        ] {
            let e = set_all(SCENE, &[o]).unwrap_err();
            assert!(e.contains(says), "{o}: {e}");
        }
    }
}
