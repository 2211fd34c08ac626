//! `mech import`: a mechanism from pyslvs's PMKS expression. (In progress.)

use crate::Failure;
use std::path::PathBuf;

/// `mech import FILE -o out.mech`.
#[derive(clap::Args, Debug)]
pub struct ImportArgs {
    /// The file with the PMKS expression (`-` = standard input).
    pub file: PathBuf,
    /// The `.mech` file to write (standard output when omitted).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
}

/// Run `mech import`.
pub fn run(_args: ImportArgs) -> Result<(), Failure> {
    Err(Failure::usage("`mech import` is not available in this build yet"))
}
