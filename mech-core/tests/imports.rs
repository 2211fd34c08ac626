//! The folders of mech-core are layers, and imports run one way: a module imports only
//! from its own folder or from a folder below it in [`LAYERS`], and the graph of
//! `crate::<folder>::<module>` references between modules (outside `#[cfg(test)]` code
//! and comments) has no cycle. ARCHITECTURE.md draws the same layers.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The folders (and root files) of `mech-core/src`, lowest first.
const LAYERS: &[&str] = &[
    "error", "kernel", "elements", "model", "front", "plan", "checks", "solvers", "spatial",
    "dynamics", "strength", "runtime", "design",
];

/// Files that are not a layer's module: the crate root, the generated code's hidden
/// paths (they reach every layer on purpose).
const OUTSIDE: &[&str] = &["lib", "private"];

/// Every module file under `src` as `folder::module` (`error` for a root file, `folder`
/// for a folder's `mod.rs`), with its code stripped of `#[cfg(test)]` tails and comments.
fn sources() -> BTreeMap<String, String> {
    fn walk(dir: &Path, prefix: &str, out: &mut BTreeMap<String, String>) {
        for entry in std::fs::read_dir(dir).expect("src") {
            let path = entry.expect("entry").path();
            let stem = path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or_default()
                .to_string();
            if path.is_dir() {
                let sub = if prefix.is_empty() {
                    stem
                } else {
                    format!("{prefix}::{stem}")
                };
                walk(&path, &sub, out);
            } else if path.extension().is_some_and(|e| e == "rs") && stem != "tests" {
                // (`tests.rs`: a folder's `#[cfg(test)] mod tests`, as the tails below)
                let name = match (prefix.is_empty(), stem.as_str()) {
                    (true, s) => s.to_string(),
                    (false, "mod") => prefix.to_string(),
                    (false, s) => format!("{prefix}::{s}"),
                };
                let text = std::fs::read_to_string(&path).expect("read");
                let code = text.split("#[cfg(test)]").next().unwrap_or_default();
                let code = code
                    .lines()
                    .map(|l| l.split("//").next().unwrap_or_default())
                    .collect::<Vec<_>>()
                    .join("\n");
                out.insert(name, code);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/src")),
        "",
        &mut out,
    );
    out.retain(|name, _| !OUTSIDE.contains(&name.as_str()));
    out
}

/// The layer (top folder or root file) of a module name.
fn layer(module: &str) -> &str {
    module.split("::").next().unwrap_or_default()
}

/// Module → the modules it names through `crate::...` paths (the longest known prefix of
/// each path; the crate root's re-exports `MechError` and `Mechanism` are their modules').
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let sources = sources();
    let names: BTreeSet<String> = sources.keys().cloned().collect();
    let resolve = |path: &str| -> Option<String> {
        match path.split("::").next()? {
            "MechError" => return Some("error".into()),
            "Mechanism" => return Some("runtime::mechanism".into()),
            _ => {}
        }
        let parts: Vec<&str> = path.split("::").collect();
        (1..=parts.len().min(3))
            .rev()
            .map(|n| parts[..n].join("::"))
            .find(|p| names.contains(p))
    };
    sources
        .iter()
        .map(|(m, code)| {
            let mut deps = BTreeSet::new();
            for rest in code.split("crate::").skip(1) {
                if let Some(group) = rest.strip_prefix('{') {
                    // `use crate::{a::b, C}`: each item of the group.
                    for item in group.split('}').next().unwrap_or_default().split(',') {
                        deps.extend(resolve(item.trim()));
                    }
                    continue;
                }
                let path: String = rest
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                    .collect();
                deps.extend(resolve(path.trim_end_matches(':')));
            }
            deps.remove(m);
            (m.clone(), deps)
        })
        .collect()
}

#[test]
fn every_folder_is_a_layer() {
    let g = graph();
    assert!(g.len() > 40, "read the modules: {:?}", g.keys());
    for m in g.keys() {
        assert!(
            LAYERS.contains(&layer(m)),
            "{m} is in no layer of {LAYERS:?}"
        );
    }
}

#[test]
fn imports_run_down_the_layers() {
    let rank = |m: &str| LAYERS.iter().position(|l| *l == layer(m)).expect("a layer");
    let mut wrong = Vec::new();
    for (m, deps) in graph() {
        for d in deps.iter().filter(|d| rank(d) > rank(&m)) {
            wrong.push(format!("{m} imports {d}"));
        }
    }
    assert!(
        wrong.is_empty(),
        "imports up the layers {LAYERS:?}:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn module_imports_have_no_cycle() {
    let g = graph();
    // Kahn's algorithm: repeatedly remove modules that import nothing left.
    let mut left = g.clone();
    while !left.is_empty() {
        let free: Vec<String> = left
            .iter()
            .filter(|(_, d)| d.iter().all(|x| !left.contains_key(x)))
            .map(|(m, _)| m.clone())
            .collect();
        assert!(!free.is_empty(), "import cycle among {:?}", left);
        for m in free {
            left.remove(&m);
        }
    }
    // The kinematic core sits below the planner and the kernels the generated code calls.
    for (low, high) in [
        ("kernel::link_state", "kernel::constraints"),
        ("kernel::constraints", "kernel::screw"),
        ("kernel::screw", "kernel::kinematics"),
        ("kernel::dyad", "plan::assur"),
    ] {
        assert!(g[high].contains(low), "{high} should build on {low}");
        assert!(!g[low].contains(high), "{low} must not import {high}");
    }
}

/// The tree drawn in ARCHITECTURE.md (its first ```text block: one `path  what it holds`
/// line per file of `mech-core/src`) is the tree on disk, file for file.
#[test]
fn architecture_draws_the_tree_on_disk() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("../ARCHITECTURE.md")).expect("ARCHITECTURE.md");
    let block = text
        .split("```text\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("a ```text block");
    let drawn: BTreeSet<String> = block
        .lines()
        .filter_map(|l| l.split_whitespace().next())
        .filter(|p| p.ends_with(".rs"))
        .map(str::to_string)
        .collect();
    fn walk(dir: &Path, rel: &str, out: &mut BTreeSet<String>) {
        for entry in std::fs::read_dir(dir).expect("src") {
            let path = entry.expect("entry").path();
            let name = path
                .file_name()
                .and_then(|s| s.to_str())
                .unwrap_or_default();
            let rel = format!("{rel}/{name}");
            if path.is_dir() {
                walk(&path, &rel, out);
            } else if name.ends_with(".rs") {
                out.insert(rel);
            }
        }
    }
    let mut disk = BTreeSet::new();
    walk(&root.join("src"), "mech-core/src", &mut disk);
    let missing: Vec<_> = disk.difference(&drawn).collect();
    let stale: Vec<_> = drawn.difference(&disk).collect();
    assert!(
        missing.is_empty() && stale.is_empty(),
        "ARCHITECTURE.md's tree differs from mech-core/src: not drawn {missing:?}, gone {stale:?}"
    );
}
