//! Machine elements and their pair kernels: cams (motion law, profile, the cam pair),
//! gears, rolling contacts, springs and dampers.

pub mod cam;
pub mod gears;
pub mod rolling;
pub mod springs;

pub use springs::*;
