//! The solvers written once over a plan's kernels: the numbers of an instance, virtual power,
//! Zhukovski's reduction, friction, and the traits every mechanism implements.

pub mod batch;
pub mod friction;
pub mod instance;
pub mod params;
pub mod traits;
pub(crate) mod virtual_power;
pub mod zhukovski;
pub mod zhukovski_series;
