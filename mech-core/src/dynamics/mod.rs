//! Dynamics written once over the traits: the direct problem (energy method, Lagrange),
//! the integrators, the flywheel, equivalent masses.

pub mod equivalent_mass;
pub mod flywheel;
pub mod ode;
mod one_dof;

pub use one_dof::*;
