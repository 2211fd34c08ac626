//! The run-time mechanism: the same text loaded and solved at run time, its results and
//! their column names.

pub mod columns;
pub mod generic;
pub mod mechanism;
