//! mech-core: the implementation crate of `mech` — the mechanics shared by the code the
//! `mechanism!` macro generates, the run-time [`Mechanism`] and the checks. Users depend on
//! the facade crate `mech`, whose API is the chosen subset of this one; the macro, the
//! `mech` tool and the Python package use this crate directly.
//!
//! Its folders are the pipeline, each a layer that imports only from the layers above it in
//! this list (the test `tests/imports.rs` enforces it; `ARCHITECTURE.md` draws it):
//!
//! | layer | holds |
//! |---|---|
//! | [`error`] | [`MechError`], the finiteness tests |
//! | [`kernel`] | a link's frame and its points' motion, the joints' constraint equations, each group kind's closed form or Newton, d'Alembert's wrenches: one entry point per group kind |
//! | [`elements`] | machine elements and their pair kernels: cams (law, profile, pair), gears, rolling contacts, springs and dampers |
//! | [`model`] | the plain data of a mechanism, its units |
//! | [`front`] | DSL text or tokens → a resolved [`model::Model`] |
//! | [`plan`] | the drawing's joint geometry, the Assur groups in solving order, each group's kernel |
//! | [`checks`] | Grübler, equations against unknowns, over-constrained sub-chains, magnitudes, the rank at the drawing; [`checks::load`], the whole front end written once for the macro and the run-time loader |
//! | [`solvers`] | the numbers of an instance, virtual power, Zhukovski's reduction, friction, the [`solvers::traits`] every mechanism implements |
//! | [`spatial`] | spatial mechanisms at run time: the `space` text form, Kutzbach's count, kinematics, kinetostatics, virtual power and Zhukovski in absolute coordinates |
//! | [`dynamics`] | the direct problem, the integrators, the flywheel, equivalent masses, written once over the traits |
//! | [`runtime`] | the run-time [`Mechanism`]: the plan walked with the generated code's kernels, its results |
//!
//! The generated code reaches what it needs through one hidden module, `__private`, that
//! lists exactly those items.

// Limits are tested as `!(x < limit)` on purpose: true for a NaN as well, so a NaN is
// refused wherever an out-of-range value is.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![deny(missing_docs)]

pub mod checks;
pub mod design;
pub mod dynamics;
pub mod elements;
pub mod error;
pub mod front;
pub mod kernel;
pub mod model;
pub mod plan;
pub mod runtime;
pub mod solvers;
pub mod spatial;
pub mod strength;

pub use error::MechError;
pub use nalgebra::{UnitQuaternion, Vector2, Vector3};
pub use runtime::mechanism::Mechanism;

#[doc(hidden)]
#[path = "private.rs"]
pub mod __private;
