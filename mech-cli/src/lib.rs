//! The `mech` command-line tool (`docs/cli.md`): a mechanism file (`*.mech`, the body of a
//! `mechanism!` invocation) checked, solved, swept, sized for a flywheel, simulated,
//! strength-checked, drawn, animated, reported and imported, a cam's profile exported, and
//! four-bars synthesised from paths, from a terminal.
//!
//! Each subcommand is a module; they share the reading of a file ([`source`]), numbers
//! with unit words ([`quantity`]), loads given as constants or tables ([`loads`]), the
//! columns of one configuration ([`columns`]) and the output formats ([`output`]). The
//! mechanics are mech-core's run-time [`mech_core::Mechanism`], the same plan and kernels
//! as the generated code.
#![deny(missing_docs)]
// Limits are tested as `!(x > limit)` on purpose: true for a NaN as well.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod balance;
pub mod cam;
pub mod check;
pub mod columns;
pub mod draw;
pub mod engine;
pub mod flywheel;
pub mod import;
pub mod limits;
pub mod loads;
pub mod motor;
pub mod optimize;
pub mod output;
pub mod pmks;
pub mod quantity;
pub mod regime;
pub mod report;
pub mod scene;
pub mod serve;
pub mod shaking;
pub mod simulate;
pub mod size;
pub mod solve;
pub mod source;
pub mod spatial;
pub mod strength;
pub mod svg;
pub mod synth;
pub mod synth_exact;

/// An error of the tool: the message for standard error, and the exit status.
#[derive(Debug)]
pub struct Failure {
    /// What went wrong, the numbers and the fix.
    pub message: String,
    /// 1 for a bad mechanism or an unsolvable configuration, 2 for bad arguments.
    pub status: u8,
}

impl Failure {
    /// A mechanism or solver error (status 1).
    pub fn mechanism(message: impl Into<String>) -> Self {
        Failure {
            message: message.into(),
            status: 1,
        }
    }
    /// A usage error (status 2).
    pub fn usage(message: impl Into<String>) -> Self {
        Failure {
            message: message.into(),
            status: 2,
        }
    }
}

impl From<mech_core::MechError> for Failure {
    fn from(e: mech_core::MechError) -> Self {
        Failure::mechanism(e.to_string())
    }
}

impl From<std::io::Error> for Failure {
    fn from(e: std::io::Error) -> Self {
        Failure::mechanism(format!("i/o: {e}"))
    }
}
