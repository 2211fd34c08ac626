//! mech-core: the run-time half of `mech`.
//!
//! The pipeline of the `mechanism!` macro, visible in the module names:
//! [`dsl`] (parse) → [`model`] (plain data) → [`resolve`] and [`validate`] (the checks of
//! SPEC section 4: [`grubler`], [`assur`]) → [`plan`] (Assur groups, solve order) → emit
//! (in `mech-macros`). The generated code calls the kernels of [`kinematics`] and
//! [`kinetostatics`]; the run-time generic solver reuses the same model and validation.

pub mod assur;
pub mod dsl;
pub mod dynamics;
pub mod error;
pub mod flywheel;
pub mod generic;
pub mod geometry;
pub mod grubler;
pub mod instance;
pub mod kinematics;
pub mod kinetostatics;
pub mod model;
pub mod ode;
pub mod pebble;
pub mod resolve;
pub mod traits;
pub mod validate;
pub mod zhukovski;

pub use error::MechError;
pub use nalgebra::Vector2;
