//! Circles in an import graph (between rooms or between files).

use std::collections::{BTreeMap, BTreeSet};

use super::source::Import;

/// Node → imported node → the imports.
pub type Graph = BTreeMap<String, BTreeMap<String, Vec<Import>>>;

/// Adds the import `i` of `to` by `from` to `g` (once per statement).
pub fn add(g: &mut Graph, from: &str, to: &str, i: Import) {
    let list = g
        .entry(from.to_string())
        .or_default()
        .entry(to.to_string())
        .or_default();
    if !list.iter().any(|j| j.file == i.file && j.line == i.line) {
        list.push(i);
    }
}

/// The circles of `g`: each strongly connected set of two or more nodes, as a message
/// listing the imports between its nodes. Empty when the nodes are layered.
pub fn circles(g: &Graph) -> Vec<String> {
    let nodes: BTreeSet<&String> = g.keys().chain(g.values().flat_map(|m| m.keys())).collect();
    let reach = |from: &String| -> BTreeSet<String> {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(n) = stack.pop() {
            for m in g.get(&n).into_iter().flat_map(|e| e.keys()) {
                if seen.insert(m.clone()) {
                    stack.push(m.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<&String, BTreeSet<String>> =
        nodes.iter().map(|&n| (n, reach(n))).collect();
    let mut done = BTreeSet::new();
    let mut out = Vec::new();
    for &n in &nodes {
        if done.contains(n) || !reachable[n].contains(n) {
            continue;
        }
        // The rooms that reach n and that n reaches: n's circle.
        let set: BTreeSet<&String> = nodes
            .iter()
            .copied()
            .filter(|m| reachable[n].contains(*m) && reachable[m].contains(n))
            .collect();
        let mut msg = format!(
            "circle between {}:",
            set.iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        );
        for a in &set {
            for (b, imports) in g.get(*a).into_iter().flatten() {
                if set.contains(b) {
                    for i in imports {
                        msg += &format!("\n  {a} -> {b}: {}:{}: {}", i.file, i.line, i.text);
                    }
                }
            }
        }
        done.extend(set.iter().map(|s| (*s).clone()));
        out.push(msg);
    }
    out
}
