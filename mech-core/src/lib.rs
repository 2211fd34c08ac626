//! mech-core: the run-time half of `mech`.
//!
//! The pipeline of the `mechanism!` macro, visible in the module names:
//! [`dsl`] (parse, syn) → [`model`] (plain data) → [`resolve`] (names) and [`validate`]
//! (the checks of `docs/conventions.md#checks`, with [`grubler`] and [`pebble`]) → [`assur::plan`]
//! (Assur groups, solve order) → emit (in `mech-macros`). The generated code is a
//! sequence of calls into the kernels of [`kinematics`], [`assur`] (closed-form dyads),
//! [`kinetostatics`], [`virtual_power`], [`zhukovski`], [`energy`], [`branches`] and
//! [`friction`], with the numbers of [`instance`] checked against the declaration by
//! [`params`]; every generated struct implements the [`traits`] that the algorithms
//! written once here take:
//! [`dynamics`] and [`ode`] (the direct problem), [`flywheel`] (Wittenbauer). The
//! run-time [`generic`] solver reads the same DSL text and reuses the same model,
//! validation and kernels, with one dense system instead of group by group.

pub mod assur;
pub mod branches;
pub mod constraints;
pub mod dsl;
pub mod dyad;
pub mod dynamics;
pub mod energy;
pub mod equivalent_mass;
pub mod error;
pub mod flywheel;
pub mod friction;
pub mod generic;
pub mod geometry;
pub mod group;
pub mod grubler;
pub mod instance;
pub mod kinematics;
pub mod kinetostatics;
pub mod linalg;
pub mod mechanism;
pub mod link_state;
pub mod model;
pub mod ode;
pub mod params;
pub mod pebble;
pub mod resolve;
pub mod screw;
pub mod traits;
pub mod validate;
pub mod virtual_power;
pub mod zhukovski;

pub use error::MechError;
pub use mechanism::Mechanism;
pub use nalgebra::Vector2;
