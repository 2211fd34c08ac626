//! Dynamics written once over the traits: the direct problem (energy method, Lagrange),
//! the integrators, the flywheel, equivalent masses, motors and the regimes they drive.

pub mod equivalent_mass;
pub mod flywheel;
pub mod motor;
mod motor_parse;
pub mod ode;
mod one_dof;
pub mod regime;

pub use one_dof::*;
