//! The integration tests of the `mech` command, one test binary (`cargo test -p mech-cli
//! --test suite`): each tests/<name>.rs is the module `<name>` below, in place, and spawns
//! the `mech` binary of this crate (`Command::cargo_bin("mech")`). Run one of them with
//! `cargo test -p mech-cli --test suite <name>::`. `autotests = false` in Cargo.toml, so a
//! new file must be declared here: the `layout` test fails for one that is not.
//!
//! insta names a snapshot after its module path: the snapshots of `snapshots` are
//! `tests/snapshots/suite__snapshots__<name>.snap`.

mod balance;
mod cli;
mod draw;
mod engine;
mod hostile;
mod import;
mod optimize;
mod regime;
mod serve;
mod snapshots;
mod spatial;
mod strength;
mod synth;
mod synth_exact;

/// Every `tests/*.rs` but this file is one of the modules above.
#[cfg(test)]
mod layout {
    #[test]
    fn every_test_file_is_a_module_of_the_suite() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests");
        let suite = include_str!("suite.rs");
        let mut missing = Vec::new();
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_str().unwrap().to_owned();
            if let Some(stem) = name.strip_suffix(".rs") {
                if stem != "suite" && !suite.lines().any(|l| l == format!("mod {stem};")) {
                    missing.push(name);
                }
            }
        }
        assert!(
            missing.is_empty(),
            "mech-cli/tests/{missing:?} not declared in mech-cli/tests/suite.rs"
        );
    }
}
