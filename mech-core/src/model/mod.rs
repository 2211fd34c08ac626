//! The plain data of a mechanism: its units, links, points, joints, inputs, loads.

mod chain;
pub mod units;

pub use chain::*;
