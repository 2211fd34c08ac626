//! The public API is a decision: the items `mech` (the facade) and `mech-core` make public
//! are listed in `docs/public-api/<crate>.txt`, and this test fails when the code's public
//! items differ from the listing. The listing is read off rustdoc's JSON output (nightly
//! rustdoc, `--output-format json`): every public module, item and re-export reachable from
//! the crate root, by path; `#[doc(hidden)]` items (the generated code's `__private`) are
//! left out, as rustdoc leaves them out.
//!
//! After a deliberate change: `MECH_BLESS=1 cargo test public_api` rewrites the listings;
//! commit them with the change.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The public items of `package` (lib name `lib`), one line each, sorted.
fn listing(package: &str, lib: &str) -> Result<Vec<String>, String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let target = root.join("target").join("public-api");
    let out = Command::new("cargo")
        .current_dir(root)
        .env_remove("RUSTFLAGS")
        .env_remove("RUSTDOCFLAGS")
        .args([
            "+nightly",
            "rustdoc",
            "-q",
            "--lib",
            "-p",
            package,
            "--target-dir",
        ])
        .arg(&target)
        .args(["--", "-Z", "unstable-options", "--output-format", "json"])
        .output()
        .map_err(|e| format!("cargo +nightly rustdoc: {e}"))?;
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).into_owned());
    }
    let path: PathBuf = target.join("doc").join(format!("{lib}.json"));
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).map_err(|e| e.to_string())?)
            .map_err(|e| e.to_string())?;
    let mut lines = Vec::new();
    walk(&json, &json["root"], lib, &mut lines);
    lines.sort();
    lines.dedup();
    Ok(lines)
}

/// The item `id` of the JSON index, if it is there.
fn item<'a>(json: &'a Value, id: &Value) -> Option<&'a Value> {
    let key = match id {
        Value::Number(n) => n.to_string(),
        Value::String(s) => s.clone(),
        _ => return None,
    };
    json["index"].get(key)
}

/// Every public item below the module `id` at `path`, as `kind path` or `use path = source`.
fn walk(json: &Value, id: &Value, path: &str, out: &mut Vec<String>) {
    let Some(module) = item(json, id) else { return };
    let Some(children) = module["inner"]["module"]["items"].as_array() else {
        return;
    };
    for child in children.iter().filter_map(|c| item(json, c)) {
        if child["visibility"] != "public" {
            continue;
        }
        let Some((kind, inner)) = child["inner"].as_object().and_then(|o| o.iter().next()) else {
            continue;
        };
        match kind.as_str() {
            "use" => {
                let name = inner["name"].as_str().unwrap_or_default();
                let glob = if inner["is_glob"] == true { "::*" } else { "" };
                out.push(format!(
                    "use {path}::{name} = {}{glob}",
                    inner["source"].as_str().unwrap_or_default()
                ));
            }
            "module" => {
                let name = child["name"].as_str().unwrap_or_default();
                let sub = format!("{path}::{name}");
                out.push(format!("mod {sub}"));
                walk(json, &child["id"], &sub, out);
            }
            "impl" => {}
            _ => out.push(format!(
                "{kind} {path}::{}",
                child["name"].as_str().unwrap_or_default()
            )),
        }
    }
}

fn check(package: &str, lib: &str) {
    let listing = match listing(package, lib) {
        Ok(l) => l,
        Err(e) if e.contains("toolchain 'nightly") && e.contains("not installed") => {
            // The listing needs nightly rustdoc; without it nothing can be compared.
            eprintln!("public_api: no nightly toolchain here, {package} not checked");
            return;
        }
        Err(e) => panic!("rustdoc JSON of {package} failed:\n{e}"),
    };
    assert!(
        listing.len() > 20,
        "{package}: too few public items read: {listing:?}"
    );
    let file = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("docs/public-api")
        .join(format!("{package}.txt"));
    let text = listing.join("\n") + "\n";
    if std::env::var_os("MECH_BLESS").is_some() {
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(&file, &text).unwrap();
        return;
    }
    let committed = std::fs::read_to_string(&file).unwrap_or_default();
    if committed != text {
        let old: std::collections::BTreeSet<&str> = committed.lines().collect();
        let new: std::collections::BTreeSet<&str> = text.lines().collect();
        panic!(
            "the public API of {package} differs from {}:\n  added: {:?}\n  removed: {:?}\nIf deliberate: MECH_BLESS=1 cargo test public_api, and commit the listing.",
            file.display(),
            new.difference(&old).collect::<Vec<_>>(),
            old.difference(&new).collect::<Vec<_>>()
        );
    }
}

#[test]
fn public_api_of_the_facade_is_the_listing() {
    check("mech", "mech");
}

#[test]
fn public_api_of_mech_core_is_the_listing() {
    check("mech-core", "mech_core");
}
