//! The plain data of a mechanism: its units, links, points, joints, inputs, loads, and the
//! shapes and materials links may be declared by.

mod chain;
pub mod shape;
pub mod units;

pub use chain::*;
