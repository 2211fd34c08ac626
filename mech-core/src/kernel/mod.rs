//! The kinematic core: a link's frame and its points' motion, the joints' constraint equations,
//! the closed-form and Newton solutions of each group kind, and the wrenches of d'Alembert.
//! Everything the generated code and the run-time `Mechanism` call per configuration.

pub(crate) mod branches;
pub mod constraints;
pub mod dyad;
pub mod energy;
pub(crate) mod finite;
pub mod group;
pub mod kinematics;
pub mod kinetostatics;
pub mod lanes;
pub mod linalg;
pub mod link_state;
pub mod natural;
pub mod screw;
pub mod slotted;
pub mod triad;

/// The tolerance check of the tests (`within`, `MECH_MEASURE=1`: tests/README.md): the root
/// tests' own file, so that the unit tests measure exactly as they do. At the lowest layer so
/// that every layer's tests reach it: `use crate::kernel::measure::within;`.
#[cfg(test)]
#[path = "../../../tests/common/measure.rs"]
pub(crate) mod measure;
