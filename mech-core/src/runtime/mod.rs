//! The run-time mechanism: the same text loaded and solved at run time, with the generated
//! code's plan and kernels; its results and their column names.

mod batch;
pub mod columns;
#[macro_use]
mod instances;
mod dispatch;
mod forces;
pub mod mechanism;
mod newton;
mod one_loop;
pub mod results;
pub mod spatial_columns;
mod strength;
mod warm;

pub use mechanism::Mechanism;
pub use results::{Forces, JointReaction, LoadValue, Loads, Motion, Pose};
