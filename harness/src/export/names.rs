//! The deck's names: the scene's names upper case (Abaqus names are case-insensitive),
//! each a valid Abaqus label (a letter, then letters, digits and underscores, at most 80
//! characters) and unique among the deck's sets and surfaces.

use std::collections::BTreeMap;

use super::ExportError;
use crate::input::scene::{FaceName, Scene};

/// The scene's names as deck labels.
pub struct Names {
    /// Material key → label.
    pub materials: BTreeMap<String, String>,
    /// Per body: its element set.
    pub bodies: Vec<String>,
    /// Per interface: its interaction.
    pub interfaces: Vec<String>,
    /// Per output: its node set.
    pub outputs: Vec<String>,
}

/// Longest Abaqus label.
const MAX_LEN: usize = 80;

fn label(name: &str) -> Option<String> {
    let ok = name.len() <= MAX_LEN - 8 // room for the suffixes added below
        && name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    ok.then(|| name.to_ascii_uppercase())
}

impl Names {
    /// The labels of `scene`'s names; a name that is no Abaqus label, or two names
    /// that become the same label, is an error naming the key.
    pub fn new(scene: &Scene) -> Result<Names, ExportError> {
        let s = &scene.spec;
        // Materials have their own namespace; sets and surfaces share one.
        let mut materials_seen: BTreeMap<String, String> = BTreeMap::new();
        let mut sets_seen: BTreeMap<String, String> = BTreeMap::new();
        let take = |seen: &mut BTreeMap<String, String>,
                    key: String,
                    name: &str|
         -> Result<String, ExportError> {
            let err = |message: String| ExportError::Unsupported {
                file: scene.file.clone(),
                key: key.clone(),
                message,
            };
            let l = label(name).ok_or_else(|| {
                err(format!(
                    "`{name}` is no Abaqus name (a letter, then letters, digits, underscores; at most {} characters)",
                    MAX_LEN - 8
                ))
            })?;
            if let Some(other) = seen.insert(l.clone(), key.clone()) {
                return Err(err(format!(
                    "`{name}` is the deck name {l} of `{other}` too (Abaqus names ignore case)"
                )));
            }
            Ok(l)
        };
        let mut materials = BTreeMap::new();
        for k in s.materials.keys() {
            materials.insert(
                k.clone(),
                take(&mut materials_seen, format!("materials.{k}"), k)?,
            );
        }
        let bodies = (s.bodies.iter().enumerate())
            .map(|(i, b)| take(&mut sets_seen, format!("bodies[{i}].name"), &b.name))
            .collect::<Result<_, _>>()?;
        let interfaces = (s.interfaces.iter().enumerate())
            .map(|(i, f)| take(&mut sets_seen, format!("interfaces[{i}].name"), &f.name))
            .collect::<Result<_, _>>()?;
        let outputs = (s.outputs.iter().enumerate())
            .map(|(i, o)| take(&mut sets_seen, format!("outputs[{i}].name"), &o.name))
            .collect::<Result<_, _>>()?;
        Ok(Names {
            materials,
            bodies,
            interfaces,
            outputs,
        })
    }
}

/// A box face as part of a label: `XMIN` … `ZMAX`.
pub fn face(f: FaceName) -> &'static str {
    match f {
        FaceName::XMin => "XMIN",
        FaceName::XMax => "XMAX",
        FaceName::YMin => "YMIN",
        FaceName::YMax => "YMAX",
        FaceName::ZMin => "ZMIN",
        FaceName::ZMax => "ZMAX",
    }
}
