//! Dimensional synthesis of four-bars (and Stephenson III six-bars for paths): from targets (a path, pairs of input and output
//! angles, poses of the coupler) to a [`four_bar::FourBar`] that writes itself as a
//! mechanism file, and the [`error`] a path is met with (SPEC §3f).

pub mod burmester;
pub mod error;
pub mod four_bar;
pub mod freudenstein;
pub mod optimiser;
pub mod path;
pub mod six_bar;
pub mod three_point;

pub use four_bar::{FourBar, FourBarPose};
pub use six_bar::{SixBar, SixBarPose};
