//! Spatial mechanisms at run time (SPEC 3i, issue 33), from the `space` text to the solvers.
//!
//! `SpatialMechanism::from_dsl(text)` reads the text form, checks it and answers the same
//! solvers as the planar run-time mechanism: `pose`, `kinematics`, `kinetostatics`,
//! `driver_action`, `reduced`, `reduced_moment`, `acceleration`. The formulation is in
//! `docs/spatial.md`. A mechanism that is one RSSR, RSSP, RSRC or spherical four-bar takes
//! its positions from that group's closed form (`closed`), the others by Newton.

pub mod closed;
pub mod constraints;
pub mod dsl;
pub mod frame;
mod friction;
pub mod kinematics;
pub mod kinetostatics;
pub mod kutzbach;
mod machine;
pub mod mechanism;
pub mod model;
mod params;
mod pebble;
mod rank;
mod resolve;
pub mod results;
pub mod solver;
mod virtual_power;
mod zhukovski;

pub use kinematics::{BodyMotion, SpatialMotion};
pub use kinetostatics::{ForcesOut, Reaction, SpatialForces, SpatialLoads};
pub use mechanism::SpatialMechanism;
pub use model::{Body, Finding, Joint, JointKind, Load, LoadKind, Site, SpatialModel};
pub use results::LinkMotion;
pub use solver::Solver;
