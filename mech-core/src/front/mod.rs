//! The front end: DSL text or tokens → a description → a resolved [`crate::model::Model`]
//! (names, units, constant expressions, constructed points), and the rendering of diagnostics.

pub(crate) mod construction;
pub mod dsl;
pub mod expr;
pub(crate) mod report;
pub mod resolve;
