//! The integration tests of `mech`, one test binary (`cargo test --test suite`), so that the
//! shared mechanisms, the `mechanism!` expansions of `tests/common/` and the crate graph are
//! compiled and linked once rather than once for each file (tests/README.md).
//!
//! Every `tests/<name>.rs` is the module `<name>` below, in place: `#[path]`s, `include!`s
//! and `include_str!`s in it still resolve from `tests/`. Run one of them with
//! `cargo test --test suite <name>::`. A new file must be declared here: the `layout` test
//! below fails for a `tests/*.rs` that is not (`autotests = false` in Cargo.toml, so cargo
//! no longer makes a binary of each file).

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

#[path = "common/data.rs"]
mod data;

#[path = "common/engine.rs"]
mod engine;

#[path = "common/shaper.rs"]
mod shaper;

/// The counting allocator of the zero-allocation tests (allocation, runtime_alloc, gears,
/// dynamics, rolling, elements, cam_rockers), installed once for the whole binary. It counts
/// each thread's own allocations, so the tests that run at the same time on the harness's
/// other threads do not disturb a count (`counting::tests` checks both halves of that).
#[global_allocator]
static ALLOC: counting::Counting = counting::Counting;

// ---------------------------------------------------------------------------------------
// The test modules, one for each file tests/<name>.rs.

mod allocation;
mod cam_laws;
mod cam_rockers;
mod cams;
mod compile_fail;
mod compile_pass;
mod dimensions;
mod dyads;
mod dynamics;
mod elements;
mod floor;
mod flywheel;
mod flywheel_designer;
mod friction;
mod gears;
mod generic;
mod hostile;
mod kinematics;
mod large;
mod loader_errors;
mod mechanism;
mod params;
mod public_api;
mod python_package;
mod redundant;
mod reference;
mod rolling;
mod runtime_alloc;
mod runtime_peer;
mod stress;

/// The suite is complete: every `tests/*.rs` but this file is one of its modules (with
/// `autotests = false`, a file that is not would silently never run).
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
            "tests/{missing:?} not declared in tests/suite.rs"
        );
    }
}
