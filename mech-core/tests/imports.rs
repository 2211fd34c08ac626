//! The modules of mech-core import one another in one direction only: the graph of
//! `crate::<module>` references (outside `#[cfg(test)]` code and comments) has no cycle.

use std::collections::{BTreeMap, BTreeSet};

fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
    let mut sources = BTreeMap::new();
    for entry in std::fs::read_dir(dir).expect("src") {
        let path = entry.expect("entry").path();
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or_default()
            .to_string();
        if path.extension().is_some_and(|e| e == "rs") && name != "lib" {
            let text = std::fs::read_to_string(&path).expect("read");
            let code = text.split("#[cfg(test)]").next().unwrap_or_default();
            let code: String = code
                .lines()
                .map(|l| l.split("//").next().unwrap_or_default())
                .collect::<Vec<_>>()
                .join("\n");
            sources.insert(name, code);
        }
    }
    let names: BTreeSet<String> = sources.keys().cloned().collect();
    sources
        .iter()
        .map(|(m, code)| {
            let deps = code
                .split("crate::")
                .skip(1)
                .map(|rest| {
                    rest.chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect::<String>()
                })
                .filter(|d| names.contains(d) && d != m)
                .collect();
            (m.clone(), deps)
        })
        .collect()
}

#[test]
fn module_imports_have_no_cycle() {
    let g = graph();
    assert!(g.len() > 20, "read the modules: {:?}", g.keys());
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
        ("link_state", "constraints"),
        ("constraints", "screw"),
        ("screw", "kinematics"),
        ("dyad", "assur"),
    ] {
        assert!(g[high].contains(low), "{high} should build on {low}");
        assert!(!g[low].contains(high), "{low} must not import {high}");
    }
}
