//! The second test binary of `mech` (`machines`; the first is `suite`, whose root
//! `tests/suite.rs` says why there are two): machine elements, cams, gears, rolling,
//! flywheels, the DSL's checks (the trybuild compile-fail cases of `tests/ui` and the
//! compile-pass topologies), run-time parameters and the Python package. None of these uses
//! `tests/common/mechanisms.rs`. Run one module with `cargo test --test machines <name>::`.

// ---------------------------------------------------------------------------------------
// Shared by the test modules, compiled once; a module uses them as `use crate::data;`.

#[path = "common/counting.rs"]
mod counting;

#[path = "common/measure.rs"]
mod measure;

#[path = "common/data.rs"]
mod data;

#[path = "common/engine.rs"]
mod engine;

#[path = "common/shaper.rs"]
mod shaper;

/// The counting allocator of the zero-allocation tests (cam_rockers, elements, gears,
/// rolling, runtime_alloc), installed once for the whole binary: it counts each thread's own
/// allocations (`counting::tests`).
#[global_allocator]
static ALLOC: counting::Counting = counting::Counting;

// ---------------------------------------------------------------------------------------
// The test modules, one for each file tests/<name>.rs.

mod balancing;
mod cam_laws;
mod cam_rockers;
mod cams;
mod compile_fail;
mod compile_pass;
mod dimensions;
mod docs_figures;
mod elements;
mod engines;
mod flywheel;
mod flywheel_designer;
mod friction;
mod gears;
mod large;
mod loader_errors;
mod optimize;
mod params;
mod python_package;
mod redundant;
mod regime;
mod rolling;
mod runtime_alloc;
mod shapes;
mod spatial;
mod strength;
mod synthesis;
