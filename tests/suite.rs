//! The integration tests of `mech` are two test binaries, this one (`suite`: the solvers on
//! the reference mechanisms of `tests/common/mechanisms.rs`) and `machines`
//! (`tests/machines.rs`: machine elements, cams, gears, flywheels, the DSL's checks and the
//! Python package), so that the shared code of `tests/common/`, the `mechanism!` expansions
//! and the crate graph are compiled and linked once or twice rather than once for each file
//! (tests/README.md).
//!
//! Why two and not one: a crate's front end (expansion, type checking) runs on one core, and
//! the whole of `tests/` as one crate was the build's critical path, 158 s of the 200 s of a
//! rebuild on this two-core machine while the other core idled; two halves of about the same
//! size compile side by side. The split follows what is shared: every user of
//! `mechanisms.rs` is here, so the ten reference mechanisms are still compiled once.
//!
//! Every `tests/<name>.rs` is the module `<name>` of one of the two, in place: `#[path]`s,
//! `include!`s and `include_str!`s in it still resolve from `tests/`. Run one with
//! `cargo test --test suite <name>::` (or `--test machines`). A new file must be declared in
//! one of them: the `layout` test below fails for a `tests/*.rs` that is not
//! (`autotests = false` in Cargo.toml, so cargo no longer makes a binary of each file).

// ---------------------------------------------------------------------------------------
// Shared by the test modules, compiled once; a module uses them as `use crate::mechanisms;`.

#[path = "common/mechanisms.rs"]
mod mechanisms;

mod support;

// Declared before the modules that use its `generic_test!` (generic, mechanism).
#[path = "common/against_reference.rs"]
#[macro_use]
mod against_reference;

#[path = "common/counting.rs"]
mod counting;

#[path = "common/measure.rs"]
mod measure;

#[path = "common/engine.rs"]
mod engine;

/// The counting allocator of the zero-allocation tests (allocation, dynamics), installed
/// once for the whole binary. It counts each thread's own allocations, so the tests that run
/// at the same time on the harness's other threads do not disturb a count
/// (`counting::tests` checks both halves of that).
#[global_allocator]
static ALLOC: counting::Counting = counting::Counting;

// ---------------------------------------------------------------------------------------
// The test modules, one for each file tests/<name>.rs.

mod allocation;
mod batch;
mod dyads;
mod dynamics;
mod floor;
mod floor_runtime;
mod generic;
mod hostile;
mod kinematics;
mod mechanism;
mod public_api;
mod reference;
mod runtime_peer;
mod stress;
mod triads;

/// The two binaries together are the whole of `tests/`: every `tests/*.rs` but their roots
/// is a module of exactly one of them (`autotests = false`: a file declared in neither would
/// silently never run, one declared in both would be compiled and run twice).
#[cfg(test)]
mod layout {
    #[test]
    fn every_test_file_is_a_module_of_one_binary() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests");
        let roots = [include_str!("suite.rs"), include_str!("machines.rs")];
        let mut wrong = Vec::new();
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_str().unwrap().to_owned();
            if let Some(stem) = name.strip_suffix(".rs") {
                let declared = roots
                    .iter()
                    .filter(|r| r.lines().any(|l| l == format!("mod {stem};")))
                    .count();
                if stem != "suite" && stem != "machines" && declared != 1 {
                    wrong.push((name, declared));
                }
            }
        }
        assert!(
            wrong.is_empty(),
            "tests/ files declared in tests/suite.rs and tests/machines.rs not once: {wrong:?}"
        );
    }
}
