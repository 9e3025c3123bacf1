//! Files no module declares: a `.rs` file under a crate's `src/` that no `mod name;` and
//! no `#[path = "…"]` of its directory's module names is never compiled — its tests
//! never run, its code is dead while it looks alive.

/// Files of `tree` (paths relative to `src/`, with their text) that no module declares.
pub fn orphans(tree: &[(String, String)]) -> Vec<String> {
    tree.iter()
        .map(|(f, _)| f)
        .filter(|f| !matches!(f.as_str(), "lib.rs" | "main.rs"))
        .filter(|f| !declared(tree, f))
        .cloned()
        .collect()
}

/// Whether a module file of `tree` declares `file`: its parent's `mod.rs`/`lib.rs`/
/// `main.rs` or the sibling `dir.rs` of its directory names it by `mod stem` (or `dir`
/// for `dir/mod.rs`), or some file's `#[path = "…"]` ends in its file name.
fn declared(tree: &[(String, String)], file: &str) -> bool {
    let (dir, name) = file.rsplit_once('/').unwrap_or(("", file));
    let (parent_dir, stem) = if name == "mod.rs" {
        let (pd, d) = dir.rsplit_once('/').unwrap_or(("", dir));
        (pd, d)
    } else {
        (dir, name.trim_end_matches(".rs"))
    };
    let join = |d: &str, f: &str| {
        if d.is_empty() {
            f.to_string()
        } else {
            format!("{d}/{f}")
        }
    };
    let mut declarers = vec![
        join(parent_dir, "mod.rs"),
        join(parent_dir, "lib.rs"),
        join(parent_dir, "main.rs"),
    ];
    if let Some((pd, d)) = parent_dir.rsplit_once('/').or(Some(("", parent_dir))) {
        if !d.is_empty() {
            declarers.push(join(pd, &format!("{d}.rs")));
        }
    }
    let by_mod = tree.iter().any(|(f, text)| {
        declarers.contains(f)
            && text.lines().any(|l| {
                let l = l.trim();
                let l = l.strip_prefix("pub ").unwrap_or(l);
                let l = l.strip_prefix("pub(crate) ").unwrap_or(l);
                l.strip_prefix("mod ")
                    .is_some_and(|rest| rest.trim_end_matches([';', ' ', '{']) == stem)
            })
    });
    let by_path = tree.iter().any(|(_, text)| {
        text.lines().any(|l| {
            let l = l.trim();
            l.starts_with("#[path") && l.trim_end_matches([']', '"']).ends_with(name)
        })
    });
    by_mod || by_path
}
