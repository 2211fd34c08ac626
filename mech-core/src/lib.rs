//! mech-core: the run-time half of `mech`.
//!
//! The pipeline of the `mechanism!` macro, visible in the module names:
//! [`dsl`] (parse, syn) → [`model`] (plain data) → [`resolve`] (names) and [`validate`]
//! (the checks of `docs/conventions.md#checks`, with [`grubler`] and [`pebble`]) →
//! [`assur::plan`] (Assur groups, solve order, each group's kernel) → emit (in `mech-macros`).
//!
//! One kinematic core, shared by the generated code, the run-time [`Mechanism`] and the
//! validation, each formula once, imports one way: [`link_state`] (a link's frame, its
//! points' motion) → [`constraints`] (the joints' equations, their scaled Jacobian) →
//! [`linalg`] → [`dyad`] (closed-form positions), [`natural`] (the RRR and RRP dyads'
//! rates and reactions in their natural coordinates), [`screw`] (the other closed-form
//! groups' rates and reactions by joint screws), [`group`] (Newton and LU for the rest) →
//! [`kinematics`]
//! (one entry point per group). The generated code is a sequence of calls into those and
//! into [`kinetostatics`], [`virtual_power`], [`zhukovski`], [`energy`], [`elements`]
//! (springs and dampers), [`branches`] and [`friction`], with the numbers of [`instance`] checked against the declaration by
//! [`params`]. Every generated struct and every run-time [`Mechanism`] implements the
//! [`traits`] that the algorithms written once here take: [`dynamics`] and [`ode`] (the
//! direct problem), [`flywheel`] (Wittenbauer), [`friction`], [`equivalent_mass`]. The
//! dense whole-system solver [`generic`] reads the same text and stays as an independent
//! cross-check.

// Limits are tested as `!(x < limit)` on purpose: true for a NaN as well, so a NaN is
// refused wherever an out-of-range value is.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod checks;
pub mod dynamics;
pub mod elements;
pub mod error;
pub mod front;
pub mod kernel;
pub mod model;
pub mod plan;
pub mod runtime;
pub mod solvers;

// Transitional flat paths (removed once the dependents use the folders).
pub use checks::{grubler, magnitudes, pebble, validate};
pub use dynamics::{equivalent_mass, flywheel, ode};
pub use elements::{cam, gears, rolling};
pub use front::{construction, dsl, expr, report, resolve};
pub use kernel::{
    branches, constraints, dyad, energy, group, kinematics, kinetostatics, linalg, link_state,
    natural, screw,
};
pub use model::units;
pub use plan::{assur, geometry};
pub use runtime::{columns, mechanism};
pub use solvers::{friction, instance, params, traits, virtual_power, zhukovski};

pub use error::MechError;
pub use nalgebra::Vector2;
pub use runtime::mechanism::Mechanism;

#[doc(hidden)]
#[path = "private.rs"]
pub mod __private;
