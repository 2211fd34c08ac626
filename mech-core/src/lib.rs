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

pub mod assur;
pub mod branches;
pub mod cam;
pub mod columns;
pub mod constraints;
pub mod construction;
pub mod dsl;
pub mod dyad;
pub mod dynamics;
pub mod elements;
pub mod energy;
pub mod equivalent_mass;
pub mod error;
pub mod expr;
pub mod flywheel;
pub mod friction;
pub mod gears;
pub mod generic;
pub mod geometry;
pub mod group;
pub mod grubler;
pub mod instance;
pub mod kinematics;
pub mod kinetostatics;
pub mod linalg;
pub mod link_state;
pub mod magnitudes;
pub mod mechanism;
pub mod model;
pub mod natural;
pub mod ode;
pub mod params;
pub mod pebble;
pub mod report;
pub mod resolve;
pub mod rolling;
pub mod screw;
pub mod traits;
pub mod units;
pub mod validate;
pub mod virtual_power;
pub mod zhukovski;

pub use error::MechError;
pub use mechanism::Mechanism;
pub use nalgebra::Vector2;
