//! The plan: each joint's geometry at the drawing, and the decomposition into Assur groups
//! in solving order, each with its kernel.

pub mod assur;
pub mod geometry;
pub mod ratios;
pub mod rotation;
